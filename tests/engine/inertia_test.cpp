// Tests for engine/inertia.cpp. Each closed form is compared with a numerical integral of
// ∫((r·r)E − r⊗r) dm over the shape, where the shape is given only by its definition (an
// inside test for solids, a parametrised surface for thin shells), so a wrong coefficient, a
// wrong axis or a misplaced centre of mass shows up. The tensor algebra is checked against the
// definition of the tensor of particles and against geometric facts (a box cut in two halves,
// a rotation swapping axes).
#include "engine/inertia.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <functional>
#include <random>
#include <stdexcept>

namespace rigidlab {
namespace {

const double pi = std::acos(-1.0);

// ---- numerical integration, independent of engine/inertia.cpp ------------------------------

// Zeroth, first and second moments ∫1, ∫r, ∫r rᵀ of a weighted set of samples.
struct Moments {
  double total = 0.0;
  Vec3 first = Vec3::Zero();
  Mat3 second = Mat3::Zero();

  void add_point(const Vec3& p, double weight) {
    total += weight;
    first += weight * p;
    second += weight * p * p.transpose();
  }
  // The cone of directions dω along unit ω, filled from the origin out to distance R:
  // ∫₀ᴿ (1, ρω, ρ²ωωᵀ) ρ² dρ, exact in ρ.
  void add_ray(const Vec3& omega, double R, double solid_angle) {
    const double R3 = R * R * R;
    total += solid_angle * R3 / 3;
    first += solid_angle * R3 * R / 4 * omega;
    second += solid_angle * R3 * R * R / 5 * omega * omega.transpose();
  }
  Vec3 com() const { return first / total; }
  // The tensor about the COM when the total weight is scaled to `mass`: the definition
  // ∫((r·r)E − r⊗r) dm with r measured from the COM.
  Mat3 inertia(double mass) const {
    const Vec3 c = com();
    const Mat3 central = (second - total * c * c.transpose()) * (mass / total);
    return central.trace() * Mat3::Identity() - central;
  }
};

// Moments of a solid that is star-shaped about the origin (every ray from the origin leaves
// it once), given only by its inside test and a radius beyond which nothing is inside: in
// spherical coordinates, the midpoint rule over n polar angles θ and 2n azimuths φ, and along
// each ray the exact radial integral out to the boundary, located by bisection to 1e-16 of the
// radius. Edges and corners of the shape make the radius a kinked function of the direction,
// which limits the accuracy to O(1/n²).
Moments integrate_solid(const std::function<bool(const Vec3&)>& inside, double radius_bound,
                        int n) {
  Moments m;
  const double step = pi / n;
  for (int i = 0; i < n; ++i) {
    const double theta = (i + 0.5) * step;
    for (int j = 0; j < 2 * n; ++j) {
      const double phi = (j + 0.5) * step;
      const Vec3 omega(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                       std::cos(theta));
      double in = 0.0, out = radius_bound;
      for (int k = 0; k < 56; ++k) {
        const double mid = 0.5 * (in + out);
        (inside(mid * omega) ? in : out) = mid;
      }
      m.add_ray(omega, 0.5 * (in + out), std::sin(theta) * step * step);
    }
  }
  return m;
}

// Compares a closed form with the numerical tensor (all nine entries, so the zero products of
// inertia are checked too) relative to the largest moment, and the COM with the origin
// relative to the shape's size.
void expect_matches(const Mat3& closed_form, const Moments& numeric, double mass, double size,
                    double tolerance) {
  const Mat3 numerical = numeric.inertia(mass);
  const double scale = closed_form.maxCoeff();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(closed_form(i, j), numerical(i, j), tolerance * scale)
          << "entry (" << i << ", " << j << ")\nclosed form\n" << closed_form
          << "\nnumerical\n" << numerical;
  EXPECT_LT(numeric.com().norm(), tolerance * size) << "the tensor is about the COM at the origin";
}

const int grid = 600;
// At grid = 600 the integration error is below 6e-5 of the largest moment for every shape here
// (the cone, whose apex and rim are the worst kinks) and falls as 1/grid²; a wrong coefficient
// or a misplaced COM changes the moments by percents.
const double integral_tolerance = 2e-4;

// ---- closed forms against integrals --------------------------------------------------------

TEST(ShapeInertia, SolidSphereMatchesIntegral) {
  const double m = 2.5, r = 0.7;
  const Moments num = integrate_solid([&](const Vec3& p) { return p.norm() <= r; }, 2 * r, grid);
  EXPECT_NEAR(num.total, 4.0 / 3.0 * pi * r * r * r, 1e-4 * num.total);
  expect_matches(inertia_solid_sphere(m, r), num, m, r, integral_tolerance);
}

TEST(ShapeInertia, SolidBoxMatchesIntegralWithWidthAlongX) {
  const double m = 3.0;
  const Vec3 size(0.4, 1.0, 2.2), half = size / 2;
  const Moments num = integrate_solid(
      [&](const Vec3& p) { return (p.cwiseAbs() - half).maxCoeff() <= 0; }, size.norm(), grid);
  expect_matches(inertia_solid_box(m, size), num, m, size.norm(), integral_tolerance);
  EXPECT_NEAR(inertia_solid_box(m, size)(0, 0), m * (1.0 + 2.2 * 2.2) / 12, 1e-15);
}

TEST(ShapeInertia, SolidCylinderMatchesIntegralWithAxisZ) {
  const double m = 1.5, r = 0.3, h = 1.1;
  const Moments num = integrate_solid(
      [&](const Vec3& p) { return p.head<2>().norm() <= r && std::abs(p.z()) <= h / 2; }, r + h,
      grid);
  expect_matches(inertia_solid_cylinder(m, r, h), num, m, h, integral_tolerance);
}

TEST(ShapeInertia, SolidEllipsoidMatchesIntegralWithSemiAxesAlongXYZ) {
  const double m = 4.0, a = 0.5, b = 1.2, c = 0.8;
  const Moments num = integrate_solid(
      [&](const Vec3& p) { return p.cwiseQuotient(Vec3(a, b, c)).squaredNorm() <= 1; },
      a + b + c, grid);
  expect_matches(inertia_solid_ellipsoid(m, a, b, c), num, m, b, integral_tolerance);
}

// The capsule's definition: all points within r of the segment from (0,0,−h/2) to (0,0,h/2).
bool inside_capsule(const Vec3& p, double r, double h) {
  const double along = std::clamp(p.z(), -h / 2, h / 2);
  return (p - Vec3(0, 0, along)).norm() <= r;
}

TEST(ShapeInertia, CapsuleMatchesIntegral) {
  const double m = 2.0, r = 0.25, h = 0.9;
  const Moments num =
      integrate_solid([&](const Vec3& p) { return inside_capsule(p, r, h); }, r + h, grid);
  expect_matches(inertia_capsule(m, r, h), num, m, h + 2 * r, integral_tolerance);
}

TEST(ShapeInertia, ShortCapsuleMatchesIntegralAndZeroLengthIsASphere) {
  const double m = 2.0, r = 0.5, h = 0.1;  // caps dominate: tests the hemisphere terms
  const Moments num =
      integrate_solid([&](const Vec3& p) { return inside_capsule(p, r, h); }, r + h, grid);
  expect_matches(inertia_capsule(m, r, h), num, m, h + 2 * r, integral_tolerance);
  EXPECT_LT((inertia_capsule(m, r, 0.0) - inertia_solid_sphere(m, r)).norm(), 1e-15);
}

TEST(ShapeInertia, SolidConeAboutItsComWithApexTowardPlusZ) {
  const double m = 1.2, r = 0.4, h = 1.3;
  // Base at z = −h/4, apex at z = 3h/4: the stated convention puts the COM at the origin,
  // which expect_matches checks from the integral.
  auto inside = [&](const Vec3& p) {
    const double from_apex = 0.75 * h - p.z();
    return from_apex >= 0 && from_apex <= h && p.head<2>().norm() <= r * from_apex / h;
  };
  const Moments num = integrate_solid(inside, r + h, grid);
  expect_matches(inertia_solid_cone(m, r, h), num, m, h, integral_tolerance);
}

// Thin shells: the surface integral by the midpoint rule in the surface's parameters.
TEST(ShapeInertia, HollowSphereMatchesSurfaceIntegral) {
  const double m = 0.8, r = 1.7;
  const int n = 400;
  Moments num;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const double theta = (i + 0.5) * pi / n, phi = (j + 0.5) * pi / n;
      const Vec3 p = r * Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                              std::cos(theta));
      num.add_point(p, r * r * std::sin(theta));  // dA = r² sinθ dθ dφ
    }
  EXPECT_NEAR(num.total * (pi / n) * (pi / n), 4 * pi * r * r, 1e-4 * 4 * pi * r * r);
  expect_matches(inertia_hollow_sphere(m, r), num, m, r, integral_tolerance);
}

