// Sleeping islands (engine/islands.hpp): a settled pyramid falls asleep and then never moves, a
// ball dropped on it wakes it and exchanges the momentum it would without sleeping, a moving
// pendulum never sleeps, sleeping off changes nothing, the wake rules, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "engine/joint.hpp"
#include "engine/world.hpp"
#include "world_stacks.hpp"

namespace rigidlab {
namespace {

constexpr double dt = 1.0 / 60.0;

std::size_t count_sleeping(const World& w) { return w.sleeping_count(); }

bool all_sleeping(const World& w) {
  for (const Body& b : w.bodies())
    if (!is_static(b) && !b.sleeping) return false;
  return true;
}

// Steps until every dynamic body sleeps; returns the time it took (s), or -1 past `limit`.
double step_until_asleep(World& w, double limit) {
  const double start = w.time();
  while (w.time() - start < limit) {
    w.step(dt);
    if (all_sleeping(w)) return w.time() - start;
  }
  return -1.0;
}

// Bit patterns of every body's state: equal only when the states are identical.
std::vector<unsigned char> state_bytes(const World& w) {
  std::vector<unsigned char> bytes;
  auto put = [&bytes](const double* p, std::size_t n) {
    const auto* c = reinterpret_cast<const unsigned char*>(p);
    bytes.insert(bytes.end(), c, c + n * sizeof(double));
  };
  for (const Body& b : w.bodies()) {
    put(b.position.data(), 3);
    put(b.orientation.coeffs().data(), 4);
    put(b.velocity.data(), 3);
    put(b.angular_velocity.data(), 3);
  }
  return bytes;
}

double max_position_difference(const World& a, const World& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.bodies().size(); ++i)
    d = std::max(d, (a.bodies()[i].position - b.bodies()[i].position).norm());
  return d;
}

TEST(Sleep, OffByDefaultAndNothingSleeps) {
  World w;
  EXPECT_FALSE(w.sleeping());
  build_stack(w, 5, true);
  for (int k = 0; k < 300; ++k) w.step(dt);
  EXPECT_EQ(count_sleeping(w), 0u);
  for (const Body& b : w.bodies()) EXPECT_EQ(b.sleep_time, 0.0);
}

// The sleep machinery with no island ever asleep (a sleep time longer than the run) leaves
// the motion bit for bit as with sleeping off.
TEST(Sleep, MachineryWithoutSleepersChangesNothing) {
  World off, on;
  build_stack(off, 5, true);
  build_stack(on, 5, true);
  on.set_sleeping(true);
  SleepSettings never;
  never.time = 1e9;
  on.set_sleep_settings(never);
  for (int k = 0; k < 240; ++k) {
    off.step(dt);
    on.step(dt);
  }
  EXPECT_EQ(state_bytes(off), state_bytes(on));
  EXPECT_EQ(count_sleeping(on), 0u);
}

// A 15-box pyramid whose rows are dropped from 5 cm gaps lands, settles and falls asleep
// within 3 s; asleep, it does not move at all for 10 s (bit-identical states), and it is where
// the same pyramid without sleeping is at the same time within 5 mm (issue 13's creep bound
// for an awake pyramid in 10 s: the sleeping one does not creep).
void build_dropped_pyramid(World& w) {
  w.add_plane(make_plane(Vec3(0, 1, 0), 0.0, 0.0, default_friction));
  for (int row = 0; row < 5; ++row)
    for (int k = 0; k < 5 - row; ++k) {
      Body box = make_box_body(1.0, Vec3(1, 1, 1));
      box.position = Vec3(k - 0.5 * (4 - row), 0.5 + 1.05 * row + 0.05, 0);
      w.add(box);
    }
}

TEST(Sleep, PyramidFallsAsleepAndStaysPut) {
  World w, awake;
  build_dropped_pyramid(w);
  build_dropped_pyramid(awake);
  w.set_sleeping(true);
  const double took = step_until_asleep(w, 3.0);
  ASSERT_GT(took, 0.0) << "the pyramid did not fall asleep within 3 s";
  std::printf("took %g\n", took);
  EXPECT_GE(took, w.sleep_settings().time);
  const std::vector<unsigned char> asleep = state_bytes(w);
  for (int k = 0; k < 600; ++k) {
    w.step(dt);
    ASSERT_TRUE(all_sleeping(w)) << "woke at t = " << w.time();
  }
  EXPECT_EQ(state_bytes(w), asleep);
  while (awake.time() < w.time() - 0.5 * dt) awake.step(dt);
  const double gap = max_position_difference(w, awake);
  EXPECT_LT(gap, 0.005) << "sleeping pyramid vs awake pyramid at t = " << w.time();
  for (const Body& b : w.bodies()) {
    if (is_static(b)) continue;
    EXPECT_EQ(b.velocity, Vec3::Zero());
    EXPECT_EQ(b.angular_velocity, Vec3::Zero());
  }
}

// A heap of 256 balls dropped into a bin (the bench's settling heap) settles and falls asleep
// whole within 10 s, although a few of its balls keep spinning about their contact normals
// (the contact model has no spin friction: engine/islands.hpp, the shape rule) and balls on the
// floor rest a hair from their neighbours (speculative contacts: the linking rule).
TEST(Sleep, SettledHeapOfBallsFallsAsleep) {
  World w;
  fill_heap(w, 256, 0.0);
  w.set_sleeping(true);
  EXPECT_GT(step_until_asleep(w, 10.0), 0.0);
}

// Drops a 2 kg ball (restitution 0.5) from 1 m above the top box of a column of `boxes` unit
// boxes that has stood for 3 s (asleep when `sleeping`), and records the ball's vertical
// velocity each step.
struct DropResult {
  std::vector<double> ball_velocity;  // m/s, after each step
  bool woke = false;                  // every box of the column woke while the ball fell
  std::vector<unsigned char> bytes;
};

DropResult drop_ball_on_column(bool sleeping, int boxes) {
  World w;
  build_stack(w, boxes, false);
  w.set_sleeping(sleeping);
  for (int k = 0; k < 180; ++k) w.step(dt);
  EXPECT_EQ(count_sleeping(w), sleeping ? std::size_t(boxes) : 0u);
  Body ball = make_sphere_body(2.0, 0.25);
  ball.position = Vec3(0.1, boxes + 1.0 + 0.25, 0.05);
  ball.restitution = 0.5;
  const BodyId id = w.add(ball);
  DropResult r;
  for (int k = 0; k < 45; ++k) {  // 0.75 s: the ball lands at 0.45 s
    w.step(dt);
    r.ball_velocity.push_back(w.store().get(id).velocity.y());
  }
  r.woke = count_sleeping(w) == 0;
  r.bytes = state_bytes(w);
  return r;
}

// The ball wakes the sleeping box and bounces off it as off the awake one, and as the closed
// form: a box resting on the floor is a rigid support, so the ball leaves on the reflected
// parabola, e √(2 g h) at the surface, which the step's end velocity shows as e √(2 g h) +
// g Δt/2 (engine/contact_constraints.hpp, restitution). On a column of boxes as well (below;
// the rebound from columns of 1-5 boxes is tests/engine/bounce_on_stack_test.cpp's).
void expect_bounce_as_awake(int boxes) {
  SCOPED_TRACE(std::to_string(boxes) + " boxes");
  const DropResult asleep = drop_ball_on_column(true, boxes);
  const DropResult awake = drop_ball_on_column(false, boxes);
  EXPECT_TRUE(asleep.woke);
  const double impact = std::sqrt(2.0 * 9.81 * 1.0);
  double rebound = 0.0;
  for (std::size_t k = 0; k < asleep.ball_velocity.size(); ++k) {
    EXPECT_NEAR(2.0 * asleep.ball_velocity[k], 2.0 * awake.ball_velocity[k], 0.01 * 2.0 * impact)
        << "step " << k;
    rebound = std::max(rebound, asleep.ball_velocity[k]);
  }
  EXPECT_NEAR(rebound, 0.5 * impact + 9.81 * dt / 2, 0.005 * 0.5 * impact);
  // Determinism: the same script, the same states.
  EXPECT_EQ(drop_ball_on_column(true, boxes).bytes, asleep.bytes);
}

TEST(Sleep, BallWakesSleepingBoxAndBouncesAsOffTheAwakeOne) { expect_bounce_as_awake(1); }

// A ball landing on the top of a sleeping column of three wakes the whole island, not only
// the box it touches, and bounces as off the awake column (asleep 2.296781 m/s, awake
// 2.296764; before the restitution stage held a column as one support, 964b212, the two
// differed by 3 %).
TEST(Sleep, BallWakesAWholeSleepingColumn) { expect_bounce_as_awake(3); }

// A frictionless 1 kg box slides at 4 m/s into a sleeping 1 kg box (friction 0.6 on the
// floor). The impact (e = 0) is perfectly inelastic: both move on at m v / (2 m) = 2 m/s, less
// the floor's friction impulse in that step (at most μ m g dt), and the pair then slows at
// μ g / 2. The sleeping run matches that, and the run without sleeping within 1 % of m v.
TEST(Sleep, SlidingBoxWakesSleepingBoxAndSharesItsMomentum) {
  auto run = [](bool sleeping) {
    World w;
    w.add_plane(make_plane(Vec3(0, 1, 0), 0.0, 0.0, default_friction));
    Body target = make_box_body(1.0, Vec3(1, 1, 1));
    target.position = Vec3(0, 0.5, 0);
    w.add(target);
    w.set_sleeping(sleeping);
    for (int k = 0; k < 60; ++k) w.step(dt);
    EXPECT_EQ(w.bodies()[0].sleeping, sleeping);
    Body puck = make_box_body(1.0, Vec3(1, 1, 1));
    puck.position = Vec3(-1.5, 0.5, 0);
    puck.velocity = Vec3(4.0, 0, 0);
    puck.friction = 0.0;
    w.add(puck);
    std::vector<double> momentum;
    for (int k = 0; k < 30; ++k) {
      w.step(dt);
      momentum.push_back(w.bodies()[0].velocity.x() + w.bodies()[1].velocity.x());
      EXPECT_FALSE(w.bodies()[0].sleeping && w.bodies()[1].position.x() > -1.0);
    }
    return std::pair{momentum, w.bodies()[0].velocity.x()};
  };
  const auto [asleep, target_asleep] = run(true);
  const auto [awake, target_awake] = run(false);
  for (std::size_t k = 0; k < asleep.size(); ++k)
    EXPECT_NEAR(asleep[k], awake[k], 0.01 * 4.0) << "step " << k;
  const double mu_g = default_friction * 9.81;
  // 0.5 s after the puck set off (impact at 0.125 s): 4 − μ m g (t − t_impact) within a step.
  EXPECT_NEAR(asleep.back(), 4.0 - mu_g * (0.5 - 0.125), mu_g * dt);
  EXPECT_NEAR(target_asleep, target_awake, 0.01 * 4.0);
}

// A pendulum (ball joint to the world, 1 m, released at 30°) is slower than 0.05 m/s only for
// a few milliseconds at each turning point: it never sleeps, and swings as without sleeping.
TEST(Sleep, SwingingPendulumNeverSleeps) {
  auto make = [](World& w, double angle = M_PI / 6) {
    Body bob = make_sphere_body(1.0, 0.05);
    bob.position = Vec3(std::sin(angle), -std::cos(angle), 0);
    const BodyId id = w.add(bob);
    JointDef def;
    def.type = JointKind::ball;
    def.a = id;
    def.anchor = Vec3::Zero();
    w.add_constraint(std::make_unique<Joint>(def, w.store().get(id), nullptr));
  };
  World w, off;
  make(w);
  make(off);
  w.set_sleeping(true);
  for (int k = 0; k < 1200; ++k) {
    w.step(dt);
    off.step(dt);
    ASSERT_FALSE(w.bodies()[0].sleeping) << "t = " << w.time();
  }
  EXPECT_EQ(state_bytes(w), state_bytes(off));
  // The control: the same pendulum hanging at rest falls asleep within 0.5 s and a step.
  World rest;
  make(rest, 0.0);
  rest.set_sleeping(true);
  const double took = step_until_asleep(rest, 1.0);
  EXPECT_GT(took, 0.0);
  EXPECT_LE(took, rest.sleep_settings().time + 1.5 * dt);
}

// A ball flying over the sleeping pyramid 0.5 m above its top does not touch it: the pyramid
// sleeps on, bit for bit.
TEST(Sleep, BodyFlyingPastDoesNotWakeAnIslandItDoesNotTouch) {
  World w;
  build_stack(w, 5, true);
  w.set_sleeping(true);
  ASSERT_GT(step_until_asleep(w, 3.0), 0.0);
  const std::vector<unsigned char> asleep = state_bytes(w);
  const std::size_t sleepers = count_sleeping(w);
  Body ball = make_sphere_body(1.0, 0.1);
  ball.position = Vec3(-4.0, 5.0 + 0.5 + 0.1 + 0.35, 0.0);  // top face at 5 m
  ball.velocity = Vec3(25.0, 0.0, 0.0);
  const BodyId id = w.add(ball);
  for (int k = 0; k < 24; ++k) {  // 0.4 s: 10 m of flight, the drop 0.8 m, past x = +2.5 in 0.26 s
    w.step(dt);
    EXPECT_EQ(count_sleeping(w), sleepers) << "t = " << w.time();
  }
  EXPECT_GT(w.store().get(id).position.x(), 4.0);
  std::vector<unsigned char> now = state_bytes(w);
  now.resize(asleep.size());  // the pyramid's bodies come first
  EXPECT_EQ(now, asleep);
}

World& sleeping_column(World& w) {
  build_stack(w, 3, false);
  w.set_sleeping(true);
  EXPECT_GT(step_until_asleep(w, 3.0), 0.0);
  return w;
}

// The viewer's rewind: a state saved with islands asleep, restored and stepped again, gives
// the same states and sleep flags bit for bit (a ball landing on the sleeping column between).
TEST(Sleep, RestoredStateStepsTheSameWithSleepers) {
  World w;
  build_stack(w, 3, false);
  w.set_sleeping(true);
  ASSERT_GT(step_until_asleep(w, 3.0), 0.0);
  Body ball = make_sphere_body(2.0, 0.25);
  ball.position = Vec3(0.1, 3.5, 0.05);
  w.add(ball);
  WorldState saved;
  w.save_state(saved);
  auto run = [&w] {
    w.step(dt, 90);
    std::vector<unsigned char> bytes = state_bytes(w);
    for (const Body& b : w.bodies()) bytes.push_back(b.sleeping ? 1 : 0);
    return bytes;
  };
  const std::vector<unsigned char> first = run();
  w.restore_state(saved);
  EXPECT_EQ(count_sleeping(w), 3u);
  EXPECT_EQ(run(), first);
}

TEST(Sleep, DisturbingABodyWakesItsIsland) {
  {
    World w;
    sleeping_column(w);
    w.bodies()[1].velocity = Vec3(0.5, 0, 0);  // a velocity set between steps
    w.step(dt);
    EXPECT_EQ(count_sleeping(w), 0u);
    EXPECT_GT(w.bodies()[1].position.x(), 0.0);
  }
  {
    World w;
    sleeping_column(w);
    apply_force(w.bodies()[2], Vec3(10, 0, 0));
    w.step(dt);
    EXPECT_EQ(count_sleeping(w), 0u);
  }
  {
    World w;
    sleeping_column(w);
    w.wake(w.store().id_at(0));
    EXPECT_EQ(count_sleeping(w), 0u);  // the whole column: one island through its contacts
  }
  {
    World w;
    sleeping_column(w);
    w.set_sleeping(false);
    EXPECT_EQ(count_sleeping(w), 0u);
  }
  {
    World w;
    sleeping_column(w);
    w.remove(w.store().id_at(0));  // the bottom box: the two above must fall
    EXPECT_EQ(count_sleeping(w), 0u);
    const double y = w.bodies()[0].position.y();
    for (int k = 0; k < 30; ++k) w.step(dt);
    EXPECT_LT(w.bodies()[0].position.y(), y - 0.3);
  }
  {
    World w;
    sleeping_column(w);
    Spring s;
    s.a = w.store().id_at(2);
    s.anchor = Vec3(0, 10, 0);
    s.stiffness = 100.0;
    s.rest_length = 0.0;
    w.add_spring(s);
    EXPECT_EQ(count_sleeping(w), 0u);
  }
}

// Sleeping turned off, then a sleeping body removed: the other keeps its own mass properties
// through the next steps (a body once frozen got the removed one's inverse mass back: a 10 kg
// box then took a 10 N s blow as 1 kg, at 10 m/s).
TEST(Sleep, MassPropertiesStayTheBodysOwnAfterSleepingIsOff) {
  World w;
  w.set_gravity(Vec3::Zero());
  Body light = make_box_body(1.0, Vec3(1, 1, 1));
  Body heavy = make_box_body(10.0, Vec3(1, 1, 1));
  heavy.position = Vec3(5, 0, 0);
  const BodyId a = w.add(light);
  const BodyId b = w.add(heavy);
  w.set_sleeping(true);
  for (int k = 0; k < 60; ++k) w.step(dt);
  ASSERT_EQ(count_sleeping(w), 2u);
  w.set_sleeping(false);
  w.remove(a);
  for (int k = 0; k < 2; ++k) w.step(dt);
  EXPECT_EQ(w.store().get(b).inverse_mass, 1.0 / 10.0);
  EXPECT_EQ(w.store().get(b).inverse_inertia, heavy.inverse_inertia);
}

// Two islands: waking one leaves the other asleep; a static floor links nothing.
TEST(Sleep, SeparateIslandsSleepAndWakeApart) {
  World w;
  w.add_plane(make_plane(Vec3(0, 1, 0), 0.0, 0.0, default_friction));
  for (double x : {-3.0, 3.0}) {
    Body box = make_box_body(1.0, Vec3(1, 1, 1));
    box.position = Vec3(x, 0.5, 0);
    w.add(box);
  }
  w.set_sleeping(true);
  ASSERT_GT(step_until_asleep(w, 3.0), 0.0);
  EXPECT_NE(w.bodies()[0].island, w.bodies()[1].island);
  w.wake(w.store().id_at(0));
  EXPECT_FALSE(w.bodies()[0].sleeping);
  EXPECT_TRUE(w.bodies()[1].sleeping);
}

TEST(Sleep, BadSettingsAreRefusedAndChangeNothing) {
  World w;
  for (double bad : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    SleepSettings s;
    s.linear = bad;
    EXPECT_THROW(w.set_sleep_settings(s), std::invalid_argument);
    s = SleepSettings{};
    s.time = bad;
    EXPECT_THROW(w.set_sleep_settings(s), std::invalid_argument);
  }
  EXPECT_EQ(w.sleep_settings().linear, 0.05);
  EXPECT_EQ(w.sleep_settings().time, 0.5);
  EXPECT_THROW(w.wake(BodyId{}), std::invalid_argument);
}

// A world with a force callback keeps every body awake: the callback may push any of them.
TEST(Sleep, ForceCallbackKeepsEveryoneAwake) {
  World w;
  sleeping_column(w);
  w.add_force([](World&, double) {});
  EXPECT_EQ(count_sleeping(w), 0u);
  for (int k = 0; k < 120; ++k) w.step(dt);
  EXPECT_EQ(count_sleeping(w), 0u);
}

}  // namespace
}  // namespace rigidlab
