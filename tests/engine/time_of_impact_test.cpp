// engine/time_of_impact.hpp and the separation bounds of engine/narrow_phase.hpp against hand
// geometry: the time a sphere needs to reach a plane or another sphere at constant velocity
// (gap / closing speed), misses, a turning box, and the separating-axis bound for two boxes
// against the exact distance of their nearest corners.
#include "engine/time_of_impact.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rigidlab {
namespace {

Shape sphere(double r) {
  Shape s;
  s.kind = ShapeKind::sphere;
  s.radius = r;
  return s;
}

Shape box(const Vec3& half) {
  Shape s;
  s.kind = ShapeKind::box;
  s.half_extents = half;
  return s;
}

Pose at(const Vec3& p) { return Pose{p, Mat3::Identity()}; }

TEST(TimeOfImpact, SphereMeetsAPlaneAtGapOverNormalSpeed) {
  // Centre 1.5 m up, radius 0.5: the gap 1 m closes at 4 m/s (the sideways 3 m/s does not
  // count): t = 0.25 s, to within the tolerance band.
  const Plane floor = make_plane(Vec3(0, 1, 0), 0.0);
  const Motion m{Vec3(3, -4, 0), Vec3::Zero()};
  const double tol = 1e-4;
  const double t = time_of_impact(sphere(0.5), at(Vec3(0, 1.5, 0)), m, floor, 1.0, tol);
  EXPECT_GE(t, 0.25 - tol / 4);
  EXPECT_LE(t, 0.25);
  EXPECT_LT(time_of_impact(sphere(0.5), at(Vec3(0, 1.5, 0)), m, floor, 0.2, tol), 0.0);  // later
  const Motion away{Vec3(3, 4, 0), Vec3::Zero()};
  EXPECT_LT(time_of_impact(sphere(0.5), at(Vec3(0, 1.5, 0)), away, floor, 10.0, tol), 0.0);
  EXPECT_EQ(time_of_impact(sphere(0.5), at(Vec3(0, 0.5, 0)), m, floor, 1.0, tol), 0.0);
}

TEST(TimeOfImpact, SpheresHeadOnAndPassingBy) {
  // Centres 3 m apart, radii 0.5 and 1: gap 1.5 m at a closing speed of 6 m/s: t = 0.25 s.
  const Motion a{Vec3(2, 0, 0), Vec3::Zero()}, b{Vec3(-4, 0, 0), Vec3::Zero()};
  const double tol = 1e-6;
  const double t =
      time_of_impact(sphere(0.5), at(Vec3::Zero()), a, sphere(1.0), at(Vec3(3, 0, 0)), b, 1.0, tol);
  EXPECT_NEAR(t, 0.25, tol);
  // Offset sideways by 1.6 m > 0.5 + 1: they pass each other.
  EXPECT_LT(time_of_impact(sphere(0.5), at(Vec3::Zero()), a, sphere(1.0), at(Vec3(3, 1.6, 0)), b,
                           1.0, tol),
            0.0);
  // Offset by 1.2 m: the centres come within 1.2 < 1.5 m, when the x gap is √(1.5² − 1.2²)
  // = 0.9 m, after (3 − 0.9)/6 = 0.35 s.
  EXPECT_NEAR(time_of_impact(sphere(0.5), at(Vec3::Zero()), a, sphere(1.0), at(Vec3(3, 1.2, 0)),
                             b, 1.0, tol),
              0.35, 1e-5);
}

// A sphere's spin moves none of its surface closer: spinning spheres meet the plane and each
// other when the non-spinning ones do (gap / closing speed), only by smaller advances (the
// bound s counts |ω| R; spins that make s a few times the closing speed still settle within
// the 64 advances).
TEST(TimeOfImpact, SpinningSpheresMeetWhenTheirCentresSaySo) {
  const Plane floor = make_plane(Vec3(0, 1, 0), 0.0);
  const double tol = 1e-6;
  const Motion falling{Vec3(3, -4, 0), Vec3(0, 0, 4)};
  const double t = time_of_impact(sphere(0.5), at(Vec3(0, 1.5, 0)), falling, floor, 1.0, tol);
  EXPECT_GE(t, 0.25 - tol / 4);
  EXPECT_LE(t, 0.25);
  const Motion a{Vec3(2, 0, 0), Vec3(2, -2, 1)}, b{Vec3(-4, 0, 0), Vec3(0, 3, 0)};
  EXPECT_NEAR(time_of_impact(sphere(0.5), at(Vec3::Zero()), a, sphere(1.0), at(Vec3(3, 1.2, 0)),
                             b, 1.0, tol),
              0.35, 1e-5);
}

TEST(TimeOfImpact, TurningBoxReachesThePlaneWithItsCorner) {
  // A box of half size (1, 0.1, 0.1) with its centre 0.6 m above a floor, turning about z at
  // 1 rad/s: its lowest corner, at distance √(1 + 0.01) from the centre, reaches the floor when
  // sin(θ) + 0.1 cos(θ) = 0.6, θ = asin(0.6/√1.01) − atan(0.1).
  const Plane floor = make_plane(Vec3(0, 1, 0), 0.0);
  const Motion turn{Vec3::Zero(), Vec3(0, 0, 1)};
  const double want = std::asin(0.6 / std::sqrt(1.01)) - std::atan(0.1);
  const double t = time_of_impact(box(Vec3(1, 0.1, 0.1)), at(Vec3(0, 0.6, 0)), turn, floor, 2.0,
                                  1e-7);
  EXPECT_NEAR(t, want, 1e-6);
  EXPECT_LE(t, want);
}

TEST(Separation, BoxesAreNeverCloserThanTheSeparatingAxesSay) {
  // Unit cubes with centres 1.4 m apart along each axis: the nearest corners, (0.5, 0.5, 0.5)
  // and (0.9, 0.9, 0.9), are 0.4·√3 m apart, while the best axis of the test (a face axis)
  // gives 0.4 m: a lower bound, which is what conservative advancement needs.
  const Vec3 half(0.5, 0.5, 0.5);
  const Vec3 offset(1.4, 1.4, 1.4);
  const double exact = std::sqrt(3.0) * 0.4;
  const double bound = separation(box(half), at(Vec3::Zero()), box(half), at(offset));
  EXPECT_LE(bound, exact);
  EXPECT_NEAR(bound, 0.4, 1e-12);  // the face axes: 1.4 − 0.5 − 0.5
  // With a sphere it is the exact distance: from the corner (0.5, 0.5, 0.5) to (1, 1, 1) less r.
  EXPECT_NEAR(separation(box(half), at(Vec3::Zero()), sphere(0.2), at(Vec3(1, 1, 1))),
              std::sqrt(3.0) * 0.5 - 0.2, 1e-12);
  const Plane floor = make_plane(Vec3(0, 1, 0), -1.0);
  EXPECT_NEAR(separation(box(half), at(Vec3::Zero()), floor), 0.5, 1e-12);
  EXPECT_EQ(separation(Shape{}, at(Vec3::Zero()), floor), std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace rigidlab
