// Narrow phase: the contact points between two shapes at given poses, or between a shape and
// a static plane. Free functions on (shape, pose) pairs; each returns a Manifold, a value with
// room for four points (no heap allocation).
//
// Conventions (world frame, metres):
// - The normal is a unit vector from shape a to shape b: pushing b along +n and a along −n
//   separates them. For a plane, a is the plane: n is the plane's normal, out of the solid.
// - Each point lies midway between the two surfaces: with p_a the deepest point of a inside b
//   and p_b the deepest point of b inside a, point = (p_a + p_b)/2 and depth = (p_a − p_b)·n.
//   The witness points are therefore point ± n·depth/2 (p_a = point + n·depth/2).
// - depth > 0 when the shapes overlap. With margin > 0, points whose gap −depth is at most
//   `margin` are reported too (speculative contacts, E. Catto, "Physics for Game
//   Programmers: Continuous Collision", GDC 2013; Box2D v3's speculative distance); with the
//   default margin 0 every reported depth is ≥ 0.
// - `feature` names the pair of features that touch (a vertex, a clipped edge, an edge pair)
//   and stays the same from step to step while they keep touching: the solver matches
//   contacts of consecutive steps by it to warm-start them.
//
// Sources: /work/shared/seeds/001_* "Collisions" (a sphere on the floor: contact point
// x − n r and depth; "with boxes they can have as much as four simultaneous points": an edge
// gives two points, a face four), Appendix D (the separation constraint n·(x_b − x_a) ≥ 0
// along a normal from a to b). Box–box is the separating-axis test over the 15 axes of two
// boxes (Gottschalk, Lin, Manocha, "OBBTree", SIGGRAPH 1996; Ericson, "Real-Time Collision
// Detection" 4.4.1) with the contact built by clipping the incident face against the side
// planes of the reference face (Sutherland–Hodgman; D. Gregorius, "Robust Contact Creation
// for Physics Simulations", GDC 2015), reduced to four points; an edge–edge contact is one
// point, the midpoint of the closest points of the two edges.
#pragma once

#include <array>
#include <cstdint>

#include "engine/body.hpp"
#include "engine/plane.hpp"

namespace rigidlab {

// Where a shape is: its centre (the body's COM) and its rotation (body -> world).
struct Pose {
  Vec3 position = Vec3::Zero();
  Mat3 rotation = Mat3::Identity();
};
inline Pose pose_of(const Body& b) { return {b.position, b.orientation.toRotationMatrix()}; }

struct ContactPoint {
  Vec3 point = Vec3::Zero();  // m, world, midway between the surfaces
  double depth = 0.0;         // m, penetration along the normal (< 0: a gap, speculative)
  std::uint32_t feature = 0;  // the touching features, stable while they touch
};

inline constexpr int max_manifold_points = 4;

struct Manifold {
  Vec3 normal = Vec3::UnitY();  // unit, from a to b
  int count = 0;
  std::array<ContactPoint, max_manifold_points> points;
};

// The points of one face contact as a manifold of at most four, `normal` its normal: `points`
// (count <= max_face_points) are the vertices of the clipped face in the order of its
// boundary. Up to four are kept as they are; of more, the vertices where the boundary turns
// by less than 1e-6 rad are dropped (they lie between their neighbours), then four are kept
// (Gregorius, GDC 2015): the deepest, the farthest from it, the largest triangle with those
// two, the largest triangle outside it (engine/narrow_phase.cpp). Reorders `points`.
inline constexpr int max_face_points = 8;  // a quad clipped by four planes gains at most four
Manifold reduce_face_points(ContactPoint* points, int count, const Vec3& normal);

// Radius of the sphere about the centre that holds the shape (m); 0 for no shape.
double bounding_radius(const Shape& shape);

// Sphere of `radius` centred at `center` against a plane (a = the plane). One point.
Manifold collide_sphere_plane(const Vec3& center, double radius, const Plane& plane,
                              double margin = 0.0);
// Box against a plane (a = the plane): the (up to four) deepest corners within the margin.
Manifold collide_box_plane(const Pose& box, const Vec3& half_extents, const Plane& plane,
                           double margin = 0.0);
// Two spheres. When the centres coincide the normal is +y (any direction is as good).
Manifold collide_sphere_sphere(const Vec3& center_a, double radius_a, const Vec3& center_b,
                               double radius_b, double margin = 0.0);
// Box a against sphere b: the closest point of the box to the centre, or, with the centre
// inside the box, the face nearest to it. One point.
Manifold collide_box_sphere(const Pose& box, const Vec3& half_extents, const Vec3& center,
                            double radius, double margin = 0.0);
// Two boxes: separating axes, then face clipping (up to four points) or one edge–edge point.
Manifold collide_box_box(const Pose& a, const Vec3& half_a, const Pose& b, const Vec3& half_b,
                         double margin = 0.0);

// Dispatch on the shape kinds (a shape of kind none touches nothing: empty manifold).
Manifold collide_shapes(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b,
                        double margin = 0.0);
Manifold collide_shape_plane(const Shape& shape, const Pose& pose, const Plane& plane,
                             double margin = 0.0);

// A lower bound on the distance between two shapes (m; ≤ 0 when they touch or overlap; +inf
// when a shape is none): exact when a sphere or a plane is involved, and for two boxes the
// largest separation along the 15 axes of the separating-axis test (the projections onto any
// axis are never farther apart than the shapes). What conservative advancement
// (engine/time_of_impact.hpp) needs: it never steps past a contact.
double separation(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b);
double separation(const Shape& shape, const Pose& pose, const Plane& plane);

}  // namespace rigidlab
