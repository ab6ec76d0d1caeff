// engine/joint.hpp in a world, against references independent of the joint code: the large-
// amplitude pendulum period 4√(L/g)·K(sin(θ₀/2)) (K by the arithmetic-geometric mean; the
// values of LESSONS.md "pendulum"), energy conservation of a hanging chain, a free hinge's
// constant rate, the continuous damped oscillator (closed form, and RK4 for the oscillator
// step), and document 000's PD responses.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "engine/joint.hpp"
#include "engine/world.hpp"
#include "tests/engine/elliptic.hpp"

namespace rigidlab {
namespace {

const SolverKind both_solvers[] = {SolverKind::soft_step, SolverKind::sequential_impulses};
std::string name(SolverKind s) { return solver_names[static_cast<int>(s)]; }

using test::elliptic_k;

Joint& add_joint(World& w, const JointDef& def) {
  const Body& a = w.store().get(def.a);
  const Body* b = def.b.valid() ? &w.store().get(def.b) : nullptr;
  return static_cast<Joint&>(w.add_constraint(std::make_unique<Joint>(def, a, b)));
}

TEST(Pendulum, EllipticIntegralGivesTheLessonValues) {
  const double g = 9.81, L = 1.0;
  const double want[] = {2.009893, 2.040990, 2.152875, 2.281886};
  const double degrees[] = {10, 30, 60, 80};
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR(4.0 * std::sqrt(L / g) * elliptic_k(std::sin(degrees[i] * M_PI / 360.0)),
                want[i], 5e-7);
}

// A bob at the end of a 1 m arm about the z axis, released at rest at θ₀, through a hinge
// (the bob a sphere: a physical pendulum with the equivalent length L + I_c/(mL)) or a rigid
// distance rod (a point mass: the bob's turning is free).
TEST(Pendulum, PeriodMatchesTheEllipticIntegralWithBothSolvers) {
  const double g = 9.81, L = 1.0, dt = 1.0 / 60.0;
  for (SolverKind solver : both_solvers)
    for (JointKind type : {JointKind::hinge, JointKind::distance})
      for (double degrees : {10.0, 30.0, 60.0, 80.0}) {
        World w;
        w.set_solver(solver);
        w.set_substeps(4);
        Body bob = make_sphere_body(1.0, 0.05);
        const double theta = degrees * M_PI / 180.0;
        bob.position = Vec3(L * std::sin(theta), -L * std::cos(theta), 0.0);
        JointDef def;
        def.type = type;
        def.a = w.add(bob);
        def.anchor = Vec3::Zero();   // hinge: the pivot
        def.axis = Vec3::UnitZ();
        def.b_point = Vec3::Zero();  // distance: the pivot, a world point
        Joint& j = add_joint(w, def);
        // The arm's angle from the vertical (the hinge's angle counts from creation).
        auto arm_angle = [&w] {
          const Vec3 p = w.bodies()[0].position;
          return std::atan2(p.x(), -p.y());
        };
        std::vector<double> crossings;
        double previous = arm_angle();
        for (int step = 0; step < 2000 && crossings.size() < 9; ++step) {
          w.step(dt);
          const double angle = arm_angle();
          if ((previous < 0.0) != (angle < 0.0))
            crossings.push_back(w.time() - dt * angle / (angle - previous));
          previous = angle;
        }
        ASSERT_EQ(crossings.size(), 9u);
        const double period = (crossings.back() - crossings.front()) / 4.0;
        const double inertia = 0.4 * 0.05 * 0.05;  // solid sphere, m = 1
        const double length = type == JointKind::hinge ? L + inertia / L : L;
        const double want = 4.0 * std::sqrt(length / g) * elliptic_k(std::sin(theta / 2.0));
        std::printf("period %s %s %2.0f°: %.6f s, closed form %.6f s (%+.3f %%)\n",
                    name(solver).c_str(), joint_kind_names[static_cast<int>(type)], degrees,
                    period, want, 100.0 * (period / want - 1.0));
        EXPECT_NEAR(period / want, 1.0, 0.002)
            << name(solver) << " " << joint_kind_names[static_cast<int>(type)] << " " << degrees
            << "°: measured " << period << " s, closed form " << want << " s";
        double position = 0.0, angle = 0.0;
        j.error(w.bodies()[0], nullptr, position, angle);
        EXPECT_LT(position, 1e-3) << name(solver);
      }
}

// Issue 14's chain: 10 boxes 0.1 × 0.5 × 0.1 m of 1 kg joined end to end by ball joints,
// hanging from the world, released at 45°; 10 s at 60 Hz with the defaults.
void run_chain(SolverKind solver, double& worst, double& rise, double& e0) {
  World w;
  w.set_solver(solver);
  const Vec3 down = Vec3(std::sin(M_PI / 4), -std::cos(M_PI / 4), 0.0);
  const Quat tilt(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitZ()));
  std::vector<Joint*> joints;
  BodyId previous = no_body_id;
  for (int i = 0; i < 10; ++i) {
    Body link = make_box_body(1.0, Vec3(0.1, 0.5, 0.1));
    link.position = (0.5 * i + 0.25) * down;
    link.orientation = tilt;
    JointDef def;
    def.type = JointKind::ball;
    def.a = w.add(link);
    def.b = previous;
    def.anchor = 0.5 * i * down;
    joints.push_back(&add_joint(w, def));
    previous = def.a;
  }
  e0 = w.energy();
  worst = 0.0;
  double highest = e0;
  for (int step = 0; step < 600; ++step) {
    w.step(1.0 / 60.0);
    for (std::size_t i = 0; i < joints.size(); ++i) {
      const Body& a = w.bodies()[i];
      const Body* b = i == 0 ? nullptr : &w.bodies()[i - 1];
      double position = 0.0, angle = 0.0;
      joints[i]->error(a, b, position, angle);
      worst = std::max(worst, position);
    }
    highest = std::max(highest, w.energy());
  }
  std::printf("chain %s: worst joint error %.3g m, energy %.6g -> highest %.6g (start %.6g)\n",
              name(solver).c_str(), worst, w.energy(), highest, e0);
  rise = highest - e0;
}

TEST(Chain, BallJointChainHoldsAndKeepsItsEnergy) {
  double worst = 0.0, rise = 0.0, e0 = 0.0;
  run_chain(SolverKind::soft_step, worst, rise, e0);
  // The 1 mm: 0.058 mm with the joint trees' exact solve (engine/joint_tree.hpp), now
  // that the joined boxes, which touch end to end at every joint, no longer collide (a joint's
  // `collide` is off by default); with their contacts fighting the joints it was 3.1 mm.
  EXPECT_LT(worst, 1e-3);
  // Energy is measured from its size: the chain's potential energy is negative (below the
  // pivot), so "rising by 1 %" is 1 % of the kinetic energy it can reach, |E0|.
  EXPECT_LE(rise, 0.01 * std::abs(e0));
}

// The same chain with sequential_impulses (document 000's solver: its joints are swept row
// block by row block, no exact tree solve). Measured: 1.53 mm (2.75 mm before its position
// pass corrected each joint's point block as one, engine/solver.cpp correct_block); the
// issue's 1 mm is soft_step's target and is NOT met here: what is left is the velocity
// sweeps' convergence along the chain (0.75 mm at 50 iterations). Energy rise 0.59 % of |E0|.
TEST(Chain, SequentialImpulsesChainHoldsWithinTwoMillimetres) {
  double worst = 0.0, rise = 0.0, e0 = 0.0;
  run_chain(SolverKind::sequential_impulses, worst, rise, e0);
  EXPECT_LT(worst, 2e-3);
  EXPECT_LE(rise, 0.01 * std::abs(e0));
}

TEST(Hinge, FreeHingeTurnsAtAConstantRateAndCountsTurns) {
  for (SolverKind solver : both_solvers) {
    World w;
    w.set_solver(solver);
    w.set_gravity(Vec3::Zero());
    Body wheel = make_body(2.0, Vec3(0.3, 0.5, 0.7).asDiagonal());
    wheel.position = Vec3(1, 2, 3);
    wheel.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3(1, 1, 0).normalized()));
    const Vec3 axis = wheel.orientation * Vec3::UnitY();  // a principal axis: no wobble
    wheel.angular_velocity = 5.0 * axis;
    JointDef def;
    def.type = JointKind::hinge;
    def.a = w.add(wheel);
    def.anchor = wheel.position;
    def.axis = axis;
    Joint& j = add_joint(w, def);
    const double dt = 1.0 / 60.0;
    for (int step = 1; step <= 240; ++step) {
      w.step(dt);
      EXPECT_NEAR(j.rate(w.bodies()[0], nullptr), 5.0, 1e-9) << name(solver);
      EXPECT_NEAR(j.angle(w.bodies()[0], nullptr), 5.0 * step * dt, 1e-9) << name(solver);
    }
    EXPECT_GT(j.angle(w.bodies()[0], nullptr), 2.0 * 2.0 * M_PI);  // past two turns
  }
}

