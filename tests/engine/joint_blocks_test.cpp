// engine/joint_blocks.*: a joint's block of equality rows, stored compactly (point rows as
// lever arms, angular rows as their axis, K⁻¹ as a packed triangle), updated as one.
//
// The reference is written here, independent of the compact form: the bodies as one 12-vector
// of velocities (v_a, ω_a, v_b, ω_b), each row as a dense 12-vector J_i, W = diag(m_a⁻¹ 1,
// I_a⁻¹, m_b⁻¹ 1, I_b⁻¹), K = J W Jᵀ inverted by Eigen's LU. One rigid update must then give
// J v' + bias = 0 exactly (the block's defining property), with λ = −K⁻¹ (J v + bias); a
// soft (push) update Δλ = −K⁻¹ (s J v + bias) − g λ (Box2D v3's soft form, s = mass_scale,
// g = impulse_scale).
#include "engine/joint_blocks.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

namespace rigidlab {
namespace {

using Vector12 = Eigen::Matrix<double, 12, 1>;
using Dense = Eigen::MatrixXd;

std::mt19937 rng(20261124);
double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
Vec3 random_vec() { return Vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)); }

SolverBody random_body() {
  SolverBody s;
  s.velocity = random_vec();
  s.angular_velocity = random_vec();
  s.inverse_mass = uniform(0.2, 2.0);
  const Mat3 m = Mat3::Random();
  s.inverse_inertia = m * m.transpose() + 0.5 * Mat3::Identity();  // symmetric positive definite
  return s;
}

Eigen::Matrix<double, 1, 12> dense_row(const Jacobian& j) {
  Eigen::Matrix<double, 1, 12> r;
  r << -j.linear.transpose(), -j.angular_a.transpose(), j.linear.transpose(),
      j.angular_b.transpose();
  return r;
}

Vector12 state(const SolverBody& a, const SolverBody& b) {
  Vector12 v;
  v << a.velocity, a.angular_velocity, b.velocity, b.angular_velocity;
  return v;
}

Eigen::Matrix<double, 12, 12> dense_w(const SolverBody& a, const SolverBody& b) {
  Eigen::Matrix<double, 12, 12> w = Eigen::Matrix<double, 12, 12>::Zero();
  w.block<3, 3>(0, 0) = a.inverse_mass * Mat3::Identity();
  w.block<3, 3>(3, 3) = a.inverse_inertia;
  w.block<3, 3>(6, 6) = b.inverse_mass * Mat3::Identity();
  w.block<3, 3>(9, 9) = b.inverse_inertia;
  return w;
}

// The row kinds a joint writes: 3 point rows along the world axes (stored as lever arms),
// angular rows (stored as an axis) and general rows (stored whole).
enum class Shape { hinge, ball, general, point_then_general };

std::vector<Jacobian> rows_of(Shape shape, int size) {
  std::vector<Jacobian> rows;
  const Vec3 r_a = random_vec(), r_b = random_vec();
  if (shape != Shape::general)
    for (int k = 0; k < 3; ++k) rows.push_back(point_jacobian(Vec3::Unit(k), r_a, r_b));
  while (static_cast<int>(rows.size()) < size) {
    if (shape == Shape::hinge)
      rows.push_back(angular_jacobian(random_vec().normalized()));
    else
      rows.push_back({random_vec(), random_vec(), random_vec()});
  }
  return rows;
}

struct Case {
  Shape shape;
  int size;
};

const Case cases[] = {{Shape::ball, 3},    {Shape::hinge, 5},  {Shape::hinge, 6},
                      {Shape::general, 2}, {Shape::general, 4}, {Shape::general, 6},
                      {Shape::point_then_general, 4}, {Shape::point_then_general, 6}};

