// engine/narrow_phase.hpp against geometry worked out by hand: depths, normals and points of
// spheres, planes and boxes in known configurations (rotated boxes included), the witness
// points on both surfaces, the margin of speculative contacts, and features that stay the
// same while the same features touch.
#include "engine/narrow_phase.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace rigidlab {
namespace {

const double sqrt2 = std::sqrt(2.0);

Pose pose(const Vec3& position, const Quat& q = Quat::Identity()) {
  return {position, q.toRotationMatrix()};
}

Quat about(const Vec3& axis, double angle) { return quat_from_axis_angle(axis, angle); }

void expect_vec(const Vec3& got, const Vec3& want, double tol = 1e-12) {
  EXPECT_NEAR((got - want).norm(), 0.0, tol)
      << "got (" << got.transpose() << "), want (" << want.transpose() << ")";
}

// The manifold holds a point at `want` (in any order); returns its index.
int find_point(const Manifold& m, const Vec3& want, double tol = 1e-9) {
  for (int k = 0; k < m.count; ++k)
    if ((m.points[k].point - want).norm() < tol) return k;
  ADD_FAILURE() << "no point at (" << want.transpose() << ")";
  return 0;
}

// Signed distance from x to the surface of a box (negative inside), by its definition.
double box_distance(const Pose& box, const Vec3& half, const Vec3& x) {
  const Vec3 local = box.rotation.transpose() * (x - box.position);
  const Vec3 q = local.cwiseAbs() - half;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

// ---- spheres and planes ----------------------------------------------------------------------

TEST(SpherePlane, OverlapDepthNormalMidpoint) {
  // normal (0, 2, 0), offset 2: the half-space y >= 1. A ball of radius 1 at height 1.5 sinks
  // 0.5 into it; its lowest point is at y = 0.5, the plane at y = 1, the midpoint at 0.75.
  const Plane floor = make_plane(Vec3(0, 2, 0), 2.0);
  const Manifold m = collide_sphere_plane(Vec3(3, 1.5, -2), 1.0, floor);
  ASSERT_EQ(m.count, 1);
  expect_vec(m.normal, Vec3(0, 1, 0));
  EXPECT_NEAR(m.points[0].depth, 0.5, 1e-15);
  expect_vec(m.points[0].point, Vec3(3, 0.75, -2));
}

TEST(SpherePlane, TiltedPlaneAndMargin) {
  // The plane x + y >= 0 and a ball of radius 2 at (1, 1, 0): distance √2, depth 2 − √2;
  // the deepest point of the ball is (1, 1, 0) − 2 n, the midpoint half the depth above it.
  const Plane slope = make_plane(Vec3(1, 1, 0), 0.0);
  const Vec3 n = Vec3(1, 1, 0) / sqrt2;
  Manifold m = collide_sphere_plane(Vec3(1, 1, 0), 2.0, slope);
  ASSERT_EQ(m.count, 1);
  expect_vec(m.normal, n);
  EXPECT_NEAR(m.points[0].depth, 2.0 - sqrt2, 1e-14);
  expect_vec(m.points[0].point, Vec3(1, 1, 0) - (2.0 - 0.5 * (2.0 - sqrt2)) * n);
  // 0.1 above the plane: nothing without a margin, a gap of 0.1 with one.
  EXPECT_EQ(collide_sphere_plane(Vec3(0, 1.1, 0), 1.0, make_plane(Vec3(0, 1, 0), 0)).count, 0);
  m = collide_sphere_plane(Vec3(0, 1.1, 0), 1.0, make_plane(Vec3(0, 1, 0), 0), 0.2);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].depth, -0.1, 1e-15);
  expect_vec(m.points[0].point, Vec3(0, 0.05, 0), 1e-15);
}

TEST(SphereSphere, DepthNormalPointAndCoincidentCentres) {
  Manifold m = collide_sphere_sphere(Vec3(0, 0, 0), 1.0, Vec3(1.5, 0, 0), 1.0);
  ASSERT_EQ(m.count, 1);
  expect_vec(m.normal, Vec3(1, 0, 0));
  EXPECT_NEAR(m.points[0].depth, 0.5, 1e-15);
  expect_vec(m.points[0].point, Vec3(0.75, 0, 0));
  // Radii 1 and 2, centres 2.4 apart along (3, 4, 0)/5: depth 0.6, a's surface at 1, b's at
  // 2.4 − 2 = 0.4 along the line, midpoint at 0.7.
  const Vec3 u(0.6, 0.8, 0.0);
  m = collide_sphere_sphere(Vec3(1, 1, 1), 1.0, Vec3(1, 1, 1) + 2.4 * u, 2.0);
  ASSERT_EQ(m.count, 1);
  expect_vec(m.normal, u, 1e-15);
  EXPECT_NEAR(m.points[0].depth, 0.6, 1e-14);
  expect_vec(m.points[0].point, Vec3(1, 1, 1) + 0.7 * u, 1e-14);
  m = collide_sphere_sphere(Vec3(2, 0, 0), 1.0, Vec3(2, 0, 0), 0.5);
  ASSERT_EQ(m.count, 1);
  expect_vec(m.normal, Vec3(0, 1, 0));
  EXPECT_EQ(m.points[0].depth, 1.5);
  EXPECT_EQ(collide_sphere_sphere(Vec3(0, 0, 0), 1.0, Vec3(0, 0, 2.01), 1.0).count, 0);
  EXPECT_EQ(collide_sphere_sphere(Vec3(0, 0, 0), 1.0, Vec3(0, 0, 2.01), 1.0, 0.02).count, 1);
}

