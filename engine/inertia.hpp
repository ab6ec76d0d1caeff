// Inertia tensors: closed forms of the primitive shapes, the tensor algebra that moves and
// combines them (parallel axis, rotation, composite bodies, principal axes) and the validator
// that says when a 3x3 matrix cannot be the inertia tensor of any body.
//
// Units: kg, m, kg·m². Every shape tensor is about the shape's centre of mass, in the shape's
// own frame, whose axes are the principal axes (so the tensor is diagonal). The tensor is
//   I = ∫ ((r·r)E − r⊗r) dm
// (/work/shared/seeds/000_*, "Inertia": diagonal entries ∫(y²+z²)dm ..., products −∫xy dm).
//
// Bad values (mass or length not finite or not > 0) throw std::invalid_argument with a message
// naming the parameter: "radius must be > 0, got -1".
#pragma once

#include <string>
#include <vector>

#include "engine/math.hpp"

namespace rigidlab {

// ---- primitive shapes (about the COM, principal axes along x, y, z) ------------------------

// Solid ball of radius r (m): I = (2/5) m r² E.
Mat3 inertia_solid_sphere(double mass, double radius);
// Thin spherical shell of radius r (m), all mass on the surface: I = (2/3) m r² E.
Mat3 inertia_hollow_sphere(double mass, double radius);
// Solid box with edge lengths size = (w, h, d) (m) along x, y, z: Ixx = m(h² + d²)/12, ...
Mat3 inertia_solid_box(double mass, const Vec3& size);
// Solid cylinder of radius r and length h (m), axis z: Ixx = Iyy = m(3r² + h²)/12, Izz = m r²/2.
Mat3 inertia_solid_cylinder(double mass, double radius, double height);
// Thin-walled tube of radius r and length h (m), axis z, open ends (the lateral surface only,
// no end caps): Ixx = Iyy = m(6r² + h²)/12, Izz = m r².
Mat3 inertia_hollow_cylinder(double mass, double radius, double height);
// Solid ellipsoid with semi-axes a, b, c (m) along x, y, z: Ixx = m(b² + c²)/5, ...
Mat3 inertia_solid_ellipsoid(double mass, double a, double b, double c);
// Capsule: a solid cylinder of radius r and length h (m) along z (h excludes the caps, so the
// total length is h + 2r) closed by two solid hemispheres of radius r; uniform density, so the
// mass splits between cylinder and caps by volume. h = 0 is allowed (a sphere).
Mat3 inertia_capsule(double mass, double radius, double height);
// Solid right circular cone, base radius r and height h (m), axis z, apex toward +z. About the
// COM, which lies on the axis h/4 above the base: base at z = −h/4, apex at z = +3h/4.
// Ixx = Iyy = (3/80) m (4r² + h²), Izz = (3/10) m r².
Mat3 inertia_solid_cone(double mass, double radius, double height);

// ---- particles and tensor algebra ----------------------------------------------------------

// Tensor of a particle of mass m (kg) at offset r (m) from the reference point:
// m((r·r)E − r⊗r). Zero mass gives the zero tensor; negative or non-finite mass throws.
Mat3 inertia_point(double mass, const Vec3& offset);

// Mass, centre of mass and inertia tensor about the centre of mass.
struct MassProperties {
  double mass = 0.0;          // kg
  Vec3 com = Vec3::Zero();    // m
  Mat3 inertia = Mat3::Zero();  // kg·m², about com
};

struct PointMass {
  double mass;  // kg, > 0
  Vec3 position;  // m
};
// A rigid set of particles: total mass, COM = Σ mᵢ pᵢ / Σ mᵢ, and Σ point(mᵢ, pᵢ − COM).
// Throws for an empty list or a mass that is not finite and > 0.
MassProperties inertia_points(const std::vector<PointMass>& points);

// Parallel axis theorem, tensor form (seed 000_*, "Parallel axis theorem"): the tensor about a
// point P, given the tensor about the COM and d = COM − P (m):  I_P = I_com + m((d·d)E − d⊗d).
Mat3 parallel_axis(const Mat3& inertia_com, double mass, const Vec3& d);

// The tensor in a frame rotated by R: R I Rᵀ (seed 000_*, "Reference frame"). R must be a
// rotation (see rotation_problem); not checked here because bodies call this every step.
Mat3 rotate_inertia(const Mat3& inertia, const Mat3& rotation);
// The same for a quaternion, normalised first (throws for a zero or non-finite quaternion).
Mat3 rotate_inertia(const Mat3& inertia, const Quat& rotation);

// Scalar moment about the axis through the reference point along n: n̂·I·n̂ (seed 003_*, "List
// of 3D inertia tensors"). n need not be unit: it is normalised; a zero or non-finite n throws.
double about_axis(const Mat3& inertia, const Vec3& axis);

// Principal moments (ascending) and principal axes (columns, right-handed, unit), so that
// I = axes · diag(values) · axesᵀ. Uses symmetric_eigen; I is symmetrised first.
SymmetricEigen principal_inertia(const Mat3& inertia);

// A body made of parts (seed 000_*, "Complex objects"): each part's mass, COM and tensor about
// its own COM, expressed in the axes of the composite frame. Returns the total mass, the
// composite COM and the tensor about it: Σ parallel_axis(Iᵢ, mᵢ, comᵢ − COM).
// Throws for an empty list or a part mass that is not finite and > 0.
MassProperties composite_inertia(const std::vector<MassProperties>& parts);

// ---- validation ----------------------------------------------------------------------------

// What a physical inertia tensor must satisfy. Every real body (about any point) has a
// symmetric, positive semidefinite tensor whose principal moments A, B, C obey the triangle
// inequality A + B >= C (each moment is a sum of two of the three second moments ∫x², ∫y², ∫z²).
// `body` additionally requires every principal moment > 0 with a finite inverse, as a body must
// have an invertible tensor; `idealized` also admits the zero moments of a particle or an
// infinitely thin rod. Entries so large that the principal moments overflow are refused too.
enum class InertiaRules { body, idealized };

// Empty when I could be an inertia tensor, otherwise one sentence naming the rule it breaks and
// by how much, e.g. "principal moments 1, 1, 3 violate A + B >= C (1 + 1 < 3 by 1)".
// Tolerances, relative to the largest entry or moment: asymmetry 1e-9, triangle inequality
// 1e-9 (so planar and rod-like bodies at equality pass), zero moment 1e-12.
std::string inertia_tensor_problem(const Mat3& inertia, InertiaRules rules = InertiaRules::body);

// Empty when R is a rotation matrix (RᵀR = E and det R = +1, each within 1e-9), else why not.
std::string rotation_problem(const Mat3& rotation);

}  // namespace rigidlab