// ---- springs and motors: the exact oscillator -------------------------------------------------

// RK4 with 10,000 small steps as the reference for the closed form.
OscillatorState rk4_oscillator(double x, double v, double k, double c, double f, double h) {
  const int n = 10000;
  const double s = h / n;
  auto acc = [&](double x_, double v_) { return f - c * v_ - k * x_; };
  for (int i = 0; i < n; ++i) {
    const double k1x = v, k1v = acc(x, v);
    const double k2x = v + 0.5 * s * k1v, k2v = acc(x + 0.5 * s * k1x, v + 0.5 * s * k1v);
    const double k3x = v + 0.5 * s * k2v, k3v = acc(x + 0.5 * s * k2x, v + 0.5 * s * k2v);
    const double k4x = v + s * k3v, k4v = acc(x + s * k3x, v + s * k3v);
    x += s / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
    v += s / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
  }
  return {x, v};
}

TEST(Oscillator, StepMatchesRk4InEveryRegime) {
  struct Case {
    double k, c, f;
  };
  // under-damped, critical (c² = 4k), over-damped, very over-damped, no spring, free
  const Case cases[] = {{157.9, 2.5, 0.0}, {100.0, 20.0, 3.0}, {100.0, 50.0, -2.0},
                        {1.0, 1e4, 1.0},   {0.0, 3.0, 2.0},    {0.0, 0.0, 9.81}};
  for (const Case& c : cases)
    for (double h : {1.0 / 240.0, 0.1}) {
      const OscillatorState got = damped_oscillator_step(0.7, -1.3, c.k, c.c, c.f, h);
      const OscillatorState want = rk4_oscillator(0.7, -1.3, c.k, c.c, c.f, h);
      EXPECT_NEAR(got.x, want.x, 1e-9) << c.k << " " << c.c << " " << h;
      EXPECT_NEAR(got.v, want.v, 1e-8) << c.k << " " << c.c << " " << h;
    }
}

