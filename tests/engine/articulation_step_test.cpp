// Tests for engine/articulation_step (the integrators over (q, q̇)) against conservation laws
// and closed forms:
//   - a frictionless 5-link pendulum (released from up to 43°) under rk4 at 1 ms keeps its
//     energy to 1e-8 relative over 10 s, and the error falls as dt⁴;
//   - the double pendulum of point masses (m = L = 1, from rest at θ₁ = 120°, θ₂ = −30° from
//     the downward vertical, g = 9.80665, potential zero at the pivot) has
//     E = g (0.5 + 0.5 − cos 30°) = 1.31384 J and keeps it: over 10 s its energy error is
//     RK4's own, the same (to 1e-3 relative) as that of a textbook RK4 on the pendulum's
//     Lagrange equations, 4.5e-8 at 1 ms, and falls as dt⁴ (2.9e-9 at 0.5 ms); its angles
//     follow that textbook solution to 1e-9 rad over the first 2 s;
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

// The point-mass double pendulum (m₁ = m₂ = 1 kg, L₁ = L₂ = 1 m) by its Lagrange equations in
// absolute angles from the downward vertical (e.g. Goldstein, "Classical Mechanics", 1.4 and
// problem 1.8; written out in any text on the double pendulum), Δ = θ₁ − θ₂:
//   θ̈₁ = (−3g sin θ₁ − g sin(θ₁ − 2θ₂) − 2 sin Δ (ω₂² + ω₁² cos Δ)) / (3 − cos 2Δ)
//   θ̈₂ = 2 sin Δ (2ω₁² + 2g cos θ₁ + ω₂² cos Δ) / (3 − cos 2Δ)
//   E = ½ω₁² + ½(ω₁² + ω₂² + 2ω₁ω₂ cos Δ) − g (2 cos θ₁ + cos θ₂)
// integrated by a textbook RK4 written here (003 "Fourth-Order Runge-Kutta"): independent of
// the engine's model, dynamics and integration core.
struct TextbookDoublePendulum {
  static constexpr double g = 9.80665;
  double y[4];  // θ₁, θ₂, ω₁, ω₂
  static void slope(const double* y, double* d) {
    const double t1 = y[0], t2 = y[1], w1 = y[2], w2 = y[3], delta = t1 - t2;
    const double den = 3.0 - std::cos(2.0 * delta);
    d[0] = w1;
    d[1] = w2;
    d[2] = (-3.0 * g * std::sin(t1) - g * std::sin(t1 - 2.0 * t2) -
            2.0 * std::sin(delta) * (w2 * w2 + w1 * w1 * std::cos(delta))) / den;
    d[3] = 2.0 * std::sin(delta) * (2.0 * w1 * w1 + 2.0 * g * std::cos(t1) +
                                    w2 * w2 * std::cos(delta)) / den;
  }
  double energy() const {
    const double t1 = y[0], t2 = y[1], w1 = y[2], w2 = y[3];
    return 0.5 * w1 * w1 + 0.5 * (w1 * w1 + w2 * w2 + 2.0 * w1 * w2 * std::cos(t1 - t2)) -
           g * (2.0 * std::cos(t1) + std::cos(t2));
  }
  void step(double h) {
    double k[4][4], stage[4];
    slope(y, k[0]);
    for (int i = 0; i < 4; ++i) stage[i] = y[i] + 0.5 * h * k[0][i];
    slope(stage, k[1]);
    for (int i = 0; i < 4; ++i) stage[i] = y[i] + 0.5 * h * k[1][i];
    slope(stage, k[2]);
    for (int i = 0; i < 4; ++i) stage[i] = y[i] + h * k[2][i];
    slope(stage, k[3]);
    for (int i = 0; i < 4; ++i) y[i] += h / 6.0 * (k[0][i] + 2.0 * k[1][i] + 2.0 * k[2][i] + k[3][i]);
  }
};

constexpr double theta1_0 = 120.0 * pi / 180.0, theta2_0 = -30.0 * pi / 180.0;

Articulation released_double_pendulum() {
  Articulation art = test::point_double_pendulum();
  VectorXd q(2);
  q << theta1_0, theta2_0 - theta1_0;  // the second joint measures from the first rod
  art.set_state(q, VectorXd::Zero(2));
  art.set_integrator(Integrator::rk4);
  return art;
}

// max |E − E0| / E0 over 10 s at step h: the engine's, and the textbook RK4's.
struct DoublePendulumDrift {
  double engine, textbook;
};
DoublePendulumDrift double_pendulum_drift(double h) {
  Articulation art = released_double_pendulum();
  TextbookDoublePendulum book{{theta1_0, theta2_0, 0.0, 0.0}};
  const double e0 = art.energy(), book_e0 = book.energy();
  DoublePendulumDrift drift{0.0, 0.0};
  for (long step = 0; step < std::lround(10.0 / h); ++step) {
    art.step(h);
    book.step(h);
    drift.engine = std::max(drift.engine, std::abs(art.energy() - e0) / e0);
    drift.textbook = std::max(drift.textbook, std::abs(book.energy() - book_e0) / book_e0);
  }
  return drift;
}

