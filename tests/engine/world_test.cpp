// Tests for engine/world.cpp and engine/forces.cpp: the body store (stable ids, order, life
// after the world), springs against statics (deflection mg/k) and energy conservation, drag
// against its exponential closed form, force callbacks at RK4 stages, substeps, and the step's
// guarantees: a non-finite state, a throwing callback or a re-entrant step leave the world
// exactly as before.
#include "engine/format.hpp"
#include "engine/world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace rigidlab {
namespace {

Body ball(const Vec3& position = Vec3::Zero()) {
  Body b = make_sphere_body(2.0, 0.5);
  b.position = position;
  return b;
}

Body tumbling_ball() {
  Body b = make_box_body(2.0, Vec3(1, 2, 3));
  b.angular_velocity = Vec3(1, 2, 0.5);
  b.velocity = Vec3(0, 3, 0);
  return b;
}

void expect_same_state(const Body& a, const Body& b) {
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.orientation.coeffs(), b.orientation.coeffs());
  EXPECT_EQ(a.velocity, b.velocity);
  EXPECT_EQ(a.angular_velocity, b.angular_velocity);
  EXPECT_EQ(a.force, b.force);
  EXPECT_EQ(a.torque, b.torque);
}

TEST(BodyStore, IdsStayValidAcrossRemovalsAndOrderIsKept) {
  World w;
  const auto a = w.add(ball(Vec3(1, 0, 0)));
  const auto b = w.add(ball(Vec3(2, 0, 0)));
  const auto c = w.add(ball(Vec3(3, 0, 0)));
  const Body removed = w.remove(b);
  EXPECT_EQ(removed.position, Vec3(2, 0, 0));
  EXPECT_EQ(w.bodies().size(), 2u);
  EXPECT_EQ(w.store().get(a).position, Vec3(1, 0, 0));
  EXPECT_EQ(w.store().get(c).position, Vec3(3, 0, 0));
  EXPECT_EQ(w.store().index_of(c), 1u);
  EXPECT_FALSE(w.store().contains(b));
  const auto d = w.add(ball(Vec3(4, 0, 0)));  // reuses b's id
  EXPECT_EQ(w.store().get(d).position, Vec3(4, 0, 0));
  EXPECT_EQ(w.store().id_at(2), d);
}

TEST(BodyStore, OutlivesItsWorld) {
  std::shared_ptr<BodyStore> store;
  BodyStore::Id id;
  {
    World w;
    id = w.add(ball(Vec3(0, 7, 0)));
    store = w.shared_store();
    EXPECT_EQ(store->world(), &w);
  }
  EXPECT_EQ(store->world(), nullptr);
  EXPECT_EQ(store->get(id).position, Vec3(0, 7, 0));
}

TEST(World, RemovingABodyDropsItsSpringsAndKeepsTheOthersIds) {
  World w;
  const auto a = w.add(ball());
  const auto b = w.add(ball(Vec3(1, 0, 0)));
  const auto c = w.add(ball(Vec3(3, 0, 0)));
  Spring s01, s12;
  s01.a = a, s01.b = b, s01.stiffness = 1;
  s12.a = b, s12.b = c, s12.stiffness = 2;
  w.add_spring(s01);
  w.add_spring(s12);
  w.add_drag(Drag{c, 0.5, 0.0});
  w.remove(a);
  ASSERT_EQ(w.springs().size(), 1u);
  EXPECT_EQ(w.springs()[0].a, b);  // nothing renumbered: the ids stay
  EXPECT_EQ(w.springs()[0].b, c);
  EXPECT_EQ(w.springs()[0].stiffness, 2);
  ASSERT_EQ(w.drags().size(), 1u);
  EXPECT_EQ(w.drags()[0].body, c);
  EXPECT_EQ(w.store().index_of(c), 1u);
}