// ---- boxes and planes -------------------------------------------------------------------------

TEST(BoxPlane, FlatBoxGivesItsFourBottomCorners) {
  // Half extents (1, 0.5, 2) with the centre at y = 0.4: the bottom face is at y = −0.1.
  const Manifold m =
      collide_box_plane(pose(Vec3(0, 0.4, 0)), Vec3(1, 0.5, 2), make_plane(Vec3(0, 1, 0), 0));
  ASSERT_EQ(m.count, 4);
  expect_vec(m.normal, Vec3(0, 1, 0));
  for (double x : {-1.0, 1.0})
    for (double z : {-2.0, 2.0}) {
      const int k = find_point(m, Vec3(x, -0.05, z));
      EXPECT_NEAR(m.points[k].depth, 0.1, 1e-15);
    }
}

TEST(BoxPlane, BoxOnAnEdgeGivesTwoPoints) {
  // A unit-half cube turned 45° about z rests on an edge along z, √2 below its centre.
  const Manifold m =
      collide_box_plane(pose(Vec3(0, sqrt2 - 0.1, 0), about(Vec3(0, 0, 1), M_PI / 4)),
                        Vec3(1, 1, 1), make_plane(Vec3(0, 1, 0), 0));
  ASSERT_EQ(m.count, 2);
  for (double z : {-1.0, 1.0}) {
    const int k = find_point(m, Vec3(0, -0.05, z));
    EXPECT_NEAR(m.points[k].depth, 0.1, 1e-14);
  }
}

TEST(BoxPlane, CornerDownAndDeepBoxKeepsTheDeepestFour) {
  // Corner down: the cube turned so its diagonal (1, 1, 1) points up; the lowest corner is
  // √3 below the centre.
  const Quat corner_up = Quat::FromTwoVectors(Vec3(1, 1, 1).normalized(), Vec3(0, 1, 0));
  Manifold m = collide_box_plane(pose(Vec3(0, std::sqrt(3.0) - 0.2, 0), corner_up), Vec3(1, 1, 1),
                                 make_plane(Vec3(0, 1, 0), 0));
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].depth, 0.2, 1e-12);
  expect_vec(m.points[0].point, Vec3(0, -0.1, 0), 1e-12);
  // Sunk below the plane entirely: eight corners under it, the four lowest are kept.
  m = collide_box_plane(pose(Vec3(0, -3, 0)), Vec3(1, 1, 1), make_plane(Vec3(0, 1, 0), 0));
  ASSERT_EQ(m.count, 4);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(m.points[k].depth, 4.0, 1e-15);
}

// ---- boxes and spheres ------------------------------------------------------------------------

TEST(BoxSphere, FaceEdgeCornerAndInside) {
  const Vec3 half(1, 1, 1);
  // Over the +y face: depth 0.2, box surface at y = 1, ball's lowest point at 0.8.
  Manifold m = collide_box_sphere(pose(Vec3::Zero()), half, Vec3(0.3, 1.8, -0.2), 1.0);
  ASSERT_EQ(m.count, 1);
  expect_vec(m.normal, Vec3(0, 1, 0));
  EXPECT_NEAR(m.points[0].depth, 0.2, 1e-15);
  expect_vec(m.points[0].point, Vec3(0.3, 0.9, -0.2), 1e-15);
  // Off the corner (1, 1, 1): distance √0.75 along (1, 1, 1)/√3.
  m = collide_box_sphere(pose(Vec3::Zero()), half, Vec3(1.5, 1.5, 1.5), 1.0);
  ASSERT_EQ(m.count, 1);
  expect_vec(m.normal, Vec3(1, 1, 1).normalized(), 1e-15);
  EXPECT_NEAR(m.points[0].depth, 1.0 - std::sqrt(0.75), 1e-15);
  // Centre inside, 0.1 under the +y face: out through it, depth 0.1 + r.
  m = collide_box_sphere(pose(Vec3::Zero()), half, Vec3(0.2, 0.9, 0), 0.5);
  ASSERT_EQ(m.count, 1);
  expect_vec(m.normal, Vec3(0, 1, 0));
  EXPECT_NEAR(m.points[0].depth, 0.6, 1e-15);
  expect_vec(m.points[0].point, Vec3(0.2, 0.7, 0), 1e-15);
  // Box turned 45° about z: its top is an edge at y = √2.
  m = collide_box_sphere(pose(Vec3(5, 0, 0), about(Vec3(0, 0, 1), M_PI / 4)), half,
                         Vec3(5, sqrt2 + 0.8, 0.5), 1.0);
  ASSERT_EQ(m.count, 1);
  expect_vec(m.normal, Vec3(0, 1, 0), 1e-15);
  EXPECT_NEAR(m.points[0].depth, 0.2, 1e-14);
  expect_vec(m.points[0].point, Vec3(5, sqrt2 - 0.1, 0.5), 1e-14);
}

