// Tests for engine/math.cpp against independent facts: the defining identity of the hat
// operator, the eigen equation A·V = V·D on random symmetric matrices, and the geometric
// meaning of an axis-angle rotation.
#include "engine/math.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace rigidlab {
namespace {

TEST(Skew, TimesVectorIsCrossProduct) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int i = 0; i < 100; ++i) {
    const Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    EXPECT_LT((skew(a) * b - a.cross(b)).norm(), 1e-12);
    EXPECT_EQ(skew(a).transpose(), -skew(a));
  }
}

TEST(Solve3, SolvesRandomSystemsAndAKnownOne) {
  // A known system: x = (1, -2, 3) for this A and b = A x, worked by hand.
  Mat3 a;
  a << 2, 1, 0,
       1, 3, 1,
       0, 1, 4;
  const Vec3 x = solve3(a, Vec3(0, -2, 10));
  EXPECT_NEAR(x.x(), 1, 1e-14);
  EXPECT_NEAR(x.y(), -2, 1e-14);
  EXPECT_NEAR(x.z(), 3, 1e-14);
  // Random well-conditioned systems (identity plus a perturbation, like the integrators'
  // Jacobians I + dt(...)): the residual A x − b is at rounding level.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 1000; ++trial) {
    Mat3 m = Mat3::Identity() * (1 + 4 * std::abs(u(rng)));
    for (int i = 0; i < 9; ++i) m(i / 3, i % 3) += 0.5 * u(rng);
    const Vec3 b(u(rng), u(rng), u(rng));
    EXPECT_LT((m * solve3(m, b) - b).norm(), 1e-13 * (1 + b.norm()));
  }
}

TEST(SymmetricEigen, SatisfiesEigenEquationOnRandomMatrices) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-5, 5);
  for (int trial = 0; trial < 1000; ++trial) {
    Mat3 r;
    for (int i = 0; i < 9; ++i) r(i / 3, i % 3) = u(rng);
    const Mat3 a = 0.5 * (r + r.transpose());
    const SymmetricEigen e = symmetric_eigen(a);
    const double scale = std::max(1.0, a.norm());
    EXPECT_LT((a * e.axes - e.axes * e.values.asDiagonal()).norm(), 1e-12 * scale);
    EXPECT_LT((e.axes.transpose() * e.axes - Mat3::Identity()).norm(), 1e-12);
    EXPECT_NEAR(e.axes.determinant(), 1.0, 1e-12);
    EXPECT_LE(e.values[0], e.values[1]);
    EXPECT_LE(e.values[1], e.values[2]);
  }
}

TEST(SymmetricEigen, DiagonalMatrixGivesItsEntriesAndTheIdentity) {
  const SymmetricEigen e = symmetric_eigen(Vec3(3, 1, 2).asDiagonal());
  EXPECT_EQ(e.values, Vec3(1, 2, 3));
  Mat3 expected;
  expected << 0, 0, 1,
              1, 0, 0,
              0, 1, 0;
  EXPECT_LT((e.axes - expected).norm(), 1e-15);
}

TEST(SymmetricEigen, RepeatedEigenvaluesStillGiveAnOrthonormalBasis) {
  const SymmetricEigen e = symmetric_eigen(Mat3::Identity() * 2.5);
  EXPECT_LT((e.values - Vec3(2.5, 2.5, 2.5)).norm(), 1e-15);
  EXPECT_NEAR(e.axes.determinant(), 1.0, 1e-15);
}

TEST(AxisAngle, QuarterTurnAboutZMapsXToY) {
  const Quat q = quat_from_axis_angle(Vec3(0, 0, 5), M_PI / 2);  // axis need not be unit
  EXPECT_LT((q * Vec3::UnitX() - Vec3::UnitY()).norm(), 1e-15);
  Vec3 axis;
  double angle;
  quat_to_axis_angle(q, axis, angle);
  EXPECT_LT((axis - Vec3::UnitZ()).norm(), 1e-15);
  EXPECT_NEAR(angle, M_PI / 2, 1e-15);
}