TEST(ShapeInertia, HollowCylinderIsTheLateralSurfaceWithAxisZ) {
  const double m = 0.6, r = 0.35, h = 2.0;
  const int n = 400;
  Moments num;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double phi = (i + 0.5) * 2 * pi / n, z = -h / 2 + (j + 0.5) * h / n;
      num.add_point(Vec3(r * std::cos(phi), r * std::sin(phi), z), 1.0);
    }
  expect_matches(inertia_hollow_cylinder(m, r, h), num, m, h, integral_tolerance);
}

TEST(ShapeInertia, RefusesImpossibleDimensions) {
  const double nan = std::nan(""), inf = HUGE_VAL;
  EXPECT_THROW(inertia_solid_sphere(0, 1), std::invalid_argument);
  EXPECT_THROW(inertia_solid_sphere(1, -1), std::invalid_argument);
  EXPECT_THROW(inertia_hollow_sphere(nan, 1), std::invalid_argument);
  EXPECT_THROW(inertia_solid_box(1, Vec3(1, 0, 1)), std::invalid_argument);
  EXPECT_THROW(inertia_solid_cylinder(1, 1, inf), std::invalid_argument);
  EXPECT_THROW(inertia_hollow_cylinder(1, 0, 1), std::invalid_argument);
  EXPECT_THROW(inertia_solid_ellipsoid(1, 1, 1, -2), std::invalid_argument);
  EXPECT_THROW(inertia_capsule(1, 1, -0.5), std::invalid_argument);
  EXPECT_THROW(inertia_solid_cone(-1, 1, 1), std::invalid_argument);
  try {
    inertia_solid_box(1, Vec3(-1, 1, 1));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "width must be > 0, got -1");
  }
}