// Issue 14: a hinge spring, 100° initial, 2 Hz, ζ = 0.1, unit inertia, 120 steps at 60 Hz
// with 4 substeps, within 1° of θ(t) = e^{−ζωt}(θ₀ cos ω_d t + θ₀ ζω/ω_d sin ω_d t) at
// every step.
TEST(Spring, HingeSpringFollowsTheContinuousDampedOscillator) {
  for (SolverKind solver : both_solvers) {
    World w;
    w.set_solver(solver);
    w.set_substeps(4);
    w.set_gravity(Vec3::Zero());
    Body wheel = make_body(1.0, Mat3::Identity());
    const double theta0 = 100.0 * M_PI / 180.0;
    JointDef def;
    def.type = JointKind::hinge;
    def.a = w.add(wheel);
    def.axis = Vec3::UnitZ();
    def.spring = JointSpring{2.0, 0.1, -theta0};  // rest at −θ₀: the hinge starts θ₀ from it
    Joint& j = add_joint(w, def);
    const double omega = 2.0 * M_PI * 2.0, zeta = 0.1;
    const double wd = omega * std::sqrt(1.0 - zeta * zeta);
    double worst = 0.0;
    for (int step = 1; step <= 120; ++step) {
      w.step(1.0 / 60.0);
      const double t = w.time();
      const double want = theta0 * std::exp(-zeta * omega * t) *
                          (std::cos(wd * t) + zeta * omega / wd * std::sin(wd * t));
      worst = std::max(worst, std::abs(j.angle(w.bodies()[0], nullptr) + theta0 - want));
    }
    std::printf("hinge spring, %s: largest error %.3g deg\n", name(solver).c_str(),
                worst * 180.0 / M_PI);
    EXPECT_LT(worst, M_PI / 180.0) << name(solver);
    // Energy: ½ I ω² + ½ k θ² decays as the damped oscillator's.
    const double t = w.time();
    const double x = theta0 * std::exp(-zeta * omega * t) *
                     (std::cos(wd * t) + zeta * omega / wd * std::sin(wd * t));
    const double v = -theta0 * std::exp(-zeta * omega * t) * (omega * omega / wd) * std::sin(wd * t);
    EXPECT_NEAR(w.energy(), 0.5 * v * v + 0.5 * omega * omega * x * x, 1e-3) << name(solver);
  }
}

