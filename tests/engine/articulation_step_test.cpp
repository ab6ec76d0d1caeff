// Tests for engine/articulation_step (the integrators over (q, q̇)) against conservation laws
// and closed forms:
//   - a frictionless 5-link pendulum (released from up to 43°) under rk4 at 1 ms keeps its
//     energy to 1e-8 relative over 10 s, and the error falls as dt⁴;
//   - the double pendulum of point masses (m = L = 1, from rest at θ₁ = 120°, θ₂ = −30° from
//     the downward vertical, g = 9.80665, potential zero at the pivot) has
//     E = g (0.5 + 0.5 − cos 30°) = 1.31384 J and keeps it (to 1e-7 over 10 s at 1 ms: it
//     swings chaotically and fast, and RK4's error grows with the speed);
//   - a free-floating tree without gravity keeps its linear and angular momentum to 1e-12 per
//     rk4 step and its centre of mass moves on a straight line at constant speed;
//   - a PD controller (document 000 "PD controller") evaluated at every RK4 stage: the joint
//     follows the damped oscillator's closed form, and the error falls as dt⁴.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "articulation_models.hpp"
#include "engine/articulation.hpp"

namespace rigidlab {
namespace {

using Eigen::VectorXd;

constexpr double pi = 3.14159265358979323846;

// max |E − E0| / |E0| over 10 s of the 5-link rod pendulum under rk4 at step dt, released
// from rest at `pose` (rad).
double five_link_drift(double dt, const VectorXd& pose) {
  Articulation art = test::rod_chain(5);
  art.set_integrator(Integrator::rk4);
  art.set_state(pose, VectorXd::Zero(5));
  const double e0 = art.energy();
  double worst = 0.0;
  const int steps = static_cast<int>(std::lround(10.0 / dt));
  for (int step = 0; step < steps; ++step) {
    art.step(dt);
    worst = std::max(worst, std::abs(art.energy() - e0));
  }
  return worst / std::abs(e0);
}

TEST(EnergyConservation, FiveLinkPendulumUnderRk4) {
  VectorXd pose(5);
  pose << 0.75, -0.3, 0.5, 0.2, -0.35;
  const double at_1ms = five_link_drift(1e-3, pose), at_2ms = five_link_drift(2e-3, pose);
  std::printf("  5-link pendulum, rk4, 10 s: max |E - E0| / |E0| = %.2e at 1 ms, %.2e at 2 ms\n",
              at_1ms, at_2ms);
  EXPECT_LT(at_1ms, 1e-8);
  EXPECT_GT(std::log2(at_2ms / at_1ms), 3.5);  // RK4's energy error is O(dt⁴)
}

TEST(EnergyConservation, PointMassDoublePendulum) {
  Articulation art = test::point_double_pendulum();
  const double theta1 = 120.0 * pi / 180.0, theta2 = -30.0 * pi / 180.0;
  VectorXd q(2);
  q << theta1, theta2 - theta1;  // the second joint measures from the first rod
  art.set_state(q, VectorXd::Zero(2));
  const double g = 9.80665, e_closed = g * (0.5 + 0.5 - std::cos(pi / 6));
  EXPECT_NEAR(art.energy(), e_closed, 1e-14);
  EXPECT_NEAR(art.energy(), 1.31384, 5e-6);
  EXPECT_EQ(art.kinetic_energy(), 0.0);
  // The masses sit where the angles say: (sin θ₁, −cos θ₁) and that plus (sin θ₂, −cos θ₂).
  const Vec3 m1(std::sin(theta1), -std::cos(theta1), 0);
  const Vec3 m2 = m1 + Vec3(std::sin(theta2), -std::cos(theta2), 0);
  EXPECT_LT((art.point_position(0, Vec3(0, -1, 0)) - m1).norm(), 1e-15);
  EXPECT_LT((art.point_position(1, Vec3(0, -1, 0)) - m2).norm(), 1e-15);
  art.set_integrator(Integrator::rk4);
  double worst = 0.0;
  for (int step = 0; step < 10000; ++step) {
    art.step(1e-3);
    worst = std::max(worst, std::abs(art.energy() - e_closed));
  }
  std::printf("  double pendulum, rk4, 1 ms, 10 s: E = %.6f J, max |E - E0| / E0 = %.2e\n",
              e_closed, worst / e_closed);
  EXPECT_LT(worst, 1e-7 * e_closed);
}

TEST(MomentumConservation, FreeFloatingTreeWithoutGravity) {
  Articulation art = test::random_tree(10, BaseType::free, 11);
  art.set_gravity(Vec3::Zero());
  art.set_integrator(Integrator::rk4);
  test::randomize_state(art, 12);
  Vec3 p0, l0, com0, p, l, com;
  art.momentum(p0, l0);
  const double mass = art.center_of_mass(com0);
  const Vec3 com_velocity = p0 / mass;
  double worst_p = 0.0, worst_l = 0.0, worst_line = 0.0;
  Vec3 p_previous = p0, l_previous = l0;
  const double dt = 1e-3;
  for (int step = 1; step <= 2000; ++step) {
    art.step(dt);
    art.momentum(p, l);
    art.center_of_mass(com);
    worst_p = std::max(worst_p, (p - p_previous).norm() / p0.norm());
    worst_l = std::max(worst_l, (l - l_previous).norm() / l0.norm());
    worst_line = std::max(worst_line, (com - (com0 + step * dt * com_velocity)).norm());
    p_previous = p;
    l_previous = l;
  }
  std::printf("  free-floating 10-link tree, rk4, 1 ms, 2 s: per step |dP|/|P| <= %.2e, "
              "|dL|/|L| <= %.2e; COM off its line by <= %.2e m\n",
              worst_p, worst_l, worst_line);
  EXPECT_LT(worst_p, 1e-12);
  EXPECT_LT(worst_l, 1e-12);
  EXPECT_LT(worst_line, 1e-10);
}

// A link of inertia I about its revolute joint under τ = kp (θd − θ) + kv (θ̇d − θ̇) with θ̇d = 0
// and no gravity: I θ̈ + kv θ̇ + kp θ = kp θd, underdamped for kv² < 4 I kp:
//   θ(t) = θd + (θ0 − θd) e^{−ζt} (cos ωt + (ζ/ω) sin ωt),  ζ = kv / (2I), ω = √(kp/I − ζ²).
double pd_error(double dt) {
  Articulation art;
  art.set_gravity(Vec3::Zero());
  art.set_integrator(Integrator::rk4);
  LinkSpec spec;
  spec.inertia = Vec3(1, 1, 2).asDiagonal();  // I = 2 about z
  art.add_link(spec);
  const double kp = 20.0, kv = 3.0, target = 1.0, inertia = 2.0;
  art.add_control([&art, kp, kv, target](double, VectorXd& tau) {
    tau[0] += kp * (target - art.q()[0]) + kv * (0.0 - art.v()[0]);
  });
  const double duration = 2.0;
  art.step(dt, static_cast<int>(std::lround(duration / dt)));
  const double zeta = kv / (2 * inertia), omega = std::sqrt(kp / inertia - zeta * zeta);
  const double exact = target + (0.0 - target) * std::exp(-zeta * duration) *
                                    (std::cos(omega * duration) +
                                     zeta / omega * std::sin(omega * duration));
  return std::abs(art.q()[0] - exact);
}

TEST(Controls, PdControllerFollowsTheClosedFormAtEveryStage) {
  EXPECT_LT(pd_error(1e-3), 1e-11);
  // Fourth order only if the control sees each stage's state: one evaluation per step would
  // make the torque lag and the error first order.
  EXPECT_NEAR(std::log2(pd_error(0.02) / pd_error(0.01)), 4.0, 0.2);
}

}  // namespace
}  // namespace rigidlab