TEST(World, RefusesInvalidForceElements) {
  World w;
  const BodyId a = w.add(ball());
  Spring s;
  s.a = a;
  s.stiffness = -1;
  EXPECT_THROW(w.add_spring(s), std::invalid_argument);
  s.stiffness = 1;
  s.b = BodyId{3, 0};
  EXPECT_THROW(w.add_spring(s), std::invalid_argument);
  s.b = a;
  EXPECT_THROW(w.add_spring(s), std::invalid_argument);  // a == b
  EXPECT_THROW(w.add_drag(Drag{a, -1, 0}), std::invalid_argument);
  EXPECT_THROW(w.add_drag(Drag{BodyId{5, 0}, 1, 0}), std::invalid_argument);
  // A stale id (its body removed, its slot reused) is refused, not taken for the newcomer.
  const BodyId gone = w.add(ball(Vec3(2, 0, 0)));
  w.remove(gone);
  const BodyId newcomer = w.add(ball(Vec3(4, 0, 0)));
  EXPECT_EQ(newcomer.slot, gone.slot);
  EXPECT_FALSE(w.contains(gone));
  EXPECT_THROW(w.add_drag(Drag{gone, 1, 0}), std::invalid_argument);
  EXPECT_THROW(w.remove(gone), std::invalid_argument);
  EXPECT_THROW(w.set_substeps(0), std::invalid_argument);
  EXPECT_THROW(w.step(0.0), std::invalid_argument);
  EXPECT_THROW(w.step(std::nan("")), std::invalid_argument);
  EXPECT_THROW(w.set_gravity(Vec3(0, std::nan(""), 0)), std::invalid_argument);
}

// Hanging mass, spring of rest length 0 to an anchor, damped: it settles where k d = m g.
TEST(Springs, StaticDeflectionIsMgOverK) {
  World w;
  w.add(ball());
  Spring s;
  s.a = w.store().id_at(0);
  s.anchor = Vec3(0, 5, 0);
  s.stiffness = 50.0;
  s.damping = 8.0;
  w.add_spring(s);
  for (int i = 0; i < 2000; ++i) w.step(0.01);
  EXPECT_NEAR(w.bodies()[0].position.y(), 5.0 - 2.0 * 9.81 / 50.0, 1e-9);
  EXPECT_NEAR(w.bodies()[0].velocity.norm(), 0.0, 1e-9);
}

// A spring with rest length stretches by mg/k beyond it.
TEST(Springs, RestLengthShiftsTheEquilibrium) {
  World w;
  w.add(ball(Vec3(0, 3, 0)));
  Spring s;
  s.a = w.store().id_at(0);
  s.anchor = Vec3(0, 5, 0);
  s.stiffness = 50.0;
  s.damping = 8.0;
  s.rest_length = 1.5;
  w.add_spring(s);
  for (int i = 0; i < 2000; ++i) w.step(0.01);
  EXPECT_NEAR(w.bodies()[0].position.y(), 5.0 - 1.5 - 2.0 * 9.81 / 50.0, 1e-9);
}

// Two bodies on an off-centre spring, in gravity: spinning, swinging, and energy conserved.
std::unique_ptr<World> two_bodies_on_a_spring(double damping) {
  auto world = std::make_unique<World>();  // a World cannot move: its store points back at it
  World& w = *world;
  w.set_integrator(Integrator::rk4);
  // Without collision shapes: the box and the ball on these springs would hit each other.
  Body box = make_box_body(1.0, Vec3(1, 0.5, 0.2)), sphere = ball(Vec3(1.5, -0.5, 0.3));
  box.shape = sphere.shape = Shape{};
  w.add(box);
  w.add(sphere);
  Spring s;
  s.a = w.store().id_at(0), s.b = w.store().id_at(1);
  s.a_point = Vec3(0.5, 0.25, 0.1);
  s.b_point = Vec3(0, 0.5, 0);
  s.stiffness = 40.0;
  s.damping = damping;
  s.rest_length = 0.5;
  w.add_spring(s);
  Spring anchor;
  anchor.a = w.store().id_at(0);
  anchor.a_point = Vec3(-0.5, 0, 0);
  anchor.anchor = Vec3(-1, 1, 0);
  anchor.stiffness = 30.0;
  anchor.damping = damping;
  w.add_spring(anchor);
  return world;
}