TEST(ShapeInertia, EveryShapeSatisfiesThePhysicalRules) {
  for (const Mat3& I :
       {inertia_solid_sphere(1, 1), inertia_hollow_sphere(1, 1),
        inertia_solid_box(1, Vec3(1, 2, 3)), inertia_solid_cylinder(1, 0.1, 5),
        inertia_hollow_cylinder(1, 2, 0.01), inertia_solid_ellipsoid(1, 1, 2, 3),
        inertia_capsule(1, 0.2, 3), inertia_solid_cone(1, 1, 0.1)})
    EXPECT_EQ(inertia_tensor_problem(I), "") << I;
}

// ---- particles and tensor algebra ----------------------------------------------------------

TEST(PointInertia, MatchesTheComponentDefinition) {
  const double m = 2.0;
  const Vec3 r(1.0, -2.0, 0.5);
  Mat3 want;  // Ixx = m(y² + z²), Ixy = −m x y, ... (seed 000_*, "Inertia")
  want << m * (4 + 0.25), m * 2, m * -0.5,
          m * 2, m * (1 + 0.25), m * 1,
          m * -0.5, m * 1, m * (1 + 4);
  EXPECT_LT((inertia_point(m, r) - want).norm(), 1e-14);
  EXPECT_THROW(inertia_point(-1, r), std::invalid_argument);
}

TEST(PointInertia, DumbbellHasTheReducedMassMoment) {
  const double m1 = 1.0, m2 = 3.0, length = 2.0;
  const MassProperties p = inertia_points({{m1, Vec3(0, 0, 0)}, {m2, Vec3(length, 0, 0)}});
  EXPECT_DOUBLE_EQ(p.mass, 4.0);
  EXPECT_LT((p.com - Vec3(1.5, 0, 0)).norm(), 1e-15);
  const double reduced = m1 * m2 / (m1 + m2) * length * length;  // μ L² about the COM
  EXPECT_LT((p.inertia - Vec3(0, reduced, reduced).asDiagonal().toDenseMatrix()).norm(), 1e-14);
}