TEST(BoxSphere, ShapeOrderFlipsOnlyTheNormal) {
  Shape box, ball;
  box.kind = ShapeKind::box, box.half_extents = Vec3(1, 2, 3);
  ball.kind = ShapeKind::sphere, ball.radius = 0.5;
  const Pose box_pose = pose(Vec3(0, 0, 0), about(Vec3(1, 2, 3), 0.7));
  const Pose ball_pose = pose(box_pose.rotation * Vec3(0, 2.3, 0));
  const Manifold ab = collide_shapes(box, box_pose, ball, ball_pose);
  const Manifold ba = collide_shapes(ball, ball_pose, box, box_pose);
  ASSERT_EQ(ab.count, 1);
  ASSERT_EQ(ba.count, 1);
  expect_vec(ab.normal, box_pose.rotation.col(1), 1e-14);
  expect_vec(ba.normal, -ab.normal);
  expect_vec(ba.points[0].point, ab.points[0].point);
  EXPECT_NEAR(ab.points[0].depth, 0.2, 1e-14);
}

// ---- box against box ----------------------------------------------------------------------

TEST(BoxBox, SmallBoxOnBigBoxFaceToFace) {
  // B (half 0.5) sits 0.1 deep in the top face of A (half 1): four points, y = 0.95.
  const Manifold m = collide_box_box(pose(Vec3::Zero()), Vec3(1, 1, 1), pose(Vec3(0, 1.4, 0)),
                                     Vec3(0.5, 0.5, 0.5));
  ASSERT_EQ(m.count, 4);
  expect_vec(m.normal, Vec3(0, 1, 0));
  for (double x : {-0.5, 0.5})
    for (double z : {-0.5, 0.5})
      EXPECT_NEAR(m.points[find_point(m, Vec3(x, 0.95, z))].depth, 0.1, 1e-14);
}

TEST(BoxBox, IncidentFaceIsClippedToTheReferenceFace) {
  // B (half (1, 0.5, 1)) overhangs A's top face: its bottom spans x in [0.5, 2.5], A ends at
  // x = 1, so the clipped points are at x = 0.5 and x = 1.
  const Manifold m =
      collide_box_box(pose(Vec3::Zero()), Vec3(1, 1, 1), pose(Vec3(1.5, 1.4, 0)), Vec3(1, 0.5, 1));
  ASSERT_EQ(m.count, 4);
  expect_vec(m.normal, Vec3(0, 1, 0));
  for (double x : {0.5, 1.0})
    for (double z : {-1.0, 1.0})
      EXPECT_NEAR(m.points[find_point(m, Vec3(x, 0.95, z))].depth, 0.1, 1e-14);
}

TEST(BoxBox, ReferenceFaceOnBFlipsTheNormalBackToAtoB) {
  // The small box is a, the big one b, below it: b's top face is the reference, the normal
  // still points from a to b (down).
  const Manifold m = collide_box_box(pose(Vec3(0, 1.4, 0)), Vec3(0.5, 0.5, 0.5), pose(Vec3::Zero()),
                                     Vec3(1, 1, 1));
  ASSERT_EQ(m.count, 4);
  expect_vec(m.normal, Vec3(0, -1, 0));
  for (double x : {-0.5, 0.5})
    for (double z : {-0.5, 0.5})
      EXPECT_NEAR(m.points[find_point(m, Vec3(x, 0.95, z))].depth, 0.1, 1e-14);
}

