// engine/solver.hpp and engine/contact_constraints.hpp through one step of a world, against
// closed forms: Newton's restitution law v' = −e v above the threshold and 0 below it, the
// speculative limit (a gap closes within the step and no more), Coulomb's limit μ λn with the
// spin it gives a ball, rolling at 5/7, the Box2D mixing rules, sequential_impulses' position
// recurrence, conservation of linear and angular momentum, warm starting; and the constraint
// row on its own (J W Jᵀ against the 12 x 12 product, the soft coefficients of b2MakeSoft).
// Both solvers unless a test is about one of them.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "engine/constraint_row.hpp"
#include "engine/contact_helpers.hpp"
#include "engine/world.hpp"

namespace rigidlab {
namespace {

constexpr double dt = 0.01;
const SolverKind both_solvers[] = {SolverKind::soft_step, SolverKind::sequential_impulses};

Body ball(double mass, double radius, const Vec3& position, const Vec3& velocity = Vec3::Zero()) {
  Body b = make_sphere_body(mass, radius);
  b.position = position;
  b.velocity = velocity;
  return b;
}

// A world with the floor y ≥ 0, the given solver and gravity.
struct Floor {
  World world;
  Floor(SolverKind solver, const Vec3& gravity, double restitution = 0.0,
        double friction = default_friction) {
    world.set_solver(solver);
    world.set_gravity(gravity);
    world.add_plane(make_plane(Vec3(0, 1, 0), 0.0, restitution, friction));
  }
  Body& body(std::size_t i = 0) { return world.bodies()[i]; }
};

std::string name(SolverKind s) { return solver_names[static_cast<int>(s)]; }

// ---- the row ---------------------------------------------------------------------------------

TEST(ConstraintRow, CouplingIsJWJtOfTheTwelveByTwelveProduct) {
  // J W Jᵀ built as the product of a 1 x 12 (or 2 x 12) Jacobian and the 12 x 12 W.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    auto random = [&] { return Vec3(u(rng), u(rng), u(rng)); };
    Mat3 ia = Mat3::Random(), ib = Mat3::Random();
    ia = ia * ia.transpose() + Mat3::Identity();
    ib = ib * ib.transpose() + Mat3::Identity();
    const double ma = 1.5 + u(rng), mb = 0.7 + 0.5 * u(rng);
    Eigen::Matrix<double, 12, 12> w = Eigen::Matrix<double, 12, 12>::Zero();
    w.block<3, 3>(0, 0) = ma * Mat3::Identity();
    w.block<3, 3>(3, 3) = ia;
    w.block<3, 3>(6, 6) = mb * Mat3::Identity();
    w.block<3, 3>(9, 9) = ib;
    const Jacobian i = point_jacobian(random().normalized(), random(), random());
    const Jacobian j{random(), random(), random()};
    auto row = [](const Jacobian& k) {
      Eigen::Matrix<double, 1, 12> r;
      r << -k.linear.transpose(), -k.angular_a.transpose(), k.linear.transpose(),
          k.angular_b.transpose();
      return r;
    };
    const double want = (row(i) * w * row(j).transpose())(0, 0);
    EXPECT_NEAR(coupling(i, j, ma, ia, mb, ib), want, 1e-12 * std::abs(want) + 1e-14);
  }
}

TEST(ConstraintRow, SoftCoefficientsAreThoseOfTheImplicitSpring) {
  // b2MakeSoft: with ω = 2π f, a1 = 2ζ + hω, a2 = hω a1: bias rate ω/a1, mass scale
  // a2/(1 + a2), impulse scale 1/(1 + a2). Independent check: the row J v' + β C + γ λ' = 0
  // of one unit mass at C = 1, v = 0 gives the implicit-Euler step of x'' = −ω² x − 2ζω x',
  //   v' = (−h ω² x)/(1 + 2ζ h ω + h² ω²)   (backward Euler on (x, v)).
  for (double hertz : {1.0, 30.0, 240.0})
    for (double zeta : {0.0, 0.7, 10.0})
      for (double h : {1.0 / 60, 1e-3}) {
        const Softness s = make_soft(hertz, zeta, h);
        const double omega = 2 * M_PI * hertz;
        SolverBody a, b;
        b.inverse_mass = 1.0;
        ConstraintRow row;
        row.jacobian = point_jacobian(Vec3::UnitX(), Vec3::Zero(), Vec3::Zero());
        prepare_row(row, a, b);
        // C = −1 (b one metre short of where it should be along x): the spring pushes it on.
        solve_row(row, a, b, s.mass_scale * s.bias_rate * -1.0, s);
        const double want = h * omega * omega / (1 + 2 * zeta * h * omega + h * h * omega * omega);
        EXPECT_NEAR(b.velocity.x(), want, 1e-12 * want) << hertz << " Hz ζ " << zeta;
      }
  EXPECT_EQ(make_soft(0.0, 1.0, 0.01).mass_scale, 1.0);  // 0 Hz: a rigid row
}

// ---- one step against closed forms -------------------------------------------------------------

TEST(Solver, RestitutionAboveTheThresholdAndNotBelow) {
  for (SolverKind solver : both_solvers)
    for (double speed : {3.0, 0.5}) {
      Floor f(solver, Vec3::Zero());
      Body b = ball(2.0, 0.5, Vec3(0, 0.5, 0), Vec3(0, -speed, 0));
      b.restitution = 0.5;
      f.world.add(b);
      f.world.step(dt);
      // 003_* "Collision Response": against an immovable body v' = −ε v; below 1 m/s, ε = 0.
      // The step ends after the impact: the velocity is the rebound (issue 12 item 16).
      const double want = speed > 1.0 ? 0.5 * speed : 0.0;
      EXPECT_NEAR(f.body().velocity.y(), want, 1e-12) << name(solver) << " speed " << speed;
      ASSERT_EQ(f.world.contacts().size(), 1u);
      EXPECT_NEAR(f.world.contacts()[0].normal_impulse, 2.0 * (want + speed), 1e-12);
      EXPECT_EQ(f.world.contacts()[0].restitution, 0.5);  // max(0.5, plane's 0)
    }
}

TEST(Solver, SpeculativeContactLandsOnTheSurfaceAndNoFurther) {
  for (SolverKind solver : both_solvers) {
    // 0.05 m above the floor at 10 m/s: in 0.01 s it would go 0.1 m; it lands on the floor at
    // the end of the step, and (e = 0) stays.
    Floor f(solver, Vec3::Zero());
    f.world.add(ball(1.0, 0.5, Vec3(0, 0.55, 0), Vec3(0, -10, 0)));
    f.world.step(dt);
    EXPECT_NEAR(f.body().position.y(), 0.5, 1e-12) << name(solver);
    EXPECT_NEAR(f.body().velocity.y(), 0.0, 1e-12) << name(solver);
    ASSERT_EQ(f.world.contacts().size(), 1u);
    EXPECT_NEAR(f.world.contacts()[0].depth, -0.05, 1e-15);
    EXPECT_NEAR(f.world.contacts()[0].normal_impulse, 10.0, 1e-12);  // all its momentum
    EXPECT_TRUE(touched(f.world.contacts()[0]));
    // At 4 m/s it covers 0.04 m: the gap stays open and is wider than speculative_distance
    // (0.02 m), so there is no contact at all; at 0.015 m it is a speculative contact that
    // stays open: no impulse, and not a touching contact.
    Floor g(solver, Vec3::Zero());
    g.world.add(ball(1.0, 0.5, Vec3(0, 0.55, 0), Vec3(0, -4, 0)));
    g.world.step(dt);
    EXPECT_EQ(g.body().velocity.y(), -4.0);
    EXPECT_EQ(g.world.contacts().size(), 0u);
    Floor h(solver, Vec3::Zero());
    h.world.add(ball(1.0, 0.5, Vec3(0, 0.515, 0), Vec3(0, -1, 0)));
    h.world.step(dt);
    EXPECT_EQ(h.body().velocity.y(), -1.0);
    ASSERT_EQ(h.world.contacts().size(), 1u);
    EXPECT_FALSE(touched(h.world.contacts()[0]));
  }
}

TEST(Solver, SlidingBallGetsTheCoulombLimitAndItsTorque) {
  // Resting on the floor, gravity makes the normal impulse m g Δt; sliding at 5 m/s, friction
  // is at its limit μ m g Δt: Δv = −μ g Δt, and about the centre the same impulse at the
  // contact, R below, spins the ball: Δω_z = −R μ m g Δt / (2/5 m R²) = −5 μ g Δt / (2 R).
  const double mass = 3.0, radius = 0.4, mu = 0.2, g = 9.81;
  for (SolverKind solver : both_solvers) {
    Floor f(solver, Vec3(0, -g, 0), 0.0, mu);
    Body b = ball(mass, radius, Vec3(0, radius, 0), Vec3(5, 0, 0));
    b.friction = mu;
    f.world.add(b);
    f.world.step(dt);
    EXPECT_NEAR(f.body().velocity.x(), 5.0 - mu * g * dt, 1e-12) << name(solver);
    EXPECT_NEAR(f.body().velocity.y(), 0.0, 1e-12);
    EXPECT_NEAR(f.body().angular_velocity.z(), -5.0 * mu * g * dt / (2.0 * radius), 1e-12);
    const ContactInfo& c = f.world.contacts()[0];
    EXPECT_NEAR(c.normal_impulse, mass * g * dt, 1e-12);
    EXPECT_NEAR(c.friction_impulse.norm(), mu * c.normal_impulse, 1e-12);
    EXPECT_NEAR(c.friction, mu, 1e-15);  // √(μ μ)
  }
}

TEST(Solver, SlowSlidingBallStartsRollingAtFiveSevenths) {
  // Friction can stop the slip within one step: the contact point stops, v = ω R, and the
  // angular momentum about the contact point, m v R, is kept: v' = 5/7 v (I = 2/5 m R²).
  const double radius = 0.5;
  for (SolverKind solver : both_solvers) {
    Floor f(solver, Vec3(0, -9.81, 0));
    f.world.add(ball(1.0, radius, Vec3(0, radius, 0), Vec3(0.01, 0, 0)));
    f.world.step(dt);
    EXPECT_NEAR(f.body().velocity.x(), 5.0 / 7.0 * 0.01, 1e-12) << name(solver);
    EXPECT_NEAR(f.body().angular_velocity.z() * radius, -5.0 / 7.0 * 0.01, 1e-12);
  }
}

TEST(Solver, MixingRules) {
  for (SolverKind solver : both_solvers) {
    Floor f(solver, Vec3::Zero(), 0.8, 0.9);
    Body b = ball(1.0, 0.5, Vec3(0, 0.5, 0), Vec3(0, -2, 0));
    b.friction = 0.4, b.restitution = 0.3;
    f.world.add(b);
    f.world.step(dt);
    EXPECT_DOUBLE_EQ(f.world.contacts()[0].friction, 0.6);
    EXPECT_EQ(f.world.contacts()[0].restitution, 0.8);
    EXPECT_NEAR(f.body().velocity.y(), 1.6, 1e-12) << name(solver);
  }
}

TEST(Solver, ImpulsesConserveMomentumBetweenBodies) {
  // Two balls meeting off-centre, spinning, with friction and restitution: equal and opposite
  // impulses at one point keep Σ m v and Σ (x × m v + I ω) about any point, the impulses
  // after the positions moved (relax, restitution) included.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (SolverKind solver : both_solvers)
    for (int trial = 0; trial < 50; ++trial) {
      World w;
      w.set_solver(solver);
      w.set_gravity(Vec3::Zero());
      Body a = ball(1.0 + 0.5 * u(rng), 0.5, Vec3(u(rng), u(rng), u(rng)));
      Body b = ball(2.0 + u(rng), 0.7,
                    a.position + 1.21 * Vec3(1, 0.3 * u(rng), 0.3 * u(rng)).normalized());
      a.velocity = Vec3(3, u(rng), u(rng)), b.velocity = Vec3(-2, u(rng), u(rng));
      a.angular_velocity = 5 * Vec3(u(rng), u(rng), u(rng));
      b.angular_velocity = 5 * Vec3(u(rng), u(rng), u(rng));
      a.restitution = 0.5 + 0.5 * u(rng), b.friction = 1.0;
      w.add(a);
      w.add(b);
      const Vec3 about(u(rng), u(rng), u(rng));
      const Vec3 p0 = w.linear_momentum(), l0 = w.angular_momentum(about);
      w.step(dt);
      ASSERT_FALSE(w.contacts().empty());
      EXPECT_GT(w.contacts()[0].normal_impulse, 0.0);
      EXPECT_NEAR((w.linear_momentum() - p0).norm(), 0.0, 1e-12) << name(solver);
      EXPECT_NEAR((w.angular_momentum(about) - l0).norm(), 0.0, 1e-12) << name(solver);
    }
}

TEST(Solver, WarmStartingCarriesTheSolutionAcrossSteps) {
  // One sweep per step cannot settle a stack of three boxes at once (each contact learns what
  // the others need over several sweeps); warm starting carries the impulses to the next step,
  // so a settled stack stays settled: the floor carries 3 m g Δt exactly and nothing moves.
  for (SolverKind solver : both_solvers) {
    Floor f(solver, Vec3(0, -9.81, 0));
    ContactSettings s;
    s.iterations = 1;
    s.relax_iterations = 1;
    f.world.set_contact_settings(s);
    for (int k = 0; k < 3; ++k) {
      Body box = make_box_body(1.0, Vec3(1.0, 0.4, 0.6));
      box.position = Vec3(0, 0.2 + 0.4 * k, 0);
      box.orientation = quat_from_axis_angle(Vec3(0, 1, 0), 0.3);
      f.world.add(box);
    }
    f.world.step(dt);
    double first = 0.0;
    for (const Body& b : f.world.bodies()) first += b.velocity.norm();
    f.world.step(dt, 400);
    double last = 0.0, floor_total = 0.0;
    for (const Body& b : f.world.bodies()) last += b.velocity.norm() + b.angular_velocity.norm();
    for (const ContactInfo& c : f.world.contacts())
      if (!c.a.valid()) floor_total += c.normal_impulse;
    // Both solvers sweep on to convergence on this first step (engine/solver.cpp
    // Solver::solve): its new contacts form a chain of 3 under the top box, longer than one
    // sweep carries a load down (3² > 1), so the first step already settles the stack; the
    // 400 steps after it have one sweep each and keep it settled by the warm start alone.
    EXPECT_LT(first, 1e-6) << name(solver);
    EXPECT_LT(last, 1e-9) << name(solver);
    EXPECT_NEAR(floor_total, 3 * 9.81 * dt, 1e-9) << name(solver);
  }
}

TEST(Solver, SoftStepStopsSweepingOnceTheSweepsHaveConverged) {
  // A stack of five boxes at rest: with the warm start the first sweep is nearly right, the
  // second leaves an error of rounding, and soft_step stops there (Solver::settled) instead of
  // sweeping its 10 iterations, and the stack stays where it was: the floor carries 5 m g Δt
  // exactly, nothing moves. Kick the top box and the next step is not settled: it takes all
  // 10 sweeps. sequential_impulses always sweeps its `iterations` (lesson
  // sequential-impulses shows them converging).
  for (SolverKind solver : both_solvers) {
    Floor f(solver, Vec3(0, -9.81, 0));
    BodyId top;
    for (int k = 0; k < 5; ++k) {
      Body box = make_box_body(1.0, Vec3(1, 1, 1));
      box.position = Vec3(0, 0.5 + k, 0);
      top = f.world.add(box);
    }
    f.world.step(dt, 60);
    const double landed = f.world.store().get(top).position.y();  // 4.5 within 1e-8
    const std::size_t settled = solver == SolverKind::soft_step ? 2 : 10;
    for (int k = 0; k < 60; ++k) {
      f.world.step(dt);
      ASSERT_EQ(f.world.solver_report().size(), settled) << name(solver) << " step " << k;
      EXPECT_LT(f.world.solver_report().back(), 1e-6 * 9.81 * dt) << name(solver);
    }
    double floor_total = 0.0, moving = 0.0;
    for (const ContactInfo& c : f.world.contacts())
      if (!c.a.valid()) floor_total += c.normal_impulse;
    for (const Body& b : f.world.bodies()) moving += b.velocity.norm() + b.angular_velocity.norm();
    EXPECT_NEAR(floor_total, 5 * 9.81 * dt, 1e-9) << name(solver);
    EXPECT_LT(moving, 1e-9) << name(solver);
    EXPECT_NEAR(landed, 4.5, 1e-8) << name(solver);
    EXPECT_NEAR(f.world.store().get(top).position.y(), landed, 1e-12) << name(solver);
    f.world.store().get(top).velocity = Vec3(0.1, 0, 0);
    f.world.step(dt);
    EXPECT_EQ(f.world.solver_report().size(), 10u) << name(solver);
  }
}

TEST(Solver, SequentialImpulsesPositionCorrectionRecurrence) {
  // A ball 0.1 m into the floor, at rest, no gravity: nothing to do for velocities; each
  // position sweep lifts it by β (d − slop) (its effective mass is m: the normal passes
  // through the centre), three sweeps by default, none once d ≤ 3 slop.
  Floor f(SolverKind::sequential_impulses, Vec3::Zero());
  f.world.add(ball(1.0, 0.5, Vec3(0, 0.4, 0)));
  f.world.step(dt);
  const ContactSettings& s = f.world.contact_settings();
  double depth = 0.1;
  for (int sweep = 0; sweep < s.position_iterations && depth > 3 * s.linear_slop; ++sweep)
    depth -= s.baumgarte * (depth - s.linear_slop);
  EXPECT_NEAR(f.body().position.y(), 0.5 - depth, 1e-14);
  EXPECT_EQ(f.body().velocity, Vec3::Zero());
  EXPECT_EQ(f.body().orientation.coeffs(), Quat::Identity().coeffs());
  // Deep in: at most max_correction per sweep.
  Floor g(SolverKind::sequential_impulses, Vec3::Zero());
  g.world.add(ball(1.0, 0.5, Vec3(0, -5, 0)));
  g.world.step(dt);
  EXPECT_NEAR(g.body().position.y(), -5 + s.position_iterations * s.max_correction, 1e-12);
}

TEST(Solver, SoftStepPushesAnOverlapOutAsTheDampedSpringAndLeavesNoVelocity) {
  // soft_step moves the positions by the push velocity of the soft row and drops it: a ball
  // 1 cm into the floor (no gravity) rises by the soft step of make_soft each step toward
  // the push's rest overlap (push_slop_fraction of the slop; the ball's slop is linear_slop,
  // under 1 % of its size), and its velocity stays 0. With ζ = 10 the spring is overdamped:
  // it never overshoots that rest.
  Floor f(SolverKind::soft_step, Vec3::Zero());
  f.world.add(ball(1.0, 0.5, Vec3(0, 0.49, 0)));
  const ContactSettings& s = f.world.contact_settings();
  const double rest = contact_detail::push_slop_fraction * s.linear_slop;
  // Against a plane the row is twice as stiff (as Box2D's static contacts).
  const Softness soft = make_soft(2 * s.contact_hertz, s.contact_damping_ratio, dt);
  double depth = 0.01;
  for (int step = 0; step < 50; ++step) {
    f.world.step(dt);
    depth -= std::min(soft.mass_scale * soft.bias_rate * (depth - rest), s.contact_push_speed) * dt;
    EXPECT_NEAR(0.5 - f.body().position.y(), depth, 1e-12) << "step " << step;
    EXPECT_EQ(f.body().velocity, Vec3::Zero());
    ASSERT_GE(0.5 - f.body().position.y(), rest) << "overshoot at step " << step;
  }
}

TEST(Solver, EvenlySunkBoxRisesWithoutTilting) {
  // A box 0.1 m into the floor on all four corners, turned about the vertical: its manifold is
  // corrected as a block (both solvers), so it rises straight.
  for (SolverKind solver : both_solvers) {
    Floor f(solver, Vec3::Zero());
    Body box = make_box_body(1.0, Vec3(1.0, 0.4, 0.6));
    box.position = Vec3(0, 0.1, 0);
    box.orientation = quat_from_axis_angle(Vec3(0, 1, 0), 0.4);
    f.world.add(box);
    f.world.step(dt, 3);
    EXPECT_GT(f.body().position.y(), 0.1 + 0.01) << name(solver);
    EXPECT_NEAR(f.body().position.x(), 0.0, 1e-12);
    EXPECT_NEAR(f.body().position.z(), 0.0, 1e-12);
    EXPECT_NEAR(f.body().orientation.angularDistance(box.orientation), 0.0, 1e-12);
  }
}

TEST(Solver, StaticBodiesNeverMove) {
  for (SolverKind solver : both_solvers) {
    World w;
    w.set_solver(solver);
    w.set_gravity(Vec3::Zero());
    Body ground = make_box_body(1.0, Vec3(4, 1, 4));
    make_static(ground);
    const BodyId g = w.add(ground);
    Body b = ball(1.0, 0.5, Vec3(0.3, 1.0, 0), Vec3(1, -3, 0));
    b.restitution = 1.0;
    const BodyId id = w.add(b);
    w.step(dt);
    EXPECT_EQ(w.bodies()[0].velocity, Vec3::Zero());
    EXPECT_EQ(w.bodies()[0].position, Vec3::Zero());
    EXPECT_NEAR(w.bodies()[1].velocity.y(), 3.0, 1e-12) << name(solver);  // e = 1
    ASSERT_EQ(w.contacts().size(), 1u);
    EXPECT_EQ(w.contacts()[0].a, g);
    EXPECT_EQ(w.contacts()[0].b, id);
  }
}

TEST(Solver, SettingsProblems) {
  ContactSettings s;
  EXPECT_EQ(contact_settings_problem(s), "");
  s.iterations = 0;
  EXPECT_EQ(contact_settings_problem(s), "iterations must be an integer from 1 to 1000, got 0");
  s = ContactSettings{};
  s.relax_iterations = -1;
  EXPECT_EQ(contact_settings_problem(s),
            "relax_iterations must be an integer from 0 to 1000, got -1");
  s = ContactSettings{};
  s.restitution_threshold = -1;
  EXPECT_EQ(contact_settings_problem(s), "restitution_threshold must be finite and >= 0, got -1");
  s = ContactSettings{};
  s.contact_hertz = std::nan("");
  EXPECT_EQ(contact_settings_problem(s), "contact_hertz must be finite and >= 0, got nan");
  s = ContactSettings{};
  s.baumgarte = 2;
  EXPECT_EQ(contact_settings_problem(s), "baumgarte must be in [0, 1], got 2");
  EXPECT_EQ(parse_solver("soft_step"), SolverKind::soft_step);
  EXPECT_EQ(parse_solver("sequential_impulses"), SolverKind::sequential_impulses);
  EXPECT_FALSE(parse_solver("pgs").has_value());
}

}  // namespace
}  // namespace rigidlab