TEST(PointInertia, EightCornerMassesOfABox) {
  const Vec3 half(0.5, 1.0, 1.5), centre(3, -1, 2);
  std::vector<PointMass> corners;
  for (int k = 0; k < 8; ++k)
    corners.push_back({0.25, centre + Vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1)
                                          .cwiseProduct(half)});
  const MassProperties p = inertia_points(corners);
  EXPECT_LT((p.com - centre).norm(), 1e-14);
  // Every corner is at (±a, ±b, ±c) from the centre: Ixx = M(b² + c²), ...
  const Vec3 h2 = half.cwiseProduct(half);
  const Vec3 want = 2.0 * Vec3(h2.y() + h2.z(), h2.x() + h2.z(), h2.x() + h2.y());
  EXPECT_LT((p.inertia - want.asDiagonal().toDenseMatrix()).norm(), 1e-13);
  EXPECT_THROW(inertia_points({}), std::invalid_argument);
  EXPECT_THROW(inertia_points({{0.0, Vec3::Zero()}}), std::invalid_argument);
}

std::vector<PointMass> random_cloud(std::mt19937& rng, int count) {
  std::uniform_real_distribution<double> position(-2, 2), mass(0.1, 3);
  std::vector<PointMass> cloud;
  for (int i = 0; i < count; ++i)
    cloud.push_back(
        {mass(rng), Vec3(position(rng), position(rng), position(rng)) + Vec3(5, 1, -3)});
  return cloud;
}

Quat random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
}

TEST(ParallelAxis, MovesTheComTensorToAnyPoint) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    const std::vector<PointMass> cloud = random_cloud(rng, 7);
    const MassProperties p = inertia_points(cloud);
    const Vec3 point(trial * 0.1, -1.0, 2.0);
    Mat3 direct = Mat3::Zero();  // the definition, summed about `point`
    for (const PointMass& q : cloud) direct += inertia_point(q.mass, q.position - point);
    const Mat3 moved = parallel_axis(p.inertia, p.mass, p.com - point);
    EXPECT_LT((moved - direct).norm(), 1e-12 * direct.norm());
  }
}

TEST(ParallelAxis, ScalarFormOfTheSeed) {
  // Seed 000_*: I_v = I_com + m r² for a parallel axis at distance r. A rod along x (a thin
  // cylinder), axis y moved to the rod's end: m L²/12 + m (L/2)² = m L²/3.
  const double m = 2.0, length = 3.0;
  const Mat3 rod = inertia_solid_cylinder(m, 1e-9, length);
  const Mat3 along_x = rotate_inertia(rod, quat_from_axis_angle(Vec3::UnitY(), pi / 2));
  const Mat3 at_end = parallel_axis(along_x, m, Vec3(length / 2, 0, 0));
  EXPECT_NEAR(about_axis(at_end, Vec3::UnitY()), m * length * length / 3, 1e-12);
}

TEST(Rotate, QuarterTurnAboutZSwapsXAndY) {
  const Mat3 box = inertia_solid_box(1, Vec3(1, 2, 3));
  const Mat3 turned = rotate_inertia(box, quat_from_axis_angle(Vec3::UnitZ(), pi / 2));
  EXPECT_NEAR(turned(0, 0), box(1, 1), 1e-15);
  EXPECT_NEAR(turned(1, 1), box(0, 0), 1e-15);
  EXPECT_NEAR(turned(2, 2), box(2, 2), 1e-15);
  EXPECT_NEAR(turned(0, 1), 0.0, 1e-15);
}

TEST(Rotate, RotatingParticlesRotatesTheTensor) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 50; ++trial) {
    const Quat q = random_rotation(rng);
    const Mat3 R = q.toRotationMatrix();
    std::vector<PointMass> cloud = random_cloud(rng, 5), rotated = cloud;
    for (PointMass& p : rotated) p.position = R * p.position;
    const Mat3 want = inertia_points(rotated).inertia;
    EXPECT_LT((rotate_inertia(inertia_points(cloud).inertia, R) - want).norm(),
              1e-12 * want.norm());
    EXPECT_LT((rotate_inertia(inertia_points(cloud).inertia, Quat(2.0 * q.coeffs())) - want).norm(),
              1e-12 * want.norm())
        << "a quaternion is normalised first";
  }
  EXPECT_THROW(rotate_inertia(Mat3::Identity(), Quat(0, 0, 0, 0)), std::invalid_argument);
}