// Twice the area of the polygon the points of m span in the plane normal to y (shoelace after
// sorting by angle about their centroid).
double twice_area_about_y(const Manifold& m) {
  std::vector<Vec3> quad;
  Vec3 centroid = Vec3::Zero();
  for (int k = 0; k < m.count; ++k) centroid += m.points[k].point / m.count;
  for (int k = 0; k < m.count; ++k) quad.push_back(m.points[k].point - centroid);
  std::sort(quad.begin(), quad.end(), [](const Vec3& p, const Vec3& q) {
    return std::atan2(p.z(), p.x()) < std::atan2(q.z(), q.x());
  });
  double area = 0;
  for (std::size_t k = 0; k < quad.size(); ++k) {
    const Vec3& p = quad[k];
    const Vec3& q = quad[(k + 1) % quad.size()];
    area += p.z() * q.x() - p.x() * q.z();
  }
  return std::abs(area);
}

TEST(BoxBox, TwistedSquaresOverlapInTheExactOctagon) {
  // B's bottom face (half 1) turned by θ about y over A's top face (|x|, |z| <= 1): the edges
  // of B are the lines p·u = ±1, p·w = ±1 with u = (cos θ, −sin θ), w = (sin θ, cos θ) in
  // (x, z). On A's side x = 1 they cross at z = (cos θ − 1)/sin θ = −tan(θ/2) and
  // z = (1 − sin θ)/cos θ = tan(π/4 − θ/2); the octagon is these two turned by multiples of
  // 90°, and its area is A's square less four corner triangles: 4 − 2 (1 − t₁)(1 − t₂). The
  // four points kept are vertices of it, all 0.1 deep, spanning more than half of it. (For
  // 0 < θ < π/2; at θ = π/4 it is the regular octagon with corners like (1, √2 − 1).)
  for (double theta : {0.3, M_PI / 4, 0.7, 1.2}) {
    const Manifold m =
        collide_box_box(pose(Vec3::Zero()), Vec3(1, 1, 1),
                        pose(Vec3(0, 1.4, 0), about(Vec3(0, 1, 0), theta)), Vec3(1, 0.5, 1));
    ASSERT_EQ(m.count, 4);
    const double t1 = -std::tan(theta / 2), t2 = std::tan(M_PI / 4 - theta / 2);
    std::vector<Vec3> octagon;
    for (const Vec3& v : {Vec3(1, 0.95, t1), Vec3(1, 0.95, t2)})
      for (int quarter = 0; quarter < 4; ++quarter)
        octagon.push_back(about(Vec3(0, 1, 0), quarter * M_PI / 2) * v);
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(m.points[k].depth, 0.1, 1e-14);
      const bool on_octagon = std::any_of(octagon.begin(), octagon.end(), [&](const Vec3& v) {
        return (v - m.points[k].point).norm() < 1e-12;
      });
      EXPECT_TRUE(on_octagon) << "theta " << theta << ": " << m.points[k].point.transpose();
    }
    const double octagon_area = 4.0 - 2.0 * (1.0 - std::abs(t1)) * (1.0 - t2);
    EXPECT_GT(twice_area_about_y(m) / 2, 0.5 * octagon_area) << "theta " << theta;
  }
}

// The octagon of two equal squares twisted by θ = 1e-8 (what rounding leaves between boxes
// stacked face on face): near each corner of A's face a vertex, and on each side a vertex
// where B's edge crosses it, turning the boundary by θ (see the test above, with
// t₁ = −tan(θ/2), t₂ = tan(π/4 − θ/2)); in boundary order.
std::vector<ContactPoint> twisted_octagon(double theta, const Vec3& deeper) {
  const double t1 = -std::tan(theta / 2), t2 = std::tan(M_PI / 4 - theta / 2);
  std::vector<ContactPoint> points;
  for (int quarter = 0; quarter < 4; ++quarter)
    for (const Vec3& v : {Vec3(1, 0, t1), Vec3(1, 0, t2)}) {
      const Vec3 p = about(Vec3(0, 1, 0), -quarter * M_PI / 2) * v;
      points.push_back({p, 0.1 + deeper.dot(p), static_cast<std::uint32_t>(points.size())});
    }
  return points;
}

TEST(ReduceFacePoints, NearlyStraightVerticesGiveWayToTheCorners) {
  // The depth slopes by 1e-3 towards x, slightly against z (by θ/2): the crossing on the side
  // x = 1, at z = −θ/2, is then the deepest vertex, by ~1e-11 m, over the corner (1, 1 − θ).
  // Kept from it, it took a corner's place (the column of 20 boxes toppled): the four kept
  // must be the corners (within θ), the full square (area 4).
  const double theta = 1e-8;
  std::vector<ContactPoint> octagon = twisted_octagon(theta, 1e-3 * Vec3(1, 0, -theta / 2));
  ASSERT_EQ(octagon.size(), 8u);
  const Manifold m = reduce_face_points(octagon.data(), 8, Vec3(0, 1, 0));
  ASSERT_EQ(m.count, 4);
  for (int k = 0; k < 4; ++k) {
    const Vec3& p = m.points[k].point;
    EXPECT_NEAR(std::abs(p.x()), 1.0, 2 * theta) << p.transpose();
    EXPECT_NEAR(std::abs(p.z()), 1.0, 2 * theta) << p.transpose();
  }
  EXPECT_NEAR(twice_area_about_y(m) / 2, 4.0, 1e-7);
}