TEST(Springs, UndampedRk4ConservesTotalEnergy) {
  const auto world = two_bodies_on_a_spring(0.0);
  World& w = *world;
  const double e0 = w.energy();
  double worst = 0.0;
  for (int i = 0; i < 5000; ++i) {
    w.step(1e-3);
    worst = std::max(worst, std::abs(w.energy() - e0));
  }
  EXPECT_LT(worst / std::abs(e0), 1e-7) << "e0 = " << e0;
  EXPECT_GT(w.bodies()[0].angular_velocity.norm(), 0.1);  // it did move and turn
}

TEST(Springs, DampingDecaysEnergy) {
  const auto world = two_bodies_on_a_spring(2.0);
  World& w = *world;
  double previous = w.energy();
  const double e0 = previous;
  for (int i = 0; i < 50; ++i) {
    for (int j = 0; j < 100; ++j) w.step(1e-3);
    EXPECT_LT(w.energy(), previous + 1e-9);
    previous = w.energy();
  }
  EXPECT_LT(previous, e0 - 1.0);
}

// Linear drag alone: v(t) = v0 e^{−c t / m}, ω similarly with the moment of inertia.
TEST(Drag, DecaysVelocityExponentially) {
  World w;
  w.set_gravity(Vec3::Zero());
  w.set_integrator(Integrator::rk4);
  Body b = ball();  // m = 2, I = 0.2
  b.velocity = Vec3(3, 0, 0);
  b.angular_velocity = Vec3(0, 0, 5);
  w.add(b);
  w.add_drag(Drag{w.store().id_at(0), 0.4, 0.1});
  for (int i = 0; i < 1000; ++i) w.step(1e-3);
  EXPECT_NEAR(w.bodies()[0].velocity.x(), 3 * std::exp(-0.4 / 2.0), 1e-12);
  EXPECT_NEAR(w.bodies()[0].angular_velocity.z(), 5 * std::exp(-0.1 / 0.2), 1e-11);
}

// The callback sees the stage state under RK4: a Hooke spring written as a callback gives the
// same motion as the built-in one. Evaluated only at the step's start, it would be off by
// O(dt²) per step.
TEST(ForceCallbacks, SeeStageStatesUnderRk4) {
  const auto builtin_world = two_bodies_on_a_spring(0.5);
  World& builtin = *builtin_world;
  World callback;
  callback.set_integrator(Integrator::rk4);
  callback.add(builtin.bodies()[0]);
  callback.add(builtin.bodies()[1]);
  const Spring s0 = builtin.springs()[0], s1 = builtin.springs()[1];
  callback.add_force([s0, s1](World& w, double) {
    std::vector<Body>& b = w.bodies();
    for (const Spring& s : {s0, s1}) {
      Body& body_a = b[w.store().index_of(s.a)];
      const Vec3 pa = to_world(body_a, s.a_point);
      const bool anchored = !s.b.valid();
      Body* body_b = anchored ? nullptr : &b[w.store().index_of(s.b)];
      const Vec3 pb = anchored ? s.anchor : to_world(*body_b, s.b_point);
      const Vec3 u = (pb - pa).normalized();
      const Vec3 vb = anchored ? Vec3::Zero() : point_velocity(*body_b, pb);
      const double tension = s.stiffness * ((pb - pa).norm() - s.rest_length) +
                             s.damping * (vb - point_velocity(body_a, pa)).dot(u);
      apply_force(body_a, tension * u, pa);
      if (!anchored) apply_force(*body_b, -tension * u, pb);
    }
  });
  for (int i = 0; i < 300; ++i) {
    builtin.step(0.01);
    callback.step(0.01);
  }
  for (int k = 0; k < 2; ++k) {
    EXPECT_LT((builtin.bodies()[k].position - callback.bodies()[k].position).norm(), 1e-12);
    EXPECT_LT((builtin.bodies()[k].angular_velocity - callback.bodies()[k].angular_velocity).norm(),
              1e-12);
  }
}