TEST(AboutAxis, IsTheMomentOfTheMassAboutThatLine) {
  std::mt19937 rng(5);
  const std::vector<PointMass> cloud = random_cloud(rng, 6);
  const MassProperties p = inertia_points(cloud);
  const Vec3 axis(1.0, 2.0, -2.0);  // not unit: normalised
  const Vec3 n = axis / 3.0;
  double direct = 0;  // Σ m (distance to the line through the COM along n)²
  for (const PointMass& q : cloud) {
    const Vec3 r = q.position - p.com;
    direct += q.mass * (r - r.dot(n) * n).squaredNorm();
  }
  EXPECT_NEAR(about_axis(p.inertia, axis), direct, 1e-12 * direct);
  EXPECT_THROW(about_axis(p.inertia, Vec3::Zero()), std::invalid_argument);
  EXPECT_THROW(about_axis(p.inertia, Vec3(std::nan(""), 0, 0)), std::invalid_argument);
}

// Axes and quaternions of any length, 1e300 (squares overflow) or 1e-320 (squares underflow),
// mean their direction: diag(1, 2, 3) about (1, 1, 0)/√2 is (1 + 2)/2, and a quarter turn
// about x swaps the y and z moments.
TEST(AboutAxisAndRotate, HugeAndTinyDirectionsAreNormalisedWithoutOverflow) {
  const Mat3 I = Vec3(1, 2, 3).asDiagonal();
  const Mat3 turned = Vec3(1, 3, 2).asDiagonal();
  for (double a : {1e300, 1e-320}) {
    EXPECT_NEAR(about_axis(I, Vec3(a, a, 0)), 1.5, 1e-15) << a;
    EXPECT_LT((rotate_inertia(I, Quat(a, a, 0, 0)) - turned).norm(), 1e-14) << a;
  }
}

TEST(Principal, RecoversDiagonalAndRotationUpToAxisSigns) {
  std::mt19937 rng(9);
  const Vec3 moments(1.0, 2.5, 3.0);
  for (int trial = 0; trial < 100; ++trial) {
    const Mat3 R = random_rotation(rng).toRotationMatrix();
    const SymmetricEigen e = principal_inertia(rotate_inertia(moments.asDiagonal(), R));
    EXPECT_LT((e.values - moments).norm(), 1e-13);
    for (int k = 0; k < 3; ++k)  // column k of R is the axis of moment k, up to sign
      EXPECT_NEAR(std::abs(e.axes.col(k).dot(R.col(k))), 1.0, 1e-12);
    EXPECT_NEAR(e.axes.determinant(), 1.0, 1e-12);
  }
}

TEST(Composite, TwoHalvesOfABoxMakeTheWholeBox) {
  const double m = 6.0;
  const Vec3 size(1.0, 2.0, 0.5), half_size(1.0, 1.0, 0.5), offset(4, 5, 6);
  const Mat3 half = inertia_solid_box(m / 2, half_size);
  const MassProperties whole = composite_inertia(
      {{m / 2, offset + Vec3(0, -0.5, 0), half}, {m / 2, offset + Vec3(0, 0.5, 0), half}});
  EXPECT_DOUBLE_EQ(whole.mass, m);
  EXPECT_LT((whole.com - offset).norm(), 1e-14);
  EXPECT_LT((whole.inertia - inertia_solid_box(m, size)).norm(), 1e-14);
}

TEST(Composite, OfParticlesEqualsPoints) {
  std::mt19937 rng(21);
  const std::vector<PointMass> cloud = random_cloud(rng, 9);
  std::vector<MassProperties> parts;
  for (const PointMass& p : cloud) parts.push_back({p.mass, p.position, Mat3::Zero()});
  const MassProperties a = composite_inertia(parts), b = inertia_points(cloud);
  EXPECT_NEAR(a.mass, b.mass, 1e-14);
  EXPECT_LT((a.com - b.com).norm(), 1e-13);
  EXPECT_LT((a.inertia - b.inertia).norm(), 1e-12 * b.inertia.norm());
  EXPECT_THROW(composite_inertia({}), std::invalid_argument);
}

// ---- validation ----------------------------------------------------------------------------

TEST(InertiaTensorProblem, ExplainsTheTriangleInequality) {
  EXPECT_EQ(inertia_tensor_problem(Vec3(1, 1, 3).asDiagonal().toDenseMatrix()),
            "principal moments 1, 1, 3 violate A + B >= C (1 + 1 < 3 by 1)");
}

