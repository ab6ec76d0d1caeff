// engine/step_poll.hpp and World::step's poll: the poll comes about every StepPoll::interval
// units of work, also inside one long substep (between the contact solver's sweeps), and a
// poll that throws stops the step and leaves the world exactly as before the call.
#include "engine/step_poll.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "engine/world.hpp"

namespace rigidlab {
namespace {

struct Stop {};  // what the test's poll throws: any exception stops a step

TEST(StepPoll, CallsEveryIntervalUnitsOfWork) {
  int calls = 0;
  const std::function<void()> count = [&calls] { ++calls; };
  StepPoll poll(count);
  for (std::size_t i = 0; i < 10 * StepPoll::interval; ++i) poll.tick(1);
  EXPECT_EQ(calls, 10);
  poll.tick(StepPoll::interval);  // one big chunk of work: one call
  EXPECT_EQ(calls, 11);
}

TEST(StepPoll, WithoutACallbackNothingHappens) {
  const std::function<void()> empty;
  StepPoll poll(empty);
  poll.tick(10 * StepPoll::interval);
  StepPoll none;
  none.tick(10 * StepPoll::interval);
}

// A 10 x 10 grid of boxes resting on a floor: every substep solves 400 contact points.
void fill_box_grid(World& w) {
  w.add_plane(make_plane(Vec3(0, 1, 0), 0.0));
  for (int i = 0; i < 100; ++i) {
    Body b = make_box_body(1.0, Vec3(1, 1, 1));
    b.position = Vec3(1.01 * (i % 10), 0.5, 1.01 * (i / 10));
    b.angular_velocity = Vec3(0, 0.1 * i, 0);
    w.add(b);
  }
  w.step(0.01, 3);  // contacts to warm-start from
}

void expect_same(const World& a, const World& b) {
  ASSERT_EQ(a.bodies().size(), b.bodies().size());
  EXPECT_EQ(a.time(), b.time());
  for (std::size_t i = 0; i < a.bodies().size(); ++i) {
    const Body& x = a.bodies()[i];
    const Body& y = b.bodies()[i];
    EXPECT_EQ(x.position, y.position) << "body " << i;
    EXPECT_EQ(x.orientation.coeffs(), y.orientation.coeffs()) << "body " << i;
    EXPECT_EQ(x.velocity, y.velocity) << "body " << i;
    EXPECT_EQ(x.angular_velocity, y.angular_velocity) << "body " << i;
    EXPECT_EQ(x.force, y.force) << "body " << i;
  }
  ASSERT_EQ(a.contacts().size(), b.contacts().size());
  for (std::size_t i = 0; i < a.contacts().size(); ++i) {
    EXPECT_EQ(a.contacts()[i].normal_impulse, b.contacts()[i].normal_impulse);
    EXPECT_EQ(a.contacts()[i].point, b.contacts()[i].point);
  }
}

// One substep of 1000 sweeps over 400 points is 400000 units: the poll comes between sweeps,
// not only between substeps.
TEST(WorldPoll, ComesInsideOneLongSubstep) {
  World w;
  fill_box_grid(w);
  ContactSettings settings = w.contact_settings();
  settings.iterations = ContactSettings::max_iterations;
  w.set_contact_settings(settings);
  int calls = 0;
  w.step(0.01, 1, [&calls] { ++calls; });
  EXPECT_GE(calls, 90);
}

TEST(WorldPoll, ComesBetweenSubstepsWithoutContacts) {
  World w;
  w.add(make_sphere_body(1.0, 0.5));
  w.set_substeps(World::max_substeps);
  int calls = 0;
  w.step(0.01, 100, [&calls] { ++calls; });
  // 10⁶ substeps of 2 units each.
  EXPECT_EQ(calls, static_cast<int>(2'000'000 / StepPoll::interval));
}

// Stopped in the middle of the contact solver of a later step, with forces applied before the
// call: the steps completed before it are kept (issue 12 item 19) and the stopped one is undone
// (bodies, accumulators, time and contacts), so the world is exactly where a twin that took
// only the completed steps is, and stepping on gives exactly what the twin gives.
TEST(WorldPoll, AThrowingPollUndoesTheStep) {
  for (Integrator integrator : {Integrator::semi_implicit, Integrator::rk4}) {
    World w, twin;
    for (World* x : {&w, &twin}) {
      x->set_integrator(integrator);
      fill_box_grid(*x);
      x->set_substeps(10);
      apply_force(x->bodies()[7], Vec3(3, 0, 0));
    }
    int calls = 0;
    EXPECT_THROW(w.step(0.01, 10, [&calls] {
      if (++calls == 40) throw Stop{};
    }),
                 Stop);
    EXPECT_EQ(calls, 40);
    EXPECT_FALSE(w.stepping());
    const long completed = w.steps_completed();
    EXPECT_GT(completed, 0);
    EXPECT_LT(completed, 10);
    twin.step(0.01, completed);
    expect_same(w, twin);
    w.step(0.01, 2);
    twin.step(0.01, 2);
    expect_same(w, twin);
  }
}

}  // namespace
}  // namespace rigidlab