TEST(EnergyConservation, PointMassDoublePendulum) {
  Articulation art = released_double_pendulum();
  const double g = 9.80665, e_closed = g * (0.5 + 0.5 - std::cos(pi / 6));
  EXPECT_NEAR(art.energy(), e_closed, 1e-14);
  EXPECT_NEAR(art.energy(), 1.31384, 5e-6);
  const TextbookDoublePendulum book{{theta1_0, theta2_0, 0.0, 0.0}};
  EXPECT_NEAR(book.energy(), e_closed, 1e-14);
  EXPECT_EQ(art.kinetic_energy(), 0.0);
  // The masses sit where the angles say: (sin θ₁, −cos θ₁) and that plus (sin θ₂, −cos θ₂).
  const Vec3 m1(std::sin(theta1_0), -std::cos(theta1_0), 0);
  const Vec3 m2 = m1 + Vec3(std::sin(theta2_0), -std::cos(theta2_0), 0);
  EXPECT_LT((art.point_position(0, Vec3(0, -1, 0)) - m1).norm(), 1e-15);
  EXPECT_LT((art.point_position(1, Vec3(0, -1, 0)) - m2).norm(), 1e-15);
}

// The energy error at 1 ms (4.5e-8) is RK4's truncation error on this fast, chaotic motion,
// not the engine's: a textbook RK4 on the Lagrange equations makes the same error to 1e-3
// relative (measured: 4.498e-8 both; 6.818e-7 both at 2 ms), and it falls as dt⁴, to 2.9e-9
// at 0.5 ms. Holding 1e-8 takes dt <= 0.69 ms (4.5e-8 (dt / 1 ms)⁴ = 1e-8).
TEST(EnergyConservation, DoublePendulumEnergyErrorIsRk4sOwn) {
  const DoublePendulumDrift at_1ms = double_pendulum_drift(1e-3);
  const DoublePendulumDrift at_half = double_pendulum_drift(5e-4);
  std::printf("  double pendulum, rk4, 10 s: max |E - E0| / E0 = %.3e at 1 ms (textbook RK4 "
              "%.3e), %.3e at 0.5 ms (textbook %.3e)\n",
              at_1ms.engine, at_1ms.textbook, at_half.engine, at_half.textbook);
  EXPECT_NEAR(at_1ms.engine / at_1ms.textbook, 1.0, 1e-3);
  EXPECT_NEAR(at_half.engine / at_half.textbook, 1.0, 1e-2);
  EXPECT_LT(at_1ms.engine, 1e-7);
  EXPECT_LT(at_half.engine, 1e-8);
  EXPECT_NEAR(std::log2(at_1ms.engine / at_half.engine), 4.0, 0.2);
}

// Same method, two formulations: the articulation's angles follow the textbook RK4 solution
// of the Lagrange equations to rounding while the motion is not yet chaotic (2 s at 1 ms).
TEST(EnergyConservation, DoublePendulumFollowsTheLagrangeEquations) {
  Articulation art = released_double_pendulum();
  TextbookDoublePendulum book{{theta1_0, theta2_0, 0.0, 0.0}};
  double worst = 0.0;
  for (int step = 0; step < 2000; ++step) {
    art.step(1e-3);
    book.step(1e-3);
    worst = std::max({worst, std::abs(art.q()[0] - book.y[0]),
                      std::abs(art.q()[0] + art.q()[1] - book.y[1])});
  }
  EXPECT_LT(worst, 1e-9);
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

// Articulation::save_state / restore_state (the live view's rewind): a free-base tree stepped
// on from a restored state follows the same motion bit for bit, held torques and time
// included; a state of another model is refused and changes nothing.
TEST(SavedState, RestoredStateStepsOnBitForBit) {
  Articulation art = test::random_tree(6, BaseType::free, 7);
  test::randomize_state(art, 11);
  art.set_integrator(Integrator::rk4);
  VectorXd tau = VectorXd::LinSpaced(art.model().nv(), -0.3, 0.4);
  art.set_torques(tau);
  ArticulationState saved;
  art.save_state(saved);
  for (int k = 0; k < 50; ++k) art.step(1e-3);
  const VectorXd q_first = art.q(), v_first = art.v();
  const double t_first = art.time();
  art.set_torques(VectorXd::Zero(art.model().nv()));  // changed after the save
  art.restore_state(saved);
  EXPECT_EQ(art.torques(), tau);
  EXPECT_EQ(art.time(), saved.time);
  for (int k = 0; k < 50; ++k) art.step(1e-3);
  EXPECT_EQ(art.q(), q_first);
  EXPECT_EQ(art.v(), v_first);
  EXPECT_EQ(art.time(), t_first);

  Articulation other = test::random_tree(4, BaseType::free, 3);
  ArticulationState foreign;
  other.save_state(foreign);
  EXPECT_THROW(art.restore_state(foreign), std::invalid_argument);
  EXPECT_EQ(art.q(), q_first);  // nothing changed
  EXPECT_EQ(art.time(), t_first);
}

}  // namespace
}  // namespace rigidlab