// Document 000 "PD controller": I θ'' = kp (θd − θ) − kv θ̇ from rest at 0. Its response is
// θd (1 − e^{−σt}(cos ω_d t + σ/ω_d sin ω_d t)) under-damped, σ = kv/2I, ω_d = √(kp/I − σ²);
// θd (1 − (1 + σt) e^{−σt}) critical; θd (1 − (r₂e^{r₁t} − r₁e^{r₂t})/(r₂ − r₁)) over-damped.
double pd_response(double inertia, double kp, double kv, double target, double t) {
  const double sigma = kv / (2.0 * inertia), w2 = kp / inertia - sigma * sigma;
  if (w2 > 1e-9) {
    const double wd = std::sqrt(w2);
    return target * (1 - std::exp(-sigma * t) * (std::cos(wd * t) + sigma / wd * std::sin(wd * t)));
  }
  if (w2 > -1e-9) return target * (1 - (1 + sigma * t) * std::exp(-sigma * t));
  const double r1 = -sigma + std::sqrt(-w2), r2 = -sigma - std::sqrt(-w2);
  return target * (1 - (r2 * std::exp(r1 * t) - r1 * std::exp(r2 * t)) / (r2 - r1));
}

// A hinge about z to the world driving a body of inertia I about it, no gravity.
Joint& motor_hinge(World& w, double inertia, const JointMotor& motor, int substeps) {
  w.set_substeps(substeps);
  w.set_gravity(Vec3::Zero());
  JointDef def;
  def.type = JointKind::hinge;
  def.a = w.add(make_body(1.0, inertia * Mat3::Identity()));
  def.axis = Vec3::UnitZ();
  def.motor = motor;
  return add_joint(w, def);
}