// The largest area of a quad of four of the points (brute force over every four, each
// spanning its convex hull: the largest of its three cyclic orders), in the plane y = 0.
double largest_quad_area(const std::vector<ContactPoint>& p) {
  auto shoelace = [&](int a, int b, int c, int d) {
    const int order[4] = {a, b, c, d};
    double twice = 0.0;
    for (int k = 0; k < 4; ++k) {
      const Vec3& u = p[order[k]].point;
      const Vec3& v = p[order[(k + 1) % 4]].point;
      twice += u.z() * v.x() - u.x() * v.z();
    }
    return std::abs(twice) / 2;
  };
  const int n = static_cast<int>(p.size());
  double best = 0.0;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      for (int c = b + 1; c < n; ++c)
        for (int d = c + 1; d < n; ++d)
          best = std::max({best, shoelace(a, b, c, d), shoelace(a, c, b, d), shoelace(a, b, d, c)});
  return best;
}

TEST(ReduceFacePoints, AFlatTwistedOctagonKeepsItsLargestQuad) {
  // θ = 0.1 rad: the four mid-edge vertices turn the boundary by θ, no longer straight. With
  // all points within a thousandth of the patch's size as deep, whichever is deepest (here
  // each mid-edge vertex in turn, by 1e-7 m), the quad kept is the largest of the eight points
  // (the corners: 2 (1 + t₂²), t₂ = tan(π/4 − θ/2)), not three corners and that vertex.
  const double theta = 0.1, t2 = std::tan(M_PI / 4 - theta / 2);
  for (int deepest = 0; deepest < 8; deepest += 2) {
    std::vector<ContactPoint> octagon = twisted_octagon(theta, Vec3::Zero());
    octagon[deepest].depth += 1e-7;
    const double largest = largest_quad_area(octagon);
    EXPECT_NEAR(largest, 2 * (1 + t2 * t2), 1e-12);
    const Manifold m = reduce_face_points(octagon.data(), 8, Vec3(0, 1, 0));
    ASSERT_EQ(m.count, 4);
    EXPECT_NEAR(twice_area_about_y(m) / 2, largest, 1e-12) << "deepest " << deepest;
  }
  // A point deeper than that (by a hundredth of the size) is kept: the penetration comes first.
  std::vector<ContactPoint> octagon = twisted_octagon(theta, Vec3::Zero());
  octagon[2].depth += 0.01;
  const Manifold m = reduce_face_points(octagon.data(), 8, Vec3(0, 1, 0));
  ASSERT_EQ(m.count, 4);
  EXPECT_EQ(m.points[0].feature, 2u);
}

TEST(ReduceFacePoints, KeepsFourCornersWhenTheFarthestIsANeighbour) {
  // A flat pentagon, deepest at (0, 0): the farthest point from it, (10, 0), is its
  // neighbour, so no point lies beyond their edge; the fourth comes from beyond the other
  // edges of the triangle. The largest quads of the five points (brute force) have area 6.2.
  const double xz[5][2] = {{0, 0}, {10, 0}, {9.9, 0.5}, {5, 1}, {0.1, 0.5}};
  ContactPoint points[5];
  for (int k = 0; k < 5; ++k)
    points[k] = {Vec3(xz[k][0], 0, xz[k][1]), k == 0 ? 0.2 : 0.1, static_cast<std::uint32_t>(k)};
  const Manifold m = reduce_face_points(points, 5, Vec3(0, 1, 0));
  ASSERT_EQ(m.count, 4);
  EXPECT_NEAR(twice_area_about_y(m) / 2, 6.2, 1e-12);
}

TEST(ReduceFacePoints, RegularHexagonKeepsItsLargestQuad) {
  // Of a regular hexagon of circumradius 1 the largest quad is a rectangle 1 × √3 (area √3,
  // against 3√3/4 for half the hexagon), whichever vertex is the deepest.
  for (int deepest = 0; deepest < 6; ++deepest) {
    ContactPoint points[6];
    for (int k = 0; k < 6; ++k)
      points[k] = {Vec3(std::cos(k * M_PI / 3), 0, std::sin(k * M_PI / 3)),
                   k == deepest ? 0.2 : 0.1, static_cast<std::uint32_t>(k)};
    const Manifold m = reduce_face_points(points, 6, Vec3(0, 1, 0));
    ASSERT_EQ(m.count, 4);
    EXPECT_EQ(m.points[0].feature, static_cast<std::uint32_t>(deepest));
    EXPECT_NEAR(twice_area_about_y(m) / 2, std::sqrt(3.0), 1e-12) << "deepest " << deepest;
  }
}