TEST(JointBlocks, OneRigidUpdateMeetsEveryRowOfTheBlockAsADenseSolveDoes) {
  for (const Case& c : cases)
    for (int trial = 0; trial < 20; ++trial) {
      SolverBody set[2] = {random_body(), random_body()};
      const std::vector<Jacobian> rows = rows_of(c.shape, c.size);
      std::vector<double> bias(c.size), push_bias(c.size, 0.0);
      for (double& x : bias) x = uniform(-1, 1);

      Dense j(c.size, 12);
      for (int i = 0; i < c.size; ++i) j.row(i) = dense_row(rows[i]);
      const Eigen::Matrix<double, 12, 12> w = dense_w(set[0], set[1]);
      const Vector12 before = state(set[0], set[1]);
      const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(bias.data(), c.size);
      const Eigen::VectorXd lambda =
          -(j * w * j.transpose()).partialPivLu().solve(j * before + b);
      const Vector12 expected = before + w * j.transpose() * lambda;

      JointBlocks blocks;
      const std::uint32_t k = blocks.add(0, 1, rows.data(), c.size, set[0], set[1], bias.data(),
                                         push_bias.data(), rigid_softness);
      ASSERT_NE(k, JointBlocks::none);
      const double largest = blocks.solve(k, set, false);
      EXPECT_NEAR(largest, (j * before + b).cwiseAbs().maxCoeff(), 1e-12);

      const Vector12 after = state(set[0], set[1]);
      const double scale = 1.0 + lambda.cwiseAbs().maxCoeff();
      EXPECT_LT((j * after + b).cwiseAbs().maxCoeff(), 1e-11 * scale)
          << "shape " << static_cast<int>(c.shape) << " size " << c.size;
      EXPECT_LT((after - expected).cwiseAbs().maxCoeff(), 1e-11 * scale);
      for (int i = 0; i < c.size; ++i) EXPECT_NEAR(blocks.impulse(k, i), lambda[i], 1e-10 * scale);
    }
}

TEST(JointBlocks, ASoftUpdateFollowsBox2dsSoftFormOnThePushVelocities) {
  for (const Case& c : cases) {
    SolverBody set[2] = {random_body(), random_body()};
    const std::vector<Jacobian> rows = rows_of(c.shape, c.size);
    std::vector<double> bias(c.size, 0.0), push_bias(c.size);
    for (double& x : push_bias) x = uniform(-1, 1);
    const Softness soft = make_soft(30.0, 1.0, 1.0 / 240.0);
    ASSERT_LT(soft.mass_scale, 1.0);
    ASSERT_GT(soft.impulse_scale, 0.0);

    JointBlocks blocks;
    const std::uint32_t k = blocks.add(0, 1, rows.data(), c.size, set[0], set[1], bias.data(),
                                       push_bias.data(), soft);
    ASSERT_NE(k, JointBlocks::none);
    Dense j(c.size, 12);
    for (int i = 0; i < c.size; ++i) j.row(i) = dense_row(rows[i]);
    const Eigen::Matrix<double, 12, 12> w = dense_w(set[0], set[1]);
    const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(push_bias.data(), c.size);
    const auto lu = (j * w * j.transpose()).partialPivLu();

    // Two updates: the second has λ ≠ 0, so the −g λ term is exercised.
    Eigen::VectorXd total = Eigen::VectorXd::Zero(c.size);
    for (int round = 0; round < 2; ++round) {
      const Vector12 before = state(set[0], set[1]);
      const Eigen::VectorXd change =
          -lu.solve(soft.mass_scale * (j * before) + b) - soft.impulse_scale * total;
      total += change;
      const Vector12 expected = before + w * j.transpose() * change;
      blocks.solve(k, set, true);
      const double scale = 1.0 + total.cwiseAbs().maxCoeff();
      EXPECT_LT((state(set[0], set[1]) - expected).cwiseAbs().maxCoeff(), 1e-11 * scale);
      for (int i = 0; i < c.size; ++i) {
        EXPECT_NEAR(blocks.push_impulse(k, i), total[i], 1e-10 * scale);
        EXPECT_EQ(blocks.impulse(k, i), 0.0);  // the velocity impulses are not touched
      }
    }
  }
}

TEST(JointBlocks, RefusesBlocksWhoseRowsCannotBeSolvedTogether) {
  const SolverBody a = random_body(), b = random_body();
  const double zero[6] = {};
  JointBlocks blocks;
  // Two rows asking the same of the bodies: K is singular.
  const Jacobian same = {random_vec(), random_vec(), random_vec()};
  const Jacobian twice[2] = {same, same};
  EXPECT_EQ(blocks.add(0, 1, twice, 2, a, b, zero, zero, rigid_softness), JointBlocks::none);
  // A row neither body can move along (both static).
  SolverBody fixed;
  const std::vector<Jacobian> hinge = rows_of(Shape::hinge, 5);
  EXPECT_EQ(blocks.add(0, 1, hinge.data(), 5, fixed, fixed, zero, zero, rigid_softness),
            JointBlocks::none);
  // Sizes outside 2..max_size.
  EXPECT_EQ(blocks.add(0, 1, hinge.data(), 1, a, b, zero, zero, rigid_softness), JointBlocks::none);
  EXPECT_EQ(blocks.size(), 0u);
  EXPECT_NE(blocks.add(0, 1, hinge.data(), 5, a, b, zero, zero, rigid_softness), JointBlocks::none);
  EXPECT_EQ(blocks.size(), 1u);
}

}  // namespace
}  // namespace rigidlab