struct PdRun {
  double worst = 0.0;    // largest |θ − closed form| (rad)
  double largest = 0.0;  // largest θ
  double peak_torque = 0.0;
};
// A hinge to the world (inertia I about its axis, no gravity) driven from rest at θ = 0
// toward `target` for 3 s at 60 Hz.
PdRun run_pd(double inertia, double kp, double kv, double target, double max_torque,
             int substeps) {
  World w;
  Joint& j = motor_hinge(w, inertia, JointMotor{target, 0.0, kp, kv, max_torque}, substeps);
  PdRun run;
  for (int step = 1; step <= 180; ++step) {
    w.step(1.0 / 60.0);
    const double angle = j.angle(w.bodies()[0], nullptr);
    run.worst = std::max(run.worst, std::abs(angle - pd_response(inertia, kp, kv, target, w.time())));
    run.largest = std::max(run.largest, angle);
    run.peak_torque = std::max(run.peak_torque, std::abs(j.motor_force()));
  }
  return run;
}

TEST(Motor, PdResponseMatchesTheSecondOrderClosedForm) {
  const double inertia = 2.0, kp = 50.0, target = 1.0;
  const double critical = 2.0 * std::sqrt(kp * inertia);
  for (double kv : {0.2 * critical, critical, 5.0 * critical}) {
    const PdRun run = run_pd(inertia, kp, kv, target, unbounded, 4);
    EXPECT_LT(run.worst, 1e-6) << "kv = " << kv;
    if (kv < critical) EXPECT_GT(run.largest, 1.1 * target);  // overshoots
    else EXPECT_LE(run.largest, target + 1e-9);              // never past the target
  }
}

// A motor whose max_torque is never reached is the unbounded motor: the same closed forms.
// (It used to lose the exact position update and turn first order: 0.129 rad off for kp = 50,
// kv = 1, I = 0.5 at 60 Hz, where the unbounded motor is within 4e-15.)
TEST(Motor, BoundedMotorThatNeverSaturatesIsTheUnboundedOne) {
  for (int substeps : {1, 4})
    for (const auto& [inertia, kp, kv] :
         {std::array<double, 3>{0.5, 50.0, 1.0}, std::array<double, 3>{2.0, 50.0, 4.0},
          std::array<double, 3>{2.0, 50.0, 20.0}, std::array<double, 3>{2.0, 50.0, 100.0}}) {
      const PdRun free = run_pd(inertia, kp, kv, 1.0, unbounded, substeps);
      const PdRun bounded = run_pd(inertia, kp, kv, 1.0, 2.0 * free.peak_torque, substeps);
      EXPECT_LT(free.worst, 1e-6) << "kv = " << kv << ", " << substeps << " substeps";
      EXPECT_LT(bounded.worst, 1e-6) << "kv = " << kv << ", " << substeps << " substeps";
      EXPECT_LT(bounded.peak_torque, 2.0 * free.peak_torque);  // it never saturated
    }
}

// A motor held at its bound the whole time (a stiff PD far from its target) applies exactly
// ±max_torque: θ = ½ (τmax/I) t² (to rounding: the exact constant-torque update), θ̇ = τmax t / I.
TEST(Motor, SaturatedMotorAppliesExactlyMaxTorque) {
  for (int substeps : {1, 4})
    for (double sign : {1.0, -1.0}) {
      const double inertia = 0.5, max_torque = 1.5;
      World w;
      Joint& j = motor_hinge(w, inertia, JointMotor{sign * 100.0, 0.0, 1e4, 10.0, max_torque},
                             substeps);
      double worst = 0.0, worst_rate = 0.0;
      for (int step = 1; step <= 60; ++step) {
        w.step(1.0 / 60.0);
        const double t = w.time();
        worst = std::max(worst, std::abs(j.angle(w.bodies()[0], nullptr) -
                                         sign * 0.5 * max_torque / inertia * t * t));
        worst_rate = std::max(worst_rate, std::abs(w.bodies()[0].angular_velocity.z() -
                                                   sign * max_torque / inertia * t));
        EXPECT_NEAR(j.motor_force(), sign * max_torque, 1e-9);
      }
      EXPECT_LT(worst, 1e-9) << substeps << " substeps";
      EXPECT_LT(worst_rate, 1e-9) << substeps << " substeps";
    }
}

}  // namespace
}  // namespace rigidlab
