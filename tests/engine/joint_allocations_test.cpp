// No heap allocation per step with joints once the solver's buffers have grown (issue 14,
// "Performance"): a grid of hinges with limits, springs and motors, a ball-joint chain and a
// distance rope, stepped with both solvers. Counted with the operator new that
// world_contacts_test.cpp installs in engine_tests (tests/engine/allocation_counter.hpp).
#include <gtest/gtest.h>

#include <atomic>
#include <memory>

#include "engine/joint.hpp"
#include "engine/world.hpp"

inline std::atomic<long> allocations{0};  // the same inline variable as allocation_counter.hpp

namespace rigidlab {
namespace {

TEST(JointAllocations, AStepAllocatesNothingOnceWarm) {
  for (SolverKind solver : {SolverKind::soft_step, SolverKind::sequential_impulses}) {
    World w;
    w.set_solver(solver);
    w.set_substeps(2);
    BodyId previous = no_body_id;
    for (int i = 0; i < 12; ++i) {
      Body b = make_body(1.0, 0.1 * Mat3::Identity());
      b.position = Vec3(0.5 * i, 0, 0);
      JointDef def;
      def.type = i % 3 == 0 ? JointKind::ball : i % 3 == 1 ? JointKind::hinge : JointKind::distance;
      def.a = w.add(b);
      def.b = previous;
      def.anchor = b.position - Vec3(0.25, 0, 0);
      def.axis = Vec3::UnitZ();
      def.b_point = Vec3(-0.5, 0, 0);
      if (def.type == JointKind::hinge) {
        def.lower = -0.5, def.upper = 0.5;
        def.spring = JointSpring{2.0, 0.3, 0.1};
        def.motor = JointMotor{0.2, 0.0, 5.0, 1.0, 2.0};
      }
      if (def.type == JointKind::distance) def.max_length = 0.6;
      const Body* other = previous.valid() ? &w.store().get(previous) : nullptr;
      w.add_constraint(std::make_unique<Joint>(def, w.store().get(def.a), other));
      previous = def.a;
    }
    w.step(1.0 / 60.0, 30);
    const long before = allocations.load();
    w.step(1.0 / 60.0, 30);
    EXPECT_EQ(allocations.load() - before, 0) << solver_names[static_cast<int>(solver)];
  }
}

}  // namespace
}  // namespace rigidlab
