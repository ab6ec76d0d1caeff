// Contacts inside World::step, judged by physics: a dropped ball rebounds to e² of its height
// (001_* Appendix C, 003_* "Collision Response"), a ball pushed along a floor ends rolling at
// 5/7 of its speed (angular momentum about the contact point), bodies at rest stay put, a
// box landing flat does not spin and one landing on an edge does, a stack stands, colliding
// balls conserve momentum (and energy when e = 1), e = 0 does not bounce, friction 0 never
// spins a ball; plus the world's bookkeeping: undo, removal, no allocation per step.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <stdexcept>

#include "engine/world.hpp"

// Counts heap allocations, to check that stepping a world with contacts allocates nothing once
// its buffers have grown (common brief: no per-step heap allocation).
namespace {
std::atomic<long> allocations{0};
}
void* operator new(std::size_t size) {
  ++allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace rigidlab {
namespace {

const Integrator all_integrators[] = {Integrator::euler, Integrator::semi_implicit,
                                      Integrator::rk4};

// A world with the floor y >= 0 (restitution e, friction mu).
void add_floor(World& w, double restitution = 0.0, double friction = default_friction) {
  w.add_plane(make_plane(Vec3(0, 1, 0), 0.0, restitution, friction));
}

Body sphere_at(double radius, const Vec3& position, double restitution = 0.0) {
  Body b = make_sphere_body(1.0, radius);
  b.position = position;
  b.restitution = restitution;
  return b;
}

// Drops a ball of radius 0.1 from `height` (its bottom above the floor) and returns the apex
// of its bottom after the first bounce.
double rebound_apex(double height, double e, Integrator integrator, double dt) {
  World w;
  w.set_integrator(integrator);
  add_floor(w, e);
  w.add(sphere_at(0.1, Vec3(0, height + 0.1, 0), e));
  const Body& b = w.bodies()[0];
  bool rising = false;
  double apex = 0.0;
  for (int i = 0; i < 100000; ++i) {
    w.step(dt);
    if (b.velocity.y() > 0.0) rising = true;
    if (rising) {
      apex = std::max(apex, b.position.y() - 0.1);
      if (b.velocity.y() < 0.0) break;
    }
  }
  return apex;
}

TEST(WorldContacts, DroppedBallReboundsToESquaredOfItsHeight) {
  const double h = 1.0, e = 0.8, want = e * e * h;
  // The impact is resolved at a step boundary, a gap of up to |v| Δt before the surface, so
  // the apex is first order in Δt (and so is semi-implicit Euler's free flight): within 3 %
  // at 1 kHz, and the error at 240 Hz is less than half that at 60 Hz.
  for (Integrator integrator : all_integrators) {
    EXPECT_NEAR(rebound_apex(h, e, integrator, 1e-3) / want, 1.0, 0.03);
    const double error_60 = std::abs(rebound_apex(h, e, integrator, 1.0 / 60) - want);
    const double error_240 = std::abs(rebound_apex(h, e, integrator, 1.0 / 240) - want);
    EXPECT_LT(error_240, 0.5 * error_60) << integrator_names[int(integrator)];
  }
}

TEST(WorldContacts, RestitutionZeroDoesNotBounce) {
  for (Integrator integrator : all_integrators) {
    World w;
    w.set_integrator(integrator);
    add_floor(w);
    w.add(sphere_at(0.2, Vec3(0, 1.2, 0)));
    double highest_after_landing = 0.0;
    bool landed = false;
    for (int i = 0; i < 180; ++i) {
      w.step(1.0 / 60.0);
      const double y = w.bodies()[0].position.y();
      if (y < 0.2 + 1e-6) landed = true;
      if (landed) highest_after_landing = std::max(highest_after_landing, y);
    }
    EXPECT_TRUE(landed);
    EXPECT_LT(highest_after_landing - 0.2, 1e-6) << integrator_names[int(integrator)];
    EXPECT_NEAR(w.bodies()[0].position.y(), 0.2, 1e-3) << integrator_names[int(integrator)];
  }
}

TEST(WorldContacts, BallPushedAlongTheFloorEndsRollingAtFiveSevenths) {
  // Friction acts at the contact point, so the angular momentum about it, m v R + I ω, is
  // kept: m v₀ R = m v R + (2/5) m R² (v/R) when rolling, v = 5/7 v₀.
  for (Integrator integrator : all_integrators) {
    World w;
    w.set_integrator(integrator);
    add_floor(w, 0.0, 0.3);
    const double radius = 0.25, v0 = 3.0;
    Body b = sphere_at(radius, Vec3(0, radius, 0));
    b.velocity = Vec3(v0, 0, 0);
    w.add(b);
    w.step(1.0 / 60.0, 120);
    const Body& ball = w.bodies()[0];
    EXPECT_NEAR(ball.velocity.x() / (5.0 / 7.0 * v0), 1.0, 0.02)
        << integrator_names[int(integrator)];
    EXPECT_NEAR(-ball.angular_velocity.z() * radius, ball.velocity.x(), 1e-9);  // no slip
  }
}

// A body on a slope of angle θ (friction μ on both surfaces): from 1 s to 2 s after release,
// its speed gains a (m/s²) · 1 s. Returns a.
double slope_acceleration(Body body, double theta_degrees, double mu, double height) {
  const double theta = theta_degrees * M_PI / 180.0;
  const Vec3 normal(-std::sin(theta), std::cos(theta), 0.0);  // downhill is +x
  World w;
  w.add_plane(make_plane(normal, 0.0, 0.0, mu));
  body.friction = mu;
  body.orientation = quat_from_axis_angle(Vec3(0, 0, 1), theta);
  body.position = height * normal;
  w.add(body);
  w.step(1.0 / 60.0, 60);
  const double v1 = w.bodies()[0].velocity.norm();
  w.step(1.0 / 60.0, 60);
  return w.bodies()[0].velocity.norm() - v1;
}

TEST(WorldContacts, InclinedPlaneCoulombAndRolling) {
  // A box stays below the friction angle (tan 20° < 0.5) and slides above it with
  // a = g (sin θ − μ cos θ) (Coulomb: friction μ N against the slip); a ball rolls down at
  // a = 5/7 g sin θ (I = 2/5 m r², no slip while tan θ <= 7/2 μ).
  const double g = 9.81, mu = 0.5;
  const Body box = make_box_body(1.0, Vec3(0.4, 0.2, 0.4));
  const Body ball = make_sphere_body(1.0, 0.2);
  EXPECT_NEAR(slope_acceleration(box, 20, mu, 0.1), 0.0, 1e-9);
  for (double degrees : {30.0, 40.0}) {
    const double theta = degrees * M_PI / 180.0;
    EXPECT_NEAR(slope_acceleration(box, degrees, mu, 0.1),
                g * (std::sin(theta) - mu * std::cos(theta)), 1e-6)
        << degrees;
    EXPECT_NEAR(slope_acceleration(ball, degrees, mu, 0.2), 5.0 / 7.0 * g * std::sin(theta), 1e-6)
        << degrees;
  }
}

TEST(WorldContacts, BallAtRestDriftsLessThanAMillimetreInTenSeconds) {
  for (Integrator integrator : all_integrators) {
    World w;
    w.set_integrator(integrator);
    add_floor(w);
    w.add(sphere_at(0.3, Vec3(1, 0.3, 2)));
    double drift = 0.0;
    for (int i = 0; i < 600; ++i) {
      w.step(1.0 / 60.0);
      drift = std::max(drift, (w.bodies()[0].position - Vec3(1, 0.3, 2)).norm());
    }
    EXPECT_LT(drift, 1e-3) << integrator_names[int(integrator)];
  }
}

// Drops a box (1 x 0.5 x 0.7 m) from 1 m with its centre 1 m up, turned by `tilt` about z;
// returns the largest angular speed over two seconds.
double largest_spin_of_landing_box(double tilt) {
  World w;
  add_floor(w);
  Body box = make_box_body(1.0, Vec3(1.0, 0.5, 0.7));
  box.position = Vec3(0, 1.0, 0);
  box.orientation = quat_from_axis_angle(Vec3(0, 0, 1), tilt);
  w.add(box);
  double largest = 0.0;
  for (int i = 0; i < 120; ++i) {
    w.step(1.0 / 60.0);
    largest = std::max(largest, w.bodies()[0].angular_velocity.norm());
  }
  EXPECT_NEAR(w.bodies()[0].position.y(), 0.25, 1e-3) << "tilt " << tilt;  // flat at the end
  return largest;
}

TEST(WorldContacts, BoxLandingFlatDoesNotSpinOneLandingOnAnEdgeDoes) {
  // 001_* "Collisions": four contacts of a face give torques that cancel, "a pure
  // translational motion"; an edge (two contacts) gives a net torque.
  EXPECT_LT(largest_spin_of_landing_box(0.0), 1e-3);
  EXPECT_GT(largest_spin_of_landing_box(0.3), 1.0);
}

TEST(WorldContacts, StackOfThreeBoxesStandsForTenSeconds) {
  World w;
  add_floor(w);
  for (int k = 0; k < 3; ++k) {
    Body box = make_box_body(1.0, Vec3(1, 1, 1));
    box.position = Vec3(0, 0.5 + k, 0);
    w.add(box);
  }
  const Vec3 start = w.bodies()[2].position;
  double moved = 0.0;
  for (int i = 0; i < 600; ++i) {
    w.step(1.0 / 60.0);
    moved = std::max(moved, (w.bodies()[2].position - start).norm());
  }
  EXPECT_LT(moved, 0.01);
  for (const Body& b : w.bodies()) EXPECT_LT(b.angular_velocity.norm(), 1e-6);
}

TEST(WorldContacts, HeadOnBallsConserveMomentumAndElasticOnesEnergy) {
  // 003_* "Collision Response": m₁v₁ + m₂v₂ is kept; with e = 1 so is the kinetic energy, and
  // the velocities are those of the 1-D elastic collision (001_* Appendix C).
  World w;
  w.set_gravity(Vec3::Zero());
  Body a = make_sphere_body(2.0, 0.3), b = make_sphere_body(1.0, 0.2);
  a.position = Vec3(-1, 0, 0), a.velocity = Vec3(2, 0, 0), a.restitution = 1.0;
  b.position = Vec3(1, 0, 0), b.velocity = Vec3(-3, 0, 0), b.restitution = 1.0;
  w.add(a);
  w.add(b);
  const Vec3 p0 = w.linear_momentum();
  const double e0 = w.kinetic_energy();
  w.step(1.0 / 60.0, 60);
  EXPECT_NEAR((w.linear_momentum() - p0).norm(), 0.0, 1e-12);
  EXPECT_NEAR(w.kinetic_energy(), e0, 1e-12 * e0);
  // v_a' = ((m_a − m_b) v_a + 2 m_b v_b)/(m_a + m_b) = (2 − 6)/3, v_b' = (−3 + 8)/3... as
  // v_b' = ((m_b − m_a) v_b + 2 m_a v_a)/(m_a + m_b) = (3 + 8)/3.
  EXPECT_NEAR(w.bodies()[0].velocity.x(), -4.0 / 3.0, 1e-12);
  EXPECT_NEAR(w.bodies()[1].velocity.x(), 11.0 / 3.0, 1e-12);
  // Off-centre with friction and spin: momentum and angular momentum are still kept.
  World v;
  v.set_gravity(Vec3::Zero());
  a.position = Vec3(-1, 0.1, 0.05), a.angular_velocity = Vec3(1, 2, 3);
  b.position = Vec3(1, -0.1, 0), b.friction = 1.0;
  v.add(a);
  v.add(b);
  const Vec3 q0 = v.linear_momentum(), l0 = v.angular_momentum(Vec3(0.3, 0.2, 0.1));
  v.step(1.0 / 60.0, 60);
  EXPECT_NEAR((v.linear_momentum() - q0).norm(), 0.0, 1e-12);
  EXPECT_NEAR((v.angular_momentum(Vec3(0.3, 0.2, 0.1)) - l0).norm(), 0.0, 1e-12);
  EXPECT_GT(v.bodies()[1].angular_velocity.norm(), 0.1);  // friction made b spin
}

TEST(WorldContacts, FrictionlessFloorNeverSpinsABall) {
  // Without friction the floor pushes along the normal, through the centre: no torque.
  for (Integrator integrator : all_integrators) {
    World w;
    w.set_integrator(integrator);
    add_floor(w, 0.5, 0.0);
    Body b = sphere_at(0.2, Vec3(0, 1, 0), 0.5);
    b.velocity = Vec3(3, -2, 1);
    w.add(b);
    for (int i = 0; i < 300; ++i) {
      w.step(1.0 / 60.0);
      ASSERT_EQ(w.bodies()[0].angular_velocity, Vec3::Zero()) << integrator_names[int(integrator)];
    }
    EXPECT_NEAR(w.bodies()[0].velocity.x(), 3.0, 1e-12);  // and never slows it
  }
}

TEST(WorldContacts, BodiesWithoutShapesDoNotCollide) {
  World w;
  add_floor(w);
  w.add(make_body(1.0, Mat3::Identity()));
  w.step(0.1, 10);
  // Fell through: semi-implicit Euler from rest gives y_n = −g Δt² n(n + 1)/2.
  EXPECT_NEAR(w.bodies()[0].position.y(), -9.81 * 0.01 * 55, 1e-12);
  EXPECT_TRUE(w.contacts().empty());
}

TEST(WorldContacts, AFailedStepLeavesTheContactsAsTheyWere) {
  World w;
  add_floor(w);
  w.add(sphere_at(0.2, Vec3(0, 0.2, 0)));
  w.step(0.01);
  const std::vector<ContactInfo> before = w.contacts();
  const Body body_before = w.bodies()[0];
  ASSERT_EQ(before.size(), 1u);
  w.add_force([](World&, double) { throw std::runtime_error("stop"); });
  w.bodies()[0].position.y() = 3.0;  // the next step would find no contact
  EXPECT_THROW(w.step(0.01), std::runtime_error);
  ASSERT_EQ(w.contacts().size(), 1u);
  EXPECT_EQ(w.contacts()[0].normal_impulse, before[0].normal_impulse);
  EXPECT_EQ(w.bodies()[0].position.y(), 3.0);
  EXPECT_EQ(w.bodies()[0].velocity, body_before.velocity);
}

TEST(WorldContacts, RemovingABodyForgetsItsContacts) {
  World w;
  add_floor(w);
  const auto first = w.add(sphere_at(0.2, Vec3(-3, 0.2, 0)));
  w.add(sphere_at(0.2, Vec3(3, 0.2, 0)));
  w.step(0.01);
  ASSERT_EQ(w.contacts().size(), 2u);
  w.remove(first);
  ASSERT_EQ(w.contacts().size(), 1u);
  EXPECT_EQ(w.contacts()[0].b, 0u);  // the other ball, now first
  w.step(0.01);
  EXPECT_EQ(w.contacts().size(), 1u);
}

TEST(WorldContacts, SettingsAndPlanesAreChecked) {
  World w;
  ContactSettings s;
  s.iterations = 0;
  EXPECT_THROW(w.set_contact_settings(s), std::invalid_argument);
  s.iterations = 25;
  w.set_contact_settings(s);
  EXPECT_EQ(w.contact_settings().iterations, 25);
  Plane bad;
  bad.normal = Vec3::Zero();
  EXPECT_THROW(w.add_plane(bad), std::invalid_argument);
  EXPECT_EQ(w.add_plane(make_plane(Vec3(0, 3, 0), 3)), 0u);
  EXPECT_EQ(w.planes()[0].offset, 1.0);
}

TEST(WorldContacts, SteppingAllocatesNothingOnceWarm) {
  World w;
  add_floor(w);
  for (int k = 0; k < 3; ++k) {
    Body box = make_box_body(1.0, Vec3(1, 1, 1));
    box.position = Vec3(0.1 * k, 0.5 + k, 0);
    w.add(box);
  }
  for (int i = 0; i < 10; ++i) {
    Body ball = sphere_at(0.2, Vec3(-3 + 0.45 * i, 0.2 + 0.1 * i, 2));
    w.add(ball);
  }
  for (Integrator integrator : all_integrators) {
    w.set_integrator(integrator);
    for (int i = 0; i < 30; ++i) w.step(1.0 / 60.0);  // buffers grow to what the scene needs
    const long before = allocations.load();
    for (int i = 0; i < 60; ++i) w.step(1.0 / 60.0);
    EXPECT_EQ(allocations.load() - before, 0) << integrator_names[int(integrator)];
  }
}

}  // namespace
}  // namespace rigidlab
