// engine/contact_solver.hpp on its own (no integrator): one solve_velocities or
// correct_positions against closed forms — Newton's restitution law v' = −e v above the
// threshold and 0 below it, the speculative limit v' = −gap/Δt, Coulomb's limit μ λn with the
// spin it gives a ball, rolling at 5/7, the Box2D mixing rules, the position-correction
// recurrence, conservation of linear and angular momentum, warm starting, and the
// bookkeeping of removed bodies.
#include "engine/contact_solver.hpp"

#include <gtest/gtest.h>

#include <random>

#include "engine/integrators.hpp"

namespace rigidlab {
namespace {

constexpr double dt = 0.01;
const Vec3 no_gravity = Vec3::Zero();
const Vec3 gravity(0, -9.81, 0);

Body ball(double mass, double radius, const Vec3& position, const Vec3& velocity = Vec3::Zero()) {
  Body b = make_sphere_body(mass, radius);
  b.position = position;
  b.velocity = velocity;
  return b;
}

std::vector<Plane> floor_plane(double restitution = 0.0, double friction = default_friction) {
  return {make_plane(Vec3(0, 1, 0), 0.0, restitution, friction)};
}

TEST(ContactSolver, RestitutionAboveTheThresholdAndNotBelow) {
  for (double speed : {3.0, 0.5}) {
    std::vector<Body> bodies{ball(2.0, 0.5, Vec3(0, 0.5, 0), Vec3(0, -speed, 0))};
    bodies[0].restitution = 0.5;
    ContactSolver solver;
    solver.solve_velocities(bodies, floor_plane(), no_gravity, dt, ContactVelocities::current);
    // 003_* "Collision Response": against an immovable body v' = −ε v; below 1 m/s, ε = 0.
    const double want = speed > 1.0 ? 0.5 * speed : 0.0;
    EXPECT_NEAR(bodies[0].velocity.y(), want, 1e-12) << "speed " << speed;
    ASSERT_EQ(solver.contacts().size(), 1u);
    EXPECT_NEAR(solver.contacts()[0].normal_impulse, 2.0 * (want + speed), 1e-12);
    EXPECT_EQ(solver.contacts()[0].restitution, 0.5);  // max(0.5, plane's 0)
  }
}

TEST(ContactSolver, SpeculativeContactLetsTheGapCloseAndNoMore) {
  // 0.05 m above the floor at 10 m/s: in 0.01 s it would go 0.1 m, so it may only go 0.05.
  std::vector<Body> bodies{ball(1.0, 0.5, Vec3(0, 0.55, 0), Vec3(0, -10, 0))};
  ContactSolver solver;
  solver.solve_velocities(bodies, floor_plane(), no_gravity, dt, ContactVelocities::current);
  EXPECT_NEAR(bodies[0].velocity.y(), -0.05 / dt, 1e-12);
  ASSERT_EQ(solver.contacts().size(), 1u);
  EXPECT_NEAR(solver.contacts()[0].depth, -0.05, 1e-15);
  EXPECT_TRUE(touched(solver.contacts()[0]));  // it pushed
  // At 4 m/s it covers 0.04 m: the gap stays open and is wider than speculative_distance
  // (0.02 m), so there is no contact at all; at 0.015 m it is a speculative contact that
  // stays open: no impulse, and not a touching contact.
  bodies[0].position = Vec3(0, 0.55, 0);
  bodies[0].velocity = Vec3(0, -4, 0);
  solver.solve_velocities(bodies, floor_plane(), no_gravity, dt, ContactVelocities::current);
  EXPECT_EQ(bodies[0].velocity.y(), -4.0);
  EXPECT_EQ(solver.contacts().size(), 0u);
  bodies[0].position = Vec3(0, 0.515, 0);
  bodies[0].velocity = Vec3(0, -1, 0);
  solver.solve_velocities(bodies, floor_plane(), no_gravity, dt, ContactVelocities::current);
  EXPECT_EQ(bodies[0].velocity.y(), -1.0);
  ASSERT_EQ(solver.contacts().size(), 1u);
  EXPECT_FALSE(touched(solver.contacts()[0]));
}

TEST(ContactSolver, SlidingBallGetsTheCoulombLimitAndItsTorque) {
  // Resting on the floor, gravity makes the normal impulse m g Δt; sliding at 5 m/s, friction
  // is at its limit μ m g Δt: Δv = −μ g Δt, and about the centre the same impulse at the
  // contact, R below, spins the ball: Δω_z = −R μ m g Δt / (2/5 m R²) = −5 μ g Δt / (2 R).
  const double mass = 3.0, radius = 0.4, mu = 0.2;
  std::vector<Body> bodies{ball(mass, radius, Vec3(0, radius, 0), Vec3(5, 0, 0))};
  bodies[0].friction = mu;
  ContactSolver solver;
  solver.solve_velocities(bodies, floor_plane(0.0, mu), gravity, dt,
                          ContactVelocities::after_forces);
  const double g = 9.81;
  EXPECT_NEAR(bodies[0].velocity.x(), 5.0 - mu * g * dt, 1e-12);
  EXPECT_NEAR(bodies[0].velocity.y(), g * dt, 1e-12);  // the change that cancels this step's g
  EXPECT_NEAR(bodies[0].angular_velocity.z(), -5.0 * mu * g * dt / (2.0 * radius), 1e-12);
  const ContactInfo& c = solver.contacts()[0];
  EXPECT_NEAR(c.normal_impulse, mass * g * dt, 1e-12);
  EXPECT_NEAR(c.friction_impulse.norm(), mu * c.normal_impulse, 1e-12);
  EXPECT_NEAR(c.friction, mu, 1e-15);  // √(μ μ)
}

TEST(ContactSolver, SlowSlidingBallStartsRollingAtFiveSevenths) {
  // Friction can stop the slip within one step: the contact point stops, v = ω R, and the
  // angular momentum about the contact point, m v R, is kept: v' = 5/7 v (I = 2/5 m R²).
  const double radius = 0.5;
  std::vector<Body> bodies{ball(1.0, radius, Vec3(0, radius, 0), Vec3(0.01, 0, 0))};
  ContactSolver solver;
  solver.solve_velocities(bodies, floor_plane(), gravity, dt, ContactVelocities::after_forces);
  EXPECT_NEAR(bodies[0].velocity.x(), 5.0 / 7.0 * 0.01, 1e-12);
  EXPECT_NEAR(bodies[0].angular_velocity.z() * radius, -5.0 / 7.0 * 0.01, 1e-12);
}

TEST(ContactSolver, MixingRules) {
  std::vector<Body> bodies{ball(1.0, 0.5, Vec3(0, 0.5, 0), Vec3(0, -2, 0))};
  bodies[0].friction = 0.4, bodies[0].restitution = 0.3;
  ContactSolver solver;
  solver.solve_velocities(bodies, floor_plane(0.8, 0.9), no_gravity, dt,
                          ContactVelocities::current);
  EXPECT_DOUBLE_EQ(solver.contacts()[0].friction, 0.6);
  EXPECT_EQ(solver.contacts()[0].restitution, 0.8);
  EXPECT_NEAR(bodies[0].velocity.y(), 1.6, 1e-12);
}

TEST(ContactSolver, ImpulsesConserveMomentumBetweenBodies) {
  // Two balls meeting off-centre, spinning, with friction and restitution: equal and opposite
  // impulses at one point keep Σ m v and Σ (x × m v + I ω) (about the origin).
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    Body a = ball(1.0 + 0.5 * u(rng), 0.5, Vec3(u(rng), u(rng), u(rng)));
    Body b = ball(2.0 + u(rng), 0.7,
                  a.position + 1.1 * Vec3(1, 0.3 * u(rng), 0.3 * u(rng)).normalized());
    a.velocity = Vec3(3, u(rng), u(rng)), b.velocity = Vec3(-2, u(rng), u(rng));
    a.angular_velocity = 5 * Vec3(u(rng), u(rng), u(rng));
    b.angular_velocity = 5 * Vec3(u(rng), u(rng), u(rng));
    a.restitution = 0.5 + 0.5 * u(rng), b.friction = 1.0;
    std::vector<Body> bodies{a, b};
    auto momenta = [&bodies](Vec3& p, Vec3& l) {
      p = l = Vec3::Zero();
      for (const Body& x : bodies) {
        p += linear_momentum(x);
        l += x.position.cross(linear_momentum(x)) + angular_momentum(x);
      }
    };
    Vec3 p0, l0, p1, l1;
    momenta(p0, l0);
    ContactSolver solver;
    solver.solve_velocities(bodies, {}, no_gravity, dt, ContactVelocities::current);
    momenta(p1, l1);
    ASSERT_FALSE(solver.contacts().empty());
    EXPECT_GT(solver.contacts()[0].normal_impulse, 0.0);
    EXPECT_NEAR((p1 - p0).norm(), 0.0, 1e-12);
    EXPECT_NEAR((l1 - l0).norm(), 0.0, 1e-12);
  }
}

TEST(ContactSolver, WarmStartingCarriesTheSolutionAcrossSteps) {
  // One sweep per step cannot settle a stack of three boxes (each contact only learns what
  // the others need over several sweeps); warm starting carries the impulses to the next
  // step, so repeated steps converge: the boxes, put back at rest each time (no integrator),
  // end up held exactly, which one sweep of a fresh solver never does.
  std::vector<Body> stack;
  for (int k = 0; k < 3; ++k) {
    Body box = make_box_body(1.0, Vec3(1.0, 0.4, 0.6));
    box.position = Vec3(0, 0.2 + 0.4 * k, 0);
    box.orientation = quat_from_axis_angle(Vec3(0, 1, 0), 0.3);
    stack.push_back(box);
  }
  auto residual = [](const std::vector<Body>& bodies) {
    double sum = 0.0;  // the velocity the step ends with: what the solver added to v + g Δt
    for (const Body& b : bodies) sum += (b.velocity + gravity * dt).norm() + b.angular_velocity.norm();
    return sum;
  };
  ContactSolver solver;
  solver.settings.iterations = 1;
  double first = 0.0, last = 0.0;
  for (int step = 0; step < 200; ++step) {
    std::vector<Body> bodies = stack;
    solver.solve_velocities(bodies, floor_plane(), gravity, dt, ContactVelocities::after_forces);
    if (step == 0) first = residual(bodies);
    last = residual(bodies);
  }
  EXPECT_GT(first, 1e-4);
  EXPECT_LT(last, 1e-10);
  double floor_total = 0.0;
  for (const ContactInfo& c : solver.contacts())
    if (c.a == no_body) floor_total += c.normal_impulse;
  EXPECT_NEAR(floor_total, 3 * 9.81 * dt, 1e-10);  // the floor carries 3 m g Δt
  ContactSolver fresh;  // no memory: every step starts from zero
  fresh.settings.iterations = 1;
  std::vector<Body> bodies = stack;
  fresh.solve_velocities(bodies, floor_plane(), gravity, dt, ContactVelocities::after_forces);
  EXPECT_GT(residual(bodies), 1e-4);
}

TEST(ContactSolver, PositionCorrectionRecurrence) {
  // A ball 0.1 m into the floor, at rest, no gravity: nothing to do for velocities; each
  // position sweep lifts it by β (d − slop) (its effective mass is m: the normal passes
  // through the centre), three sweeps by default, none once d ≤ 3 slop.
  std::vector<Body> bodies{ball(1.0, 0.5, Vec3(0, 0.4, 0))};
  ContactSolver solver;
  solver.solve_velocities(bodies, floor_plane(), no_gravity, dt, ContactVelocities::current);
  EXPECT_EQ(bodies[0].velocity, Vec3::Zero());
  solver.correct_positions(bodies);
  const ContactSettings& s = solver.settings;
  double depth = 0.1;
  for (int sweep = 0; sweep < s.position_iterations && depth > 3 * s.linear_slop; ++sweep)
    depth -= s.baumgarte * (depth - s.linear_slop);
  EXPECT_NEAR(bodies[0].position.y(), 0.5 - depth, 1e-14);
  EXPECT_EQ(bodies[0].velocity, Vec3::Zero());
  EXPECT_EQ(bodies[0].orientation.coeffs(), Quat::Identity().coeffs());
  // Deep in: at most max_correction per sweep.
  bodies[0].position = Vec3(0, -5, 0);
  solver.solve_velocities(bodies, floor_plane(), no_gravity, dt, ContactVelocities::current);
  solver.correct_positions(bodies);
  EXPECT_NEAR(bodies[0].position.y(), -5 + s.position_iterations * s.max_correction, 1e-12);
}

TEST(ContactSolver, EvenlySunkBoxRisesWithoutTilting) {
  // A box 0.1 m into the floor on all four corners, turned about the vertical: its manifold is
  // corrected at the centroid first, so it rises straight (corner after corner would tip it).
  Body box = make_box_body(1.0, Vec3(1.0, 0.4, 0.6));
  box.position = Vec3(0, 0.1, 0);
  box.orientation = quat_from_axis_angle(Vec3(0, 1, 0), 0.4);
  std::vector<Body> bodies{box};
  ContactSolver solver;
  solver.solve_velocities(bodies, floor_plane(), no_gravity, dt, ContactVelocities::current);
  solver.correct_positions(bodies);
  EXPECT_GT(bodies[0].position.y(), 0.1 + 0.01);
  EXPECT_NEAR(bodies[0].position.x(), 0.0, 1e-12);
  EXPECT_NEAR(bodies[0].position.z(), 0.0, 1e-12);
  EXPECT_NEAR(bodies[0].orientation.angularDistance(box.orientation), 0.0, 1e-12);
}

TEST(ContactSolver, StaticBodiesNeverMove) {
  Body ground = make_box_body(1.0, Vec3(4, 1, 4));
  make_static(ground);
  std::vector<Body> bodies{ground, ball(1.0, 0.5, Vec3(0.3, 0.9, 0), Vec3(1, -3, 0))};
  bodies[1].restitution = 1.0;
  ContactSolver solver;
  solver.solve_velocities(bodies, {}, no_gravity, dt, ContactVelocities::current);
  solver.correct_positions(bodies);
  EXPECT_EQ(bodies[0].velocity, Vec3::Zero());
  EXPECT_EQ(bodies[0].position, Vec3::Zero());
  EXPECT_NEAR(bodies[1].velocity.y(), 3.0, 1e-12);  // e = 1 off an immovable box
  ASSERT_EQ(solver.contacts().size(), 1u);
  EXPECT_EQ(solver.contacts()[0].a, 0u);
  EXPECT_EQ(solver.contacts()[0].b, 1u);
  EXPECT_NEAR(solver.contacts()[0].depth, 0.1, 1e-15);
}

TEST(ContactSolver, RemovedBodiesAreForgottenAndTheOthersRenumbered) {
  std::vector<Body> bodies{ball(1, 0.5, Vec3(-5, 0.5, 0)), ball(1, 0.5, Vec3(0, 0.5, 0)),
                           ball(1, 0.5, Vec3(5, 0.5, 0))};
  ContactSolver solver;
  solver.solve_velocities(bodies, floor_plane(), gravity, dt, ContactVelocities::after_forces);
  ASSERT_EQ(solver.contacts().size(), 3u);
  solver.body_removed(1);
  ASSERT_EQ(solver.contacts().size(), 2u);
  EXPECT_EQ(solver.contacts()[0].b, 0u);
  EXPECT_EQ(solver.contacts()[1].b, 1u);
  EXPECT_EQ(solver.contacts()[1].plane, 0u);
  EXPECT_EQ(solver.contacts()[1].a, no_body);
}

TEST(ContactSolver, SaveAndRestore) {
  std::vector<Body> bodies{ball(1, 0.5, Vec3(0, 0.5, 0))};
  ContactSolver solver;
  solver.solve_velocities(bodies, floor_plane(), gravity, dt, ContactVelocities::after_forces);
  solver.save();
  const double impulse = solver.contacts()[0].normal_impulse;
  bodies[0].position.y() = 5;  // away: the next solve finds nothing
  solver.solve_velocities(bodies, floor_plane(), gravity, dt, ContactVelocities::after_forces);
  EXPECT_TRUE(solver.contacts().empty());
  solver.restore();
  ASSERT_EQ(solver.contacts().size(), 1u);
  EXPECT_EQ(solver.contacts()[0].normal_impulse, impulse);
}

TEST(ContactSettings, Problems) {
  ContactSettings s;
  EXPECT_EQ(contact_settings_problem(s), "");
  s.iterations = 0;
  EXPECT_EQ(contact_settings_problem(s), "iterations must be an integer from 1 to 1000, got 0");
  s = ContactSettings{};
  s.restitution_threshold = -1;
  EXPECT_EQ(contact_settings_problem(s), "restitution_threshold must be finite and >= 0, got -1");
  s = ContactSettings{};
  s.baumgarte = 2;
  EXPECT_EQ(contact_settings_problem(s), "baumgarte must be in [0, 1], got 2");
}

}  // namespace
}  // namespace rigidlab