TEST(ReduceFacePoints, FourOrFewerAreKeptAsTheyAre) {
  ContactPoint points[3] = {{Vec3(0, 0, 0), 0.1, 7}, {Vec3(1, 0, 0), 0.3, 8}, {Vec3(0, 0, 1), 0.2, 9}};
  const Manifold m = reduce_face_points(points, 3, Vec3(0, 1, 0));
  ASSERT_EQ(m.count, 3);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(m.points[k].feature, 7u + k);
  expect_vec(m.normal, Vec3(0, 1, 0));
}

TEST(BoxBox, CrossedEdgesGiveOnePoint) {
  // A turned 45° about z has its top edge along z at y = √2. B turned 45° about x has its
  // bottom edge along x, √2 below its centre; with the centre at 2√2 − 0.1 the edges cross
  // 0.1 deep at (0, √2, 0): one point, midway, normal +y.
  const Manifold m = collide_box_box(
      pose(Vec3::Zero(), about(Vec3(0, 0, 1), M_PI / 4)), Vec3(1, 1, 1),
      pose(Vec3(0, 2 * sqrt2 - 0.1, 0), about(Vec3(1, 0, 0), M_PI / 4)), Vec3(1, 1, 1));
  ASSERT_EQ(m.count, 1);
  expect_vec(m.normal, Vec3(0, 1, 0), 1e-14);
  EXPECT_NEAR(m.points[0].depth, 0.1, 1e-14);
  expect_vec(m.points[0].point, Vec3(0, sqrt2 - 0.05, 0), 1e-14);
}

TEST(BoxBox, SeparatedBoxesAndTheMargin) {
  const Pose a = pose(Vec3::Zero(), about(Vec3(0, 1, 0), 0.3));
  const Pose b = pose(a.rotation * Vec3(2.05, 0, 0), about(Vec3(0, 1, 0), 0.3));
  EXPECT_EQ(collide_box_box(a, Vec3(1, 1, 1), b, Vec3(1, 1, 1)).count, 0);
  const Manifold m = collide_box_box(a, Vec3(1, 1, 1), b, Vec3(1, 1, 1), 0.1);
  ASSERT_EQ(m.count, 4);
  expect_vec(m.normal, a.rotation.col(0), 1e-14);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(m.points[k].depth, -0.05, 1e-14);
}

// In any overlapping configuration, each point's witnesses (point ± n·depth/2) lie on the two
// surfaces: p_a = point + n depth/2 on a's surface, p_b = point − n depth/2 on b's, measured
// with a distance function of boxes written here from their definition.
TEST(BoxBox, WitnessPointsLieOnTheSurfacesOfRandomRotatedBoxes) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0), size(0.3, 1.2);
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Vec3 ha(size(rng), size(rng), size(rng)), hb(size(rng), size(rng), size(rng));
    const Pose a =
        pose(Vec3(u(rng), u(rng), u(rng)), about(Vec3(u(rng), u(rng), u(rng) + 2), 3 * u(rng)));
    const Pose b = pose(a.position + 1.5 * Vec3(u(rng), u(rng), u(rng)),
                        about(Vec3(u(rng) + 2, u(rng), u(rng)), 3 * u(rng)));
    const Manifold m = collide_box_box(a, ha, b, hb);
    for (int k = 0; k < m.count; ++k) {
      const ContactPoint& p = m.points[k];
      EXPECT_GE(p.depth, 0.0);
      const Vec3 on_a = p.point + 0.5 * p.depth * m.normal,
                 on_b = p.point - 0.5 * p.depth * m.normal;
      EXPECT_NEAR(box_distance(a, ha, on_a), 0.0, 1e-9);
      EXPECT_NEAR(box_distance(b, hb, on_b), 0.0, 1e-9);
      // The incident witness (a clipped corner, or a point of a crossing edge) is inside the
      // other box; its projection on the reference face need not be inside the tilted box.
      // (Only for overlaps thinner than the boxes: deeper, a clipped corner can come out of
      // the far side of the reference box.)
      if (p.depth < std::min(ha.minCoeff(), hb.minCoeff()))
        EXPECT_LE(std::min(box_distance(a, ha, on_b), box_distance(b, hb, on_a)), 1e-9);
      ++checked;
    }
  }
  EXPECT_GT(checked, 200);
}

