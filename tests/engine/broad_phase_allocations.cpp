// No heap allocation per step in the broad phase once its buffers have grown (issue 13, item
// 5): a settling-pile-like scene (many persistent pairs) and a scattered one with bodies
// removed and added every step are stepped until every buffer has reached its size, then
// stepped again while a replaced operator new counts (allocation_counter.hpp). Its own
// executable, since engine_tests counts with world_contacts_test.cpp: tests/CMakeLists.txt.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "engine/broad_phase.hpp"
#include "engine/constraint_row.hpp"
#include "tests/engine/allocation_counter.hpp"  // replaces operator new: counts allocations

namespace rigidlab {
namespace {

struct Body {
  Vec3 centre, half, velocity;
  ProxyId proxy;
};

Aabb box_of(const Body& b) { return {b.centre - b.half, b.centre + b.half}; }

// Bodies on a jittered lattice, `spacing` apart, moving back and forth (a pile that does not
// settle completely), or scattered far apart.
struct Scene {
  std::mt19937 rng{1};
  std::uniform_real_distribution<double> u{-1.0, 1.0};
  BroadPhase bp;
  std::vector<Body> bodies;
  std::uint64_t next_key = 0;
  double dt = 1.0 / 60.0, time = 0.0;

  Body make(const Vec3& centre, double speed) {
    Body b{centre, Vec3::Constant(0.5), Vec3(speed * u(rng), speed * u(rng), speed * u(rng)), 0};
    b.proxy = bp.create_proxy(box_of(b), next_key++, ProxyKind::moving, dt * b.velocity);
    return b;
  }
  Scene(int side, double spacing, double speed) {
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j)
        for (int k = 0; k < side; ++k) bodies.push_back(make(spacing * Vec3(i, j, k), speed));
    bp.create_proxy(Aabb{Vec3::Constant(-1), Vec3(spacing * side, 0, spacing * side)}, next_key++,
                    ProxyKind::fixed);  // a floor
  }
  // One step: every body swings about its start (the velocity turns every 30 steps); with churn,
  // one body is removed and a new one added.
  void step(bool churn) {
    time += dt;
    const bool turn = std::fmod(time, 0.5) < dt;
    for (Body& b : bodies) {
      if (turn) b.velocity = -b.velocity;
      b.centre += dt * b.velocity;
      bp.move_proxy(b.proxy, box_of(b), dt * b.velocity);
    }
    if (churn) {
      const std::size_t i = rng() % bodies.size();
      bp.destroy_proxy(bodies[i].proxy);
      bodies[i] = make(bodies[i].centre, 1.0);
    }
    bp.update_pairs();
  }
};

long allocations_while(Scene& run, int steps, bool churn) {
  const long before = allocations.load();
  for (int s = 0; s < steps; ++s) run.step(churn);
  return allocations.load() - before;
}

TEST(BroadPhaseAllocations, NoneInSteadyStateWithManyPairs) {
  Scene run(12, 1.0, 0.5);  // 1,728 touching bodies: thousands of persistent pairs
  allocations_while(run, 200, false);
  ASSERT_GT(run.bp.pairs().size(), 5000u);
  EXPECT_EQ(allocations_while(run, 200, false), 0);
  EXPECT_EQ(run.bp.check(), "");
}

TEST(BroadPhaseAllocations, NoneWithBodiesRemovedAndAdded) {
  Scene run(12, 4.0, 3.0);  // far apart, fast: many re-insertions
  allocations_while(run, 300, true);
  EXPECT_EQ(allocations_while(run, 300, true), 0);
  EXPECT_EQ(run.bp.check(), "");
}

TEST(BroadPhaseAllocations, NoneInQueriesOrRayCasts) {
  Scene run(10, 1.5, 1.0);
  run.step(false);
  const long before = allocations.load();
  int hits = 0;
  run.bp.query(Aabb{Vec3::Zero(), Vec3::Constant(5)}, [&](ProxyId, std::uint64_t) {
    return ++hits, true;
  });
  run.bp.ray_cast(Vec3(-5, 1, 1), Vec3(1, 0.1, 0.1), 30.0, [&](ProxyId, std::uint64_t, double t) {
    return ++hits, t;
  });
  EXPECT_EQ(allocations.load() - before, 0);
  EXPECT_GT(hits, 10);
}

// After reserve(), even the first steps allocate nothing.
TEST(BroadPhaseAllocations, NoneAfterReserve) {
  BroadPhase bp;
  bp.reserve(1000, 20000);
  const long before = allocations.load();
  for (int i = 0; i < 1000; ++i) {
    const Vec3 c(i % 10, (i / 10) % 10, i / 100);
    bp.create_proxy(Aabb{c, c + Vec3::Constant(1.0)}, static_cast<std::uint64_t>(i));
  }
  bp.update_pairs();
  EXPECT_EQ(allocations.load() - before, 0);
  EXPECT_GT(bp.pairs().size(), 10000u);
}

}  // namespace
}  // namespace rigidlab

// The solver bodies are over-aligned (engine/constraint_row.hpp): their vectors allocate through
// operator new(size, align_val_t), which the counter must see too, or the world's
// no-allocation tests would pass whatever the solver arrays did.
TEST(BroadPhaseAllocations, CounterSeesOverAlignedAllocations) {
  static_assert(alignof(rigidlab::SolverBody) > __STDCPP_DEFAULT_NEW_ALIGNMENT__);
  const long before = allocations.load();
  std::vector<rigidlab::SolverBody> bodies(3);
  EXPECT_EQ(allocations.load() - before, 1);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(bodies.data()) % alignof(rigidlab::SolverBody), 0u);
}