TEST(AxisAngle, RoundTripsForAnglesUpToPi) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_real_distribution<double> angle_distribution(0.01, M_PI - 0.01);
  for (int i = 0; i < 200; ++i) {
    const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
    const double angle = angle_distribution(rng);
    Vec3 axis_back;
    double angle_back;
    quat_to_axis_angle(quat_from_axis_angle(axis, angle), axis_back, angle_back);
    EXPECT_NEAR(angle_back, angle, 1e-12);
    EXPECT_LT((axis_back - axis).norm(), 1e-12);
  }
}

TEST(AxisAngle, ZeroOrNonFiniteAxisIsRefused) {
  EXPECT_THROW(quat_from_axis_angle(Vec3::Zero(), 1.0), std::invalid_argument);
  EXPECT_THROW(quat_from_axis_angle(Vec3(NAN, 0, 0), 1.0), std::invalid_argument);
  EXPECT_THROW(quat_from_axis_angle(Vec3(1, 0, 0), INFINITY), std::invalid_argument);
}

// |(a, a, 0)| = √2 a and its direction (1, 1, 0)/√2 at every scale, including those where
// a² overflows (1e300) or underflows (1e-170, and the subnormal 1e-320 with no square at all).
TEST(StableNorm, HugeAndTinyVectorsKeepTheirLengthAndDirection) {
  const double root2 = std::sqrt(2.0);
  for (double a : {1.0, 1e300, 1e-170, 1e-300}) {
    const Vec3 v(a, a, 0);
    EXPECT_NEAR(stable_norm(v) / a, root2, 1e-15) << a;
    EXPECT_LT((unit(v) - Vec3(1, 1, 0) / root2).norm(), 1e-15) << a;
    const Quat q(a, 0, -a, 0);
    EXPECT_NEAR(stable_norm(q) / a, root2, 1e-15) << a;
    EXPECT_LT((unit(q).coeffs() - Eigen::Vector4d(0, -1, 0, 1) / root2).norm(), 1e-15) << a;
  }
  EXPECT_EQ(stable_norm(Vec3(1e-320, 0, 0)), 1e-320);  // a subnormal: its square is 0
  EXPECT_EQ(unit(Vec3(0, 0, -1e-320)), Vec3(0, 0, -1));
  EXPECT_EQ(stable_norm(Vec3(3, 4, 0)), 5.0);
  EXPECT_EQ(stable_norm(Vec3(1e308, 1e308, 0)), std::sqrt(2.0) * 1e308);
  EXPECT_EQ(stable_norm(Vec3::Zero()), 0.0);
  EXPECT_TRUE(std::isinf(stable_norm(Vec3(INFINITY, 0, 0))));
}

TEST(StableNorm, ZeroMeansEveryComponentZero) {
  EXPECT_TRUE(is_zero(Vec3::Zero()));
  EXPECT_FALSE(is_zero(Vec3(0, 1e-320, 0)));
  EXPECT_TRUE(is_zero(Quat(0, 0, 0, 0)));
  EXPECT_FALSE(is_zero(Quat(0, 0, 0, -1e-320)));
}

// A quarter turn about (1, 1, 0) given with a huge or tiny axis maps z to (1, -1, 0)/√2.
TEST(AxisAngle, HugeAndTinyAxesGiveTheSameUnitRotation) {
  for (double a : {1e300, 1e-320}) {
    const Quat q = quat_from_axis_angle(Vec3(a, a, 0), M_PI / 2);
    EXPECT_NEAR(q.norm(), 1.0, 1e-15) << a;
    EXPECT_LT((q * Vec3::UnitZ() - Vec3(1, -1, 0) / std::sqrt(2.0)).norm(), 1e-15) << a;
  }
}

TEST(Finite, DetectsNanAndInfinity) {
  EXPECT_TRUE(is_finite(Vec3(1, 2, 3)));
  EXPECT_FALSE(is_finite(Vec3(1, NAN, 3)));
  EXPECT_FALSE(is_finite(Mat3(Mat3::Identity() * INFINITY)));
  EXPECT_FALSE(is_finite(Quat(NAN, 0, 0, 0)));
}

TEST(Asymmetry, ZeroForSymmetricAndLargestDifferenceOtherwise) {
  Mat3 m = Mat3::Identity();
  EXPECT_EQ(asymmetry(m), 0.0);
  m(0, 2) = 0.5;
  EXPECT_EQ(asymmetry(m), 0.5);
}

}  // namespace
}  // namespace rigidlab
