// Tests for engine/aba, engine/rnea, engine/crba and the kinematics of engine/articulation on
// random trees (8 to 16 links, mixed revolute, prismatic and fixed joints, random axes, origins
// and inertias, fixed and free base), each algorithm against the others or a finite difference:
//   - forward dynamics (ABA, O(n)) against M⁻¹(τ − C q̇ − g) from CRBA and RNEA, and RNEA of
//     ABA's q̈ gives back τ (to 1e-12 relative);
//   - T = ½ q̇ᵀ M q̇ against Σ ½ (m |v_com|² + ωᵀ I ω) from point velocities;
//   - Ṁ − 2C is skew-symmetric (C the Christoffel matrix ½ ∂(C q̇)/∂q̇, Ṁ by central
//     differences along q̇), for a fixed base; for a free base q̇ᵀ(Ṁ − 2C)q̇ = 0;
//   - gravity compensation: τ = g(q) from inverse dynamics holds any pose (q̈ = 0);
//   - the Jacobian against point velocities and the finite difference of the point's position,
//     and virtual forces τ = Jᵀ F.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "articulation_models.hpp"
#include "engine/articulation.hpp"

namespace rigidlab {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

struct TreeCase {
  int links;
  BaseType base;
  unsigned seed;
};
const std::vector<TreeCase> tree_cases = {{8, BaseType::fixed, 1},  {12, BaseType::fixed, 2},
                                          {16, BaseType::fixed, 3}, {8, BaseType::free, 4},
                                          {12, BaseType::free, 5},  {16, BaseType::free, 6}};

std::string label(const TreeCase& c) {
  return std::to_string(c.links) + " links, " + base_type_names[int(c.base)] + " base, seed " +
         std::to_string(c.seed);
}

VectorXd random_vector(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  VectorXd x(n);
  for (int k = 0; k < n; ++k) x[k] = u(rng);
  return x;
}

// q ⊕ h q̇ for a finite difference along the motion.
Articulation moved(const Articulation& art, double h) {
  Articulation copy = art;
  VectorXd q = art.q();
  integrate_coordinates(art.model(), q, art.v(), h);
  copy.set_state(q, art.v());
  return copy;
}

TEST(RandomTrees, AbaAgreesWithCrbaAndRnea) {
  for (const TreeCase& c : tree_cases) {
    Articulation art = test::random_tree(c.links, c.base, c.seed);
    test::randomize_state(art, c.seed + 100);
    const VectorXd tau = random_vector(art.model().nv(), c.seed + 200);
    const VectorXd qdd = art.forward_dynamics(tau);
    const MatrixXd M = art.mass_matrix();
    const VectorXd bias = art.bias_forces();
    const VectorXd reference = M.llt().solve(tau - bias);
    const double against_crba = (qdd - reference).norm() / reference.norm();
    const double rnea_residual = (art.inverse_dynamics(qdd) - tau).norm() / tau.norm();
    std::printf("  [%s] |qdd_aba - M^-1(tau - b)| / |qdd| = %.2e, |RNEA(qdd_aba) - tau| / |tau| "
                "= %.2e, cond(M) = %.1e\n",
                label(c).c_str(), against_crba, rnea_residual,
                [&] {
                  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(M);
                  return eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff();
                }());
    EXPECT_LT(against_crba, 1e-12) << label(c);
    EXPECT_LT(rnea_residual, 1e-12) << label(c);
    EXPECT_LT((M - M.transpose()).norm(), 1e-12 * M.norm()) << label(c);
  }
}

TEST(RandomTrees, KineticEnergyIsHalfQdotMQdot) {
  for (const TreeCase& c : tree_cases) {
    Articulation art = test::random_tree(c.links, c.base, c.seed);
    test::randomize_state(art, c.seed + 300);
    const VectorXd& v = art.v();
    const double from_m = 0.5 * v.dot(art.mass_matrix() * v);
    double from_points = 0.0;  // Σ ½ m |v_com|² + ½ ωᵀ (R I_c Rᵀ) ω
    for (int k = 0; k < art.model().link_count(); ++k) {
      const LinkSpec& spec = art.model().links()[k].spec;
      const Vec3 v_com = art.point_velocity(k, spec.com), w = art.angular_velocity(k);
      const Mat3 R = art.link_rotation(k);
      from_points += 0.5 * spec.mass * v_com.squaredNorm() +
                     0.5 * w.dot(R * spec.inertia * R.transpose() * w);
    }
    EXPECT_NEAR(art.kinetic_energy(), from_m, 1e-12 * from_m) << label(c);
    EXPECT_NEAR(from_points, from_m, 1e-12 * from_m) << label(c);
  }
}

// C(q, q̇) as the Christoffel matrix ½ ∂(C q̇)/∂q̇: C q̇ + g is quadratic in q̇ plus a constant,
// so the central difference in q̇ is exact up to rounding.
MatrixXd christoffel_matrix(const Articulation& art) {
  const int n = art.model().nv();
  MatrixXd C(n, n);
  const double h = 1e-3;
  for (int j = 0; j < n; ++j) {
    Articulation plus = art, minus = art;
    VectorXd v = art.v();
    v[j] += h;
    plus.set_state(art.q(), v);
    v[j] -= 2 * h;
    minus.set_state(art.q(), v);
    C.col(j) = 0.5 * (plus.bias_forces() - minus.bias_forces()) / (2 * h);
  }
  return C;
}

TEST(RandomTrees, MdotMinusTwoCIsSkewSymmetric) {
  for (const TreeCase& c : tree_cases) {
    Articulation art = test::random_tree(c.links, c.base, c.seed);
    test::randomize_state(art, c.seed + 400);
    const double h = 1e-5;
    const MatrixXd Mdot = (moved(art, h).mass_matrix() - moved(art, -h).mass_matrix()) / (2 * h);
    const MatrixXd N = Mdot - 2.0 * christoffel_matrix(art);
    const VectorXd& v = art.v();
    const double quadratic = std::abs(v.dot(N * v)) / (N.norm() * v.squaredNorm());
    const double symmetric_part = (N + N.transpose()).norm() / N.norm();
    std::printf("  [%s] |N + N^T| / |N| = %.2e, |qd^T N qd| / (|N| |qd|^2) = %.2e\n",
                label(c).c_str(), symmetric_part, quadratic);
    EXPECT_LT(quadratic, 1e-8) << label(c);
    if (c.base == BaseType::fixed) EXPECT_LT(symmetric_part, 1e-8) << label(c);
  }
}

TEST(RandomTrees, GravityCompensationHoldsAnyPose) {
  for (const TreeCase& c : tree_cases) {
    Articulation art = test::random_tree(c.links, c.base, c.seed);
    test::randomize_state(art, c.seed + 500, 0.0);  // at rest
    const VectorXd g = art.bias_forces();
    const double falling = art.forward_dynamics(VectorXd::Zero(art.model().nv())).norm();
    const double held = art.forward_dynamics(g).norm();
    std::printf("  [%s] |qdd| unheld %.3g, held by tau = g(q): %.2e\n", label(c).c_str(),
                falling, held);
    EXPECT_LT(held, 1e-12 * falling) << label(c);
    art.set_torques(g);  // and it stays there
    art.set_integrator(Integrator::rk4);
    const VectorXd q0 = art.q();
    art.step(1e-3, 1000);
    EXPECT_LT((art.q() - q0).norm(), 1e-11) << label(c);
  }
}

TEST(RandomTrees, JacobianMatchesPointVelocitiesAndFiniteDifferences) {
  for (const TreeCase& c : tree_cases) {
    Articulation art = test::random_tree(c.links, c.base, c.seed);
    test::randomize_state(art, c.seed + 600);
    const int link = art.model().link_count() - 1;
    const Vec3 point(0.3, -0.2, 0.4);
    const MatrixXd J = art.jacobian(link, point);
    const VectorXd velocity = J * art.v();
    EXPECT_LT((velocity.head<3>() - art.point_velocity(link, point)).norm(), 1e-12) << label(c);
    EXPECT_LT((velocity.tail<3>() - art.angular_velocity(link)).norm(), 1e-12) << label(c);
    const double h = 1e-6;
    const Vec3 difference =
        (moved(art, h).point_position(link, point) - moved(art, -h).point_position(link, point)) /
        (2 * h);
    EXPECT_LT((difference - velocity.head<3>()).norm(), 1e-8) << label(c);
    const Vec3 force(1.0, -2.0, 0.5), torque(0.3, 0.1, -0.7);
    VectorXd wrench(6);
    wrench << force, torque;
    EXPECT_LT((art.virtual_force(link, point, force, torque) - J.transpose() * wrench).norm(),
              1e-12)
        << label(c);
  }
}

}  // namespace
}  // namespace rigidlab