// Which kind of contact two boxes get, against a separating-axis test written here by brute
// force: each of the 15 axes (3 faces of a, 3 of b, the 9 edge cross products of at least
// 1e-6 length), the boxes' 8 corners each projected on it, the gap between the two intervals.
// The rule (engine/narrow_phase.cpp, collide_box_box): separated when an axis parts them by
// more than the margin; otherwise a's face unless b's is better by the tolerance, and an edge
// pair only when better than that face by the tolerance too. The edge axes that cannot win
// are not computed by the engine (bounded through the products of the two rotations): an edge
// it skipped wrongly would show here as a face contact where the edge pair wins. Ties within
// 1e-9 of the rule's thresholds are left out (rounding decides them).
TEST(BoxBox, ContactKindFollowsABruteForceSeparatingAxisTest) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0), size(0.2, 1.0);
  auto corners_gap = [](const Pose& a, const Vec3& ha, const Pose& b, const Vec3& hb,
                        const Vec3& n) {
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (int box = 0; box < 2; ++box)
      for (int c = 0; c < 8; ++c) {
        const Pose& p = box == 0 ? a : b;
        const Vec3& h = box == 0 ? ha : hb;
        const Vec3 local((c & 1) ? h.x() : -h.x(), (c & 2) ? h.y() : -h.y(),
                         (c & 4) ? h.z() : -h.z());
        const double s = n.dot(p.position + p.rotation * local);
        lo[box] = std::min(lo[box], s), hi[box] = std::max(hi[box], s);
      }
    return std::max(lo[1] - hi[0], lo[0] - hi[1]);
  };
  int kinds[3] = {0, 0, 0}, separated = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Vec3 ha(size(rng), size(rng), size(rng)), hb(size(rng), size(rng), size(rng));
    // Every third pair nearly aligned (rotations of 1e-9 to 1e-2 rad), as boxes resting on
    // each other are; the others at random.
    const double tilt = trial % 3 == 0 ? std::pow(10.0, -2.0 - 7.0 * std::abs(u(rng))) : 3.0;
    const Pose a = pose(Vec3(u(rng), u(rng), u(rng)),
                        about(Vec3(u(rng), u(rng), u(rng) + 2), tilt * u(rng)));
    const Vec3 direction = Vec3(u(rng), u(rng), u(rng)).normalized();
    const Pose b = pose(a.position + (ha.norm() + hb.norm()) * (0.4 + 0.7 * std::abs(u(rng))) *
                                         direction,
                        about(Vec3(u(rng) + 2, u(rng), u(rng)), tilt * u(rng)));
    const double margin = trial % 2 == 0 ? 0.0 : 0.05;
    double best[3] = {-1e300, -1e300, -1e300};
    Vec3 edge_axis = Vec3::Zero();
    for (int i = 0; i < 3; ++i) {
      best[0] = std::max(best[0], corners_gap(a, ha, b, hb, a.rotation.col(i)));
      best[1] = std::max(best[1], corners_gap(a, ha, b, hb, b.rotation.col(i)));
      for (int j = 0; j < 3; ++j) {
        const Vec3 axis = a.rotation.col(i).cross(b.rotation.col(j));
        if (axis.norm() <= 1e-6) continue;
        const double gap = corners_gap(a, ha, b, hb, axis.normalized());
        if (gap > best[2]) best[2] = gap, edge_axis = axis.normalized();
      }
    }
    const double tolerance = std::min(1e-3, 0.01 * std::min(ha.minCoeff(), hb.minCoeff()));
    const double face = best[1] > best[0] + tolerance ? best[1] : best[0];
    const double largest = std::max({best[0], best[1], best[2]});
    auto near = [](double x, double y) { return std::abs(x - y) < 1e-9; };
    if (near(largest, margin) || near(best[1], best[0] + tolerance) ||
        near(best[2], face + tolerance))
      continue;
    const Manifold m = collide_box_box(a, ha, b, hb, margin);
    if (largest > margin) {
      EXPECT_EQ(m.count, 0) << trial;
      ++separated;
      continue;
    }
    const int kind = best[2] > face + tolerance ? 2 : (face == best[1] ? 1 : 0);
    // A face contact may keep no point: the incident face's corners clipped to the reference
    // face can all lie beyond the margin while the boxes' nearest features, edges, do not
    // (best[2] within the tolerance of the face). An edge pair always has its point.
    if (m.count == 0) {
      EXPECT_NE(kind, 2) << trial;
      continue;
    }
    // An edge pair's one point has feature 2³¹ + 3 i + j; a face's points have hashed ids
    // (which may look the same), so its normal, along no face normal, tells it apart.
    auto along_face_of = [&m](const Pose& box) {
      return std::abs((box.rotation.transpose() * m.normal).cwiseAbs().maxCoeff() - 1.0) < 1e-9;
    };
    const bool edge = m.count == 1 && m.points[0].feature - 0x80000000u < 9u &&
                      !along_face_of(a) && !along_face_of(b);
    ++kinds[kind];
    EXPECT_EQ(edge, kind == 2) << trial;
    if (kind == 2) {
      EXPECT_EQ(m.count, 1) << trial;
      EXPECT_NEAR(std::abs(m.normal.dot(edge_axis)), 1.0, 1e-9) << trial;
    } else {  // the normal is a face normal of the box the rule picks
      EXPECT_TRUE(along_face_of(kind == 0 ? a : b)) << trial;
    }
  }
  // Every outcome was seen many times.
  EXPECT_GT(kinds[0], 300);
  EXPECT_GT(kinds[1], 200);
  EXPECT_GT(kinds[2], 200);
  EXPECT_GT(separated, 300);
}