TEST(ForceCallbacks, AreCalledAtEveryStageWithStageTimes) {
  for (Integrator integrator : {Integrator::rk4, Integrator::semi_implicit}) {
    World w;
    w.set_integrator(integrator);
    w.set_substeps(2);
    w.add(ball());
    std::vector<double> times;
    w.add_force([&times](World& world, double t) {
      times.push_back(t);
      EXPECT_EQ(world.time(), t);
    });
    w.step(0.5);
    const std::vector<double> want = integrator == Integrator::rk4
        ? std::vector<double>{0, 0.125, 0.125, 0.25, 0.25, 0.375, 0.375, 0.5}
        : std::vector<double>{0, 0.25};
    EXPECT_EQ(times, want);
    EXPECT_EQ(w.time(), 0.5);
  }
}

TEST(Step, SubstepsEqualSmallerSteps) {
  World a, b;
  a.set_substeps(5);
  for (World* w : {&a, &b}) {
    w->add(two_bodies_on_a_spring(1.0)->bodies()[0]);
    w->add_drag(Drag{w->store().id_at(0), 0.3, 0.2});
    w->bodies()[0].angular_velocity = Vec3(1, 2, 3);
  }
  for (int i = 0; i < 10; ++i) a.step(0.05);
  for (int i = 0; i < 50; ++i) b.step(0.01);
  EXPECT_LT((a.bodies()[0].position - b.bodies()[0].position).norm(), 1e-12);
  EXPECT_LT((a.bodies()[0].angular_velocity - b.bodies()[0].angular_velocity).norm(), 1e-12);
}

// A force applied before step(dt) acts during the whole step, every substep, then is cleared.
TEST(Step, AppliedForceActsForTheWholeStepThenIsCleared) {
  for (Integrator integrator : {Integrator::euler, Integrator::semi_implicit, Integrator::rk4}) {
    World w;
    w.set_gravity(Vec3::Zero());
    w.set_integrator(integrator);
    w.set_substeps(4);
    w.add(ball());  // m = 2
    apply_force(w.bodies()[0], Vec3(6, 0, 0));
    apply_torque(w.bodies()[0], Vec3(0, 0.2, 0));  // I = 0.2
    w.step(0.5);
    EXPECT_NEAR(w.bodies()[0].velocity.x(), 1.5, 1e-14);
    EXPECT_NEAR(w.bodies()[0].angular_velocity.y(), 0.5, 1e-14);
    EXPECT_EQ(w.bodies()[0].force, Vec3::Zero());
    EXPECT_EQ(w.bodies()[0].torque, Vec3::Zero());
    w.step(0.5);
    EXPECT_NEAR(w.bodies()[0].velocity.x(), 1.5, 1e-14);
  }
}

TEST(Step, StaticBodiesDoNotMove) {
  World w;
  Body wall = make_static_body();
  wall.position = Vec3(0, -1, 0);
  w.add(wall);
  w.add(ball());
  Spring s;
  s.a = w.store().id_at(1), s.b = w.store().id_at(0), s.stiffness = 10;
  w.add_spring(s);
  for (Integrator integrator : {Integrator::euler, Integrator::semi_implicit, Integrator::rk4}) {
    w.set_integrator(integrator);
    for (int i = 0; i < 10; ++i) w.step(0.01);
  }
  EXPECT_EQ(w.bodies()[0].position, Vec3(0, -1, 0));
  EXPECT_EQ(w.bodies()[0].velocity, Vec3::Zero());
  EXPECT_NE(w.bodies()[1].position, Vec3::Zero());
}