TEST(InertiaTensorProblem, RefusesEachImpossibleTensor) {
  Mat3 asymmetric = Mat3::Identity();
  asymmetric(0, 1) = 0.1;
  EXPECT_NE(inertia_tensor_problem(asymmetric).find("not symmetric"), std::string::npos);
  Mat3 infinite = Mat3::Identity();
  infinite(2, 2) = HUGE_VAL;
  EXPECT_NE(inertia_tensor_problem(infinite).find("not finite"), std::string::npos);
  const Mat3 negative = Vec3(-1, 2, 2).asDiagonal();
  EXPECT_NE(inertia_tensor_problem(negative).find("not all > 0"), std::string::npos);
  EXPECT_NE(inertia_tensor_problem(negative, InertiaRules::idealized).find("not all >= 0"),
            std::string::npos);
  // The products of inertia can make a tensor with a positive diagonal impossible.
  Mat3 products = Mat3::Identity();
  products(0, 1) = products(1, 0) = 2.0;  // eigenvalues −1, 1, 3
  EXPECT_NE(inertia_tensor_problem(products).find("not all > 0"), std::string::npos);
}

// Subnormal moments have no finite inverse: not a body's tensor, though a particle's may be that
// small. Entries near DBL_MAX make the principal moments overflow: refused, saying so.
TEST(InertiaTensorProblem, TooSmallToInvertOrTooLargeToAnalyse) {
  const Mat3 tiny = 1e-320 * Mat3::Identity();
  EXPECT_EQ(inertia_tensor_problem(tiny),
            "principal moments 9.999888672e-321, 9.999888672e-321, 9.999888672e-321 are too "
            "small for a body: the inverse tensor overflows (1/9.999888672e-321 = inf)");
  EXPECT_EQ(inertia_tensor_problem(tiny, InertiaRules::idealized), "");
  EXPECT_EQ(inertia_tensor_problem(1e-300 * Mat3::Identity()), "");
  EXPECT_EQ(inertia_tensor_problem(1e308 * Mat3::Identity(), InertiaRules::idealized),
            "the tensor is too large: its principal moments overflow (largest entry 1e+308)");
}

TEST(InertiaTensorProblem, RodsAndPointsAreIdealizedNotBodies) {
  const Mat3 rod = Vec3(0, 1, 1).asDiagonal();
  EXPECT_NE(inertia_tensor_problem(rod).find("not all > 0"), std::string::npos);
  EXPECT_EQ(inertia_tensor_problem(rod, InertiaRules::idealized), "");
  EXPECT_EQ(inertia_tensor_problem(Mat3::Zero(), InertiaRules::idealized), "");
  // A rod tensor rotated arbitrarily: its zero moment comes back as ±1e-17, zero to rounding.
  const Mat3 tilted = rotate_inertia(rod, quat_from_axis_angle(Vec3(1, 2, 3), 0.7));
  EXPECT_NE(inertia_tensor_problem(tilted).find("zero to rounding"), std::string::npos)
      << inertia_tensor_problem(tilted);
  EXPECT_EQ(inertia_tensor_problem(tilted, InertiaRules::idealized), "");
}

TEST(InertiaTensorProblem, PlanarBodiesAtEqualityPassAfterRotation) {
  // A flat plate: Izz = Ixx + Iyy exactly; rounding after a rotation must not refuse it.
  std::mt19937 rng(13);
  const Mat3 plate = inertia_solid_box(1, Vec3(1, 2, 1e-300));
  for (int trial = 0; trial < 200; ++trial)
    EXPECT_EQ(inertia_tensor_problem(rotate_inertia(plate, random_rotation(rng))), "");
  const Mat3 slightly_beyond = Vec3(1, 1, 2 * (1 + 1e-6)).asDiagonal();
  EXPECT_NE(inertia_tensor_problem(slightly_beyond).find("violate"), std::string::npos);
}

TEST(RotationProblem, AcceptsRotationsOnly) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 50; ++trial)
    EXPECT_EQ(rotation_problem(random_rotation(rng).toRotationMatrix()), "");
  EXPECT_NE(rotation_problem(2.0 * Mat3::Identity()).find("not orthonormal"), std::string::npos);
  EXPECT_NE(rotation_problem(Vec3(1, 1, -1).asDiagonal()).find("reflection"), std::string::npos);
  Mat3 nan = Mat3::Identity();
  nan(0, 0) = std::nan("");
  EXPECT_NE(rotation_problem(nan).find("not finite"), std::string::npos);
}

}  // namespace
}  // namespace rigidlab
