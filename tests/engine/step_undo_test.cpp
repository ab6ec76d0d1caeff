// The world's undo of a failed step (engine/world.cpp, World::save_step): the contacts the
// step started from are kept aside by the step's first store (ContactConstraints::begin_step),
// not copied. The reference is a twin world built and stepped the same way that never failed:
// after the undo, the failed world must hold its twin's contacts and bodies bit for bit, and
// stepping both again must keep them equal bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/world.hpp"
#include "tests/engine/both_solvers.hpp"
#include "tests/engine/world_stacks.hpp"

namespace rigidlab {
namespace {

constexpr double dt = 1.0 / 60.0;

// Every field of the contacts, bit for bit (an equal double compared with == would let a
// NaN or a −0 slip).
void expect_same_contacts(const std::vector<ContactInfo>& x, const std::vector<ContactInfo>& y) {
  ASSERT_EQ(x.size(), y.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    const ContactInfo& p = x[k];
    const ContactInfo& q = y[k];
    EXPECT_EQ(p.a, q.a);
    EXPECT_EQ(p.b, q.b);
    EXPECT_EQ(p.plane, q.plane);
    EXPECT_EQ(p.feature, q.feature);
    auto same = [](const auto& u, const auto& v) { return std::memcmp(&u, &v, sizeof u) == 0; };
    EXPECT_TRUE(same(p.point, q.point)) << k;
    EXPECT_TRUE(same(p.normal, q.normal)) << k;
    EXPECT_TRUE(same(p.depth, q.depth)) << k;
    EXPECT_TRUE(same(p.normal_impulse, q.normal_impulse)) << k;
    EXPECT_TRUE(same(p.friction_impulse, q.friction_impulse)) << k;
    EXPECT_TRUE(same(p.restitution, q.restitution)) << k;
    EXPECT_TRUE(same(p.friction, q.friction)) << k;
    EXPECT_TRUE(same(p.sweep_impulse, q.sweep_impulse)) << k;
  }
}

void expect_same_bodies(const World& x, const World& y) {
  ASSERT_EQ(x.bodies().size(), y.bodies().size());
  for (std::size_t i = 0; i < x.bodies().size(); ++i) {
    const Body& p = x.bodies()[i];
    const Body& q = y.bodies()[i];
    EXPECT_EQ(std::memcmp(p.position.data(), q.position.data(), sizeof(double) * 3), 0) << i;
    EXPECT_EQ(std::memcmp(p.velocity.data(), q.velocity.data(), sizeof(double) * 3), 0) << i;
    EXPECT_EQ(std::memcmp(p.angular_velocity.data(), q.angular_velocity.data(),
                          sizeof(double) * 3), 0) << i;
    EXPECT_EQ(std::memcmp(p.orientation.coeffs().data(), q.orientation.coeffs().data(),
                          sizeof(double) * 4), 0) << i;
  }
}

class StepUndo : public testing::TestWithParam<SolverKind> {};

// A heap of 64 spheres settling in a bin, three substeps per step; a force callback in both
// worlds, which in the failing one throws in the last substep of one step: two substeps have
// stored their contacts by then, so the undo must find the step's first contacts, not the
// last stored.
TEST_P(StepUndo, AFailureAfterTwoSubstepsRestoresTheContactsBitForBit) {
  World failing, twin;
  double throw_from = -1.0;  // s; the callback throws at stage times >= this when > 0
  int late_calls = 0;
  for (World* w : {&failing, &twin}) {
    w->set_solver(GetParam());
    w->set_substeps(3);
    fill_heap(*w, 64, 0.3);
    const bool fails = w == &failing;
    w->add_force([fails, &throw_from, &late_calls](World&, double t) {
      if (!fails || throw_from < 0.0 || t < throw_from) return;
      ++late_calls;
      throw std::runtime_error("stop");
    });
  }
  failing.step(dt, 40);
  twin.step(dt, 40);
  const std::vector<ContactInfo> before = failing.contacts();
  ASSERT_GT(before.size(), 64u);
  expect_same_contacts(before, twin.contacts());

  throw_from = failing.time() + 2.0 * dt / 3.0 - 1e-9;  // the third substep's stages
  EXPECT_THROW(failing.step(dt), std::runtime_error);
  EXPECT_EQ(late_calls, 1);  // it did fail in the third substep
  throw_from = -1.0;
  EXPECT_EQ(failing.time(), twin.time());
  expect_same_contacts(failing.contacts(), before);
  expect_same_bodies(failing, twin);

  for (int k = 0; k < 5; ++k) {
    failing.step(dt);
    twin.step(dt);
  }
  expect_same_contacts(failing.contacts(), twin.contacts());
  expect_same_bodies(failing, twin);
}

// Undo, saved states and stepping interleaved: a state saved, a failed step, a restored
// state, and the twin that only saw the restore agree bit for bit.
TEST_P(StepUndo, AFailedStepThenARestoredStateStepLikeTheTwin) {
  World failing, twin;
  bool armed = false;
  for (World* w : {&failing, &twin}) {
    w->set_solver(GetParam());
    fill_heap(*w, 32, 0.0);
    const bool fails = w == &failing;
    w->add_force([fails, &armed](World&, double) {
      if (fails && armed) throw std::runtime_error("stop");
    });
    w->step(dt, 30);
  }
  WorldState saved_failing, saved_twin;
  failing.save_state(saved_failing);
  twin.save_state(saved_twin);
  failing.step(dt, 3);
  twin.step(dt, 3);
  armed = true;
  EXPECT_THROW(failing.step(dt), std::runtime_error);
  armed = false;
  expect_same_contacts(failing.contacts(), twin.contacts());
  failing.restore_state(saved_failing);
  twin.restore_state(saved_twin);
  failing.step(dt, 4);
  twin.step(dt, 4);
  expect_same_contacts(failing.contacts(), twin.contacts());
  expect_same_bodies(failing, twin);
}

INSTANTIATE_FOR_BOTH_SOLVERS(StepUndo);

}  // namespace
}  // namespace rigidlab
