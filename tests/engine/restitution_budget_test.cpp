// The restitution stage's budget (engine/contact_restitution.cpp, round_work): a round with a
// bounce spends at most 16,000 manifold solves (16 manifolds x ContactSettings::max_iterations)
// unless even the velocity stage's `iterations` sweeps of it cost more; a round of up to 16
// manifolds may sweep all 1,000 times; no round is allowed fewer than `iterations` sweeps; a
// round of landings only gets `iterations`. The bound is written here from that rule, not read
// from the engine; the solves are counted where round_sweep solves a manifold
// (World::restitution_rounds), and checked against the sweeps times the manifolds they cover.
#include <gtest/gtest.h>

#include <algorithm>

#include "engine/world.hpp"
#include "tests/engine/world_stacks.hpp"

namespace rigidlab {
namespace {

constexpr double dt = 1.0 / 60.0;
constexpr long budget = 16'000;  // manifold solves of a round with a bounce
constexpr int small_round = 16;  // manifolds: such a round may sweep max_iterations times

struct Seen {
  int bounce_rounds = 0, landing_rounds = 0;
  int over_budget_sized = 0;  // bounce rounds whose `iterations` sweeps alone exceed the budget
  int budget_limited = 0;     // bounce rounds allowed between `iterations` and max_iterations
  int small_rounds = 0;       // bounce rounds of up to 16 manifolds
};

// Steps the world and checks every round of every step against the rule; returns what it saw.
Seen check_rounds(World& w, int steps) {
  const int iterations = w.contact_settings().iterations;
  const int most = ContactSettings::max_iterations;
  Seen seen;
  for (int k = 0; k < steps; ++k) {
    w.step(dt);
    const std::vector<RestitutionRound>& rounds = w.restitution_rounds();
    EXPECT_LE(rounds.size(), 32u);
    for (const RestitutionRound& r : rounds) {
      const long m = r.manifolds;
      EXPECT_GT(m, 0);
      // The counter counts what was solved: every manifold of the round, every sweep.
      EXPECT_EQ(r.solves, static_cast<long>(r.sweeps) * m) << "step " << k;
      EXPECT_LE(r.sweeps, r.allowed_sweeps);
      EXPECT_GE(r.allowed_sweeps, iterations) << "no round gets fewer than `iterations`";
      EXPECT_LE(r.allowed_sweeps, most);
      if (!r.bounces) {
        ++seen.landing_rounds;
        EXPECT_EQ(r.allowed_sweeps, iterations) << "landings are swept like the velocity stage";
        continue;
      }
      ++seen.bounce_rounds;
      if (m <= small_round) {
        ++seen.small_rounds;
        EXPECT_EQ(r.allowed_sweeps, most) << "a round of " << m << " manifolds";
      } else if (m * iterations > budget) {
        ++seen.over_budget_sized;
        EXPECT_EQ(r.allowed_sweeps, iterations);
      } else {
        ++seen.budget_limited;
        EXPECT_LE(r.solves, budget) << "a bounce round of " << m << " manifolds, step " << k;
        EXPECT_GT(static_cast<long>(r.allowed_sweeps + 1) * m, budget)
            << "the budget is spent, not left over";
      }
    }
  }
  return seen;
}

TEST(RestitutionBudget, BouncingHeapsStayWithinTheBudget) {
  // 1,024 spheres: a bounce round spans most of the heap (~1,800 manifolds: `iterations`
  // sweeps alone exceed 16,000 solves); 64 spheres: rounds of ~100 manifolds, allowed
  // 16,000 / m sweeps.
  for (const int n : {64, 1024}) {
    World w;
    fill_heap(w, n, 0.5);
    const Seen seen = check_rounds(w, 90);
    EXPECT_GT(seen.bounce_rounds, 0) << n << " spheres";
    EXPECT_GT(seen.landing_rounds, 0) << n << " spheres";
    if (n == 64) EXPECT_GT(seen.budget_limited, 0);
    if (n == 1024) EXPECT_GT(seen.over_budget_sized, 0);
  }
}

TEST(RestitutionBudget, SmallRoundsGetEverySweepAndConverge) {
  // A row of five balls 1 mm apart (e = 1, no friction, no gravity), the first struck at
  // 3 m/s, at 1 kHz. Its rounds span at most 4 manifolds: allowed all 1,000 sweeps, and they
  // converge (stop before the limit), leaving the striker's speed to the far ball (the closed
  // form of successive elastic collisions of equal masses).
  World w;
  w.set_gravity(Vec3::Zero());
  for (int i = 0; i < 5; ++i) {
    Body b = make_sphere_body(1.0, 0.1);
    b.position = Vec3(0.201 * i, 0.0, 0.0);
    b.restitution = 1.0;
    b.friction = 0.0;
    if (i == 0) b.velocity = Vec3(3.0, 0.0, 0.0);
    w.add(b);
  }
  int small = 0;
  for (int k = 0; k < 20; ++k) {
    w.step(1e-3);
    for (const RestitutionRound& r : w.restitution_rounds()) {
      if (!r.bounces) continue;
      ++small;
      EXPECT_LE(r.manifolds, 4u);
      EXPECT_EQ(r.allowed_sweeps, ContactSettings::max_iterations);
      EXPECT_LT(r.sweeps, r.allowed_sweeps);
    }
  }
  EXPECT_GT(small, 0);
  EXPECT_NEAR(w.bodies()[4].velocity.x(), 3.0, 1e-9);
  EXPECT_NEAR(w.bodies()[0].velocity.x(), 0.0, 1e-9);
}

}  // namespace
}  // namespace rigidlab