TEST(BoxBox, FeaturesStayWhileTheSameFeaturesTouch) {
  const Pose a = pose(Vec3::Zero());
  // B's bottom face overhangs A's top face along x: two of its corners and two clipped points.
  const Manifold m1 = collide_box_box(a, Vec3(1, 1, 1), pose(Vec3(1.5, 1.4, 0)), Vec3(1, 0.5, 0.8));
  const Manifold m2 =
      collide_box_box(a, Vec3(1, 1, 1), pose(Vec3(1.45, 1.41, 0.02)), Vec3(1, 0.5, 0.8));
  ASSERT_EQ(m1.count, 4);
  ASSERT_EQ(m2.count, 4);
  std::vector<std::uint32_t> f1, f2;
  for (int k = 0; k < 4; ++k)
    f1.push_back(m1.points[k].feature), f2.push_back(m2.points[k].feature);
  std::sort(f1.begin(), f1.end());
  std::sort(f2.begin(), f2.end());
  EXPECT_EQ(f1, f2);
  EXPECT_EQ(std::unique(f1.begin(), f1.end()), f1.end()) << "features of one manifold differ";
}

TEST(Shapes, NoneTouchesNothingAndBoundingRadius) {
  Shape none, ball, box;
  ball.kind = ShapeKind::sphere, ball.radius = 2;
  box.kind = ShapeKind::box, box.half_extents = Vec3(1, 2, 2);
  EXPECT_EQ(collide_shapes(none, pose(Vec3::Zero()), ball, pose(Vec3::Zero())).count, 0);
  EXPECT_EQ(collide_shape_plane(none, pose(Vec3::Zero()), make_plane(Vec3(0, 1, 0), 5)).count, 0);
  EXPECT_EQ(bounding_radius(ball), 2.0);
  EXPECT_EQ(bounding_radius(box), 3.0);
  EXPECT_EQ(bounding_radius(none), 0.0);
}

TEST(Plane, NormalisedWithTheSameHalfSpaceAndRefusals) {
  const Plane p = make_plane(Vec3(0, 0, -4), 8, 0.25, 0.1);
  expect_vec(p.normal, Vec3(0, 0, -1));
  EXPECT_EQ(p.offset, 2.0);  // -4 z >= 8  <=>  -z >= 2
  EXPECT_EQ(p.restitution, 0.25);
  EXPECT_EQ(p.friction, 0.1);
  EXPECT_EQ(signed_distance(p, Vec3(0, 0, -5)), 3.0);
  // Tiny and huge normals: the same half-space, without underflow or overflow.
  EXPECT_EQ(make_plane(Vec3(0, 1e-300, 0), 2e-300).offset, 2.0);
  EXPECT_EQ(make_plane(Vec3(3e300, 0, 4e300), 1e300).normal, Vec3(0.6, 0, 0.8));
  EXPECT_THROW(make_plane(Vec3(0, 1e-300, 0), 1e10), std::invalid_argument);  // offset 1e310
  EXPECT_THROW(make_plane(Vec3::Zero(), 0), std::invalid_argument);
  EXPECT_THROW(make_plane(Vec3(0, NAN, 0), 0), std::invalid_argument);
  EXPECT_THROW(make_plane(Vec3(0, 1, 0), INFINITY), std::invalid_argument);
  EXPECT_THROW(make_plane(Vec3(0, 1, 0), 0, 1.5, 0.5), std::invalid_argument);
  EXPECT_THROW(make_plane(Vec3(0, 1, 0), 0, 0.5, -0.1), std::invalid_argument);
  EXPECT_EQ(material_problem(-0.5, 0), "restitution must be in [0, 1], got -0.5");
  EXPECT_EQ(material_problem(0, NAN), "friction must be finite and >= 0, got nan");
  EXPECT_DOUBLE_EQ(mix_friction(0.4, 0.9), 0.6);
  EXPECT_EQ(mix_restitution(0.2, 0.7), 0.7);
}

}  // namespace
}  // namespace rigidlab