TEST(Step, NonFiniteStateIsRefusedAndUndone) {
  for (Integrator integrator : {Integrator::euler, Integrator::semi_implicit, Integrator::rk4}) {
    World w;
    w.set_integrator(integrator);
    w.add(ball());
    w.add(ball(Vec3(1, 0, 0)));
    w.bodies()[1].velocity = Vec3(1e306, 0, 0);
    w.step(0.1);
    apply_force(w.bodies()[0], Vec3(1, 2, 3));
    const Body before0 = w.bodies()[0], before1 = w.bodies()[1];
    try {
      w.step(1000.0);
      ADD_FAILURE() << "no error";
    } catch (const StepError& e) {
      EXPECT_EQ(e.body_index, 1u);
      EXPECT_EQ(e.time, 0.1);
      EXPECT_EQ(std::string(e.what()),
                "body 2 of 2 would get a non-finite position in the step from t = 0.1 s to "
                "t = 1000.1 s; nothing was changed (the world is still at t = 0.1 s)");
    }
    expect_same_state(w.bodies()[0], before0);
    expect_same_state(w.bodies()[1], before1);
    EXPECT_EQ(w.time(), 0.1);
    EXPECT_FALSE(w.stepping());
  }
}

// A failure in the k-th of n steps undoes that step only (issue 12 item 19): the world is where
// a twin that took the k − 1 completed steps is, and the error says how many completed.
TEST(Step, FailureInALaterStepKeepsTheCompletedSteps) {
  World w, twin;
  for (World* x : {&w, &twin}) {
    x->set_gravity(Vec3(1e305, 0, 0));
    Body b = ball();
    b.velocity = Vec3(1, 0, 0);
    x->add(b);
    apply_force(x->bodies()[0], Vec3(0, 1, 0));
  }
  try {
    w.step(1.0, 100);
    ADD_FAILURE() << "no error";
  } catch (const StepError& e) {
    EXPECT_EQ(e.body_index, 0u);
    EXPECT_GT(e.time, 0.5);  // v grows by 1e305 per step: x overflows after a few steps
    const long completed = w.steps_completed();
    EXPECT_EQ(e.time, static_cast<double>(completed));
    EXPECT_EQ(std::string(e.what()),
              "body 1 of 1 would get a non-finite position in the step from t = " +
                  format_number(e.time) + " s to t = " + format_number(e.time + 1) +
                  " s; that step was undone: " + std::to_string(completed) +
                  " of 100 steps completed (the world is at t = " + format_number(e.time) +
                  " s)");
    twin.step(1.0, completed);
  }
  expect_same_state(w.bodies()[0], twin.bodies()[0]);
  EXPECT_EQ(w.time(), twin.time());
  EXPECT_FALSE(w.stepping());
}

// The same for an error a force callback raises in the 4th of 10 steps: 3 steps are kept.
TEST(Step, CallbackErrorInALaterStepKeepsTheCompletedSteps) {
  for (Integrator integrator : {Integrator::euler, Integrator::semi_implicit, Integrator::rk4}) {
    World w, twin;
    int calls = 0;
    const int per_step = integrator == Integrator::rk4 ? 4 : 1;
    for (World* x : {&w, &twin}) {
      x->set_integrator(integrator);
      x->add(tumbling_ball());
      apply_force(x->bodies()[0], Vec3(0, 3, 0));
    }
    w.add_force([&calls, per_step](World&, double) {
      if (++calls == 3 * per_step + 1) throw std::runtime_error("boom");
    });
    twin.add_force([](World&, double) {});
    EXPECT_THROW(w.step(0.01, 10), std::runtime_error);
    EXPECT_EQ(w.steps_completed(), 3);
    twin.step(0.01, 3);
    expect_same_state(w.bodies()[0], twin.bodies()[0]);
    EXPECT_EQ(w.time(), twin.time());
  }
}

TEST(Step, ManyStepsEqualRepeatedSingleSteps) {
  World a, b;
  for (World* w : {&a, &b}) {
    w->set_integrator(Integrator::rk4);
    w->add(tumbling_ball());
    w->add_drag(Drag{w->store().id_at(0), 0.3, 0.2});
    apply_force(w->bodies()[0], Vec3(5, 0, 0));
  }
  a.step(0.01, 30);
  for (int i = 0; i < 30; ++i) b.step(0.01);
  expect_same_state(a.bodies()[0], b.bodies()[0]);
  EXPECT_EQ(a.time(), b.time());
}

TEST(Step, ThrowingCallbackLeavesTheWorldAsBefore) {
  World w;
  w.set_integrator(Integrator::rk4);
  w.add(ball());
  w.bodies()[0].velocity = Vec3(1, 0, 0);
  apply_force(w.bodies()[0], Vec3(0, 1, 0));
  int calls = 0;
  w.add_force([&calls](World&, double) {
    if (++calls == 3) throw std::runtime_error("boom");
  });
  const Body before = w.bodies()[0];
  EXPECT_THROW(w.step(0.1), std::runtime_error);
  expect_same_state(w.bodies()[0], before);
  EXPECT_EQ(w.time(), 0.0);
  EXPECT_FALSE(w.stepping());
  calls = 10;
  w.step(0.1);  // the world still works
  EXPECT_NEAR(w.time(), 0.1, 0);
}

TEST(Step, ReentrantStepAddAndRemoveAreRefused) {
  World w;
  const auto id = w.add(ball());
  std::string message;
  w.add_force([&](World& world, double) {
    for (auto attempt : {0, 1, 2}) {
      try {
        if (attempt == 0) world.step(0.1);
        if (attempt == 1) world.add(ball());
        if (attempt == 2) world.remove(id);
      } catch (const std::logic_error& e) {
        message += std::string(e.what()) + "\n";
      }
    }
  });
  w.step(0.1);
  EXPECT_EQ(message,
            "cannot step the world during a step (force callbacks may only apply forces)\n"
            "cannot add a body during a step (force callbacks may only apply forces)\n"
            "cannot remove a body during a step (force callbacks may only apply forces)\n");
  EXPECT_EQ(w.bodies().size(), 1u);
}

// Energy and momentum totals against hand-computed values.
TEST(Totals, MatchHandComputedValues) {
  World w;  // g = (0, −9.81, 0)
  Body a = ball(Vec3(0, 2, 0));  // m = 2, I = 0.2
  a.velocity = Vec3(1, 0, 0);
  a.angular_velocity = Vec3(0, 0, 3);
  w.add(a);
  Body b = ball(Vec3(1, 0, 0));
  b.velocity = Vec3(0, 0, 2);
  w.add(b);
  Spring s;
  s.a = w.store().id_at(0), s.b = w.store().id_at(1), s.stiffness = 4, s.rest_length = 1;  // length √5
  w.add_spring(s);
  EXPECT_NEAR(w.kinetic_energy(), 0.5 * 2 * 1 + 0.5 * 0.2 * 9 + 0.5 * 2 * 4, 1e-14);
  const double stretch = std::sqrt(5.0) - 1;
  EXPECT_NEAR(w.potential_energy(), 2 * 9.81 * 2 + 0.5 * 4 * stretch * stretch, 1e-12);
  EXPECT_NEAR(w.energy(), w.kinetic_energy() + w.potential_energy(), 0);
  EXPECT_EQ(w.linear_momentum(), Vec3(2, 0, 4));
  // About the origin: (0,2,0) × (2,0,0) + (0,0,0.6) + (1,0,0) × (0,0,4).
  EXPECT_LT((w.angular_momentum() - Vec3(0, -4, -4 + 0.6)).norm(), 1e-14);
  // About (1, 0, 0): (−1,2,0) × (2,0,0) + (0,0,0.6).
  EXPECT_LT((w.angular_momentum(Vec3(1, 0, 0)) - Vec3(0, 0, -4 + 0.6)).norm(), 1e-14);
}

}  // namespace
}  // namespace rigidlab
