// Issue 13: a pyramid of unit boxes with default settings (60 Hz, one substep) must stand
// still: static friction holds it exactly, so whatever its top box moves is the solver's. It
// must also stand whatever should not matter: the order its contacts are solved in (the boxes
// added bottom-up, top-down or shuffled), positions moved by 1e-9 m, a smaller or larger
// pyramid. And the motion must stop: a creep that grows with time topples the pile at last.
//
// Before the patch friction (engine/contact_friction.cpp) the top moved, at 10 s / 20 s (mm;
// the test runs 10 s and takes the growth from 5 s to 10 s, to keep the suite short):
//                    bottom-up   top-down   shuffled   jitter 1e-9   base 10      base 30
//   soft_step        4.5 / 9.7   7.4 / 87   2.1 / 21   5.6 / 14      1.2 / 6.8    9.2 / 21
//   seq. impulses    4.7 / 79    4.0 / 308  1.7 / 32   3.2 / 71      0.02 / 0.02  38 / 878
// growing in a slow twist about the vertical and a sway out of the pyramid's plane. Now:
//   soft_step        2.8 / 2.8   2.6 / 2.5  1.5 / 1.4  2.8 / 2.8     0.23 / 0.23  5.8 / 5.3
//   seq. impulses    0.25 / 0.25 0.19/0.19  1.3 / 1.6  0.25 / 0.25   0.00 / 0.00  1.8 / 1.9
// soft_step's few millimetres were set in the first second, while its push-out lifted the
// pyramid back from the sinking of the cold first steps (the top 12 mm down at 0.5 s), and
// some shuffled orders fell apart from it (below). Since soft_step's cold start sweeps on
// where new contacts form a long chain (engine/solver.cpp Solver::solve), soft_step:
//   soft_step        0.26        0.10       0.03       0.26          0.00         1.8
// (sequential_impulses as above), and over the shuffled orders of mt19937 seeds 1 to 40 at
// most 0.56 mm (before: 10 of them fell apart, the top 1.8 to 7.0 m away).
#include <gtest/gtest.h>

#include <string>

#include "engine/world.hpp"
#include "tests/engine/both_solvers.hpp"
#include "tests/engine/world_stacks.hpp"

namespace rigidlab {
namespace {

struct Creep {
  Vec3 at5, at10;  // m, the top box's displacement after 5 s and 10 s
};

Creep top_creep(SolverKind solver, int base, AddOrder added, double jitter,
                unsigned seed = 7) {
  World w;
  w.set_solver(solver);
  const BodyId top = build_pyramid(w, base, added, jitter, seed);
  const Vec3 start = w.store().get(top).position;
  Creep creep;
  for (int i = 0; i < 600; ++i) {
    w.step(1.0 / 60.0);
    if (i == 299) creep.at5 = w.store().get(top).position - start;
  }
  creep.at10 = w.store().get(top).position - start;
  return creep;
}

class PyramidCreep : public testing::TestWithParam<SolverKind> {};

// The top within `limit` of where it started after 10 s (the 5 mm, tighter where the
// solver does better by a margin), and moved sideways by less than `growth` from 5 s to 10 s
// (vertically soft_step is still lifting the pile back from its first steps' sinking).
void expect_stands(const Creep& c, double limit, double growth) {
  EXPECT_LT(c.at10.norm(), limit) << "mm after 10 s: " << 1e3 * c.at10.transpose();
  const Vec3 sideways(c.at10.x() - c.at5.x(), 0.0, c.at10.z() - c.at5.z());
  EXPECT_LT(sideways.norm(), growth)
      << "mm moved sideways from 5 s to 10 s: " << 1e3 * sideways.transpose();
}

double base20_limit(SolverKind s) { return s == SolverKind::soft_step ? 0.005 : 0.002; }

TEST_P(PyramidCreep, BaseTwentyAddedBottomUp) {
  expect_stands(top_creep(GetParam(), 20, AddOrder::bottom_up, 0.0), base20_limit(GetParam()),
                1e-3);
}

TEST_P(PyramidCreep, BaseTwentyAddedTopDown) {
  expect_stands(top_creep(GetParam(), 20, AddOrder::top_down, 0.0), base20_limit(GetParam()),
                1e-3);
}

TEST_P(PyramidCreep, BaseTwentyAddedShuffled) {
  expect_stands(top_creep(GetParam(), 20, AddOrder::shuffled, 0.0), base20_limit(GetParam()),
                1e-3);
}

// The add orders of these seeds made soft_step's pyramid fall apart before its cold start
// swept on (engine/solver.cpp Solver::solve): the top 1842, 1805, 3320 and 3240 mm away after
// 10 s (10 of the first 40 seeds fell so; sequential_impulses 0.20, 0.03, 0.67 and 0.01 mm).
TEST_P(PyramidCreep, BaseTwentyAddedInOrdersThatFellApart) {
  for (const unsigned seed : {4u, 9u, 11u, 15u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    expect_stands(top_creep(GetParam(), 20, AddOrder::shuffled, 0.0, seed),
                  base20_limit(GetParam()), 1e-3);
  }
}

TEST_P(PyramidCreep, BaseTwentyWithPositionsMovedByANanometre) {
  expect_stands(top_creep(GetParam(), 20, AddOrder::bottom_up, 1e-9), base20_limit(GetParam()),
                1e-3);
}

TEST_P(PyramidCreep, BaseTen) {
  expect_stands(top_creep(GetParam(), 10, AddOrder::bottom_up, 0.0), 5e-4, 1e-4);
}

TEST_P(PyramidCreep, BaseThirty) {
  // 465 boxes: soft_step's top settled 5.8 mm away before its cold start swept on, 1.8 mm
  // now (sequential_impulses 1.8 mm).
  expect_stands(top_creep(GetParam(), 30, AddOrder::bottom_up, 0.0), 0.005, 1e-3);
}

// soft_step sweeps on (to convergence, Solver::solve) only on a step whose new touching
// points form a chain under some body longer than `iterations` sweeps carry a load down
// (n² > iterations): the sweeps the last substep ran, by what is built.
std::size_t first_step_sweeps(int boxes, int iterations) {
  World w;
  ContactSettings s;
  s.iterations = iterations;
  w.set_contact_settings(s);
  build_stack(w, boxes, false);
  w.step(1.0 / 60.0);
  return w.solver_report().size();
}

TEST(ColdStart, SweepsOnWhereNewContactsFormALongChain) {
  EXPECT_EQ(first_step_sweeps(3, 10), 10u);   // 3² ≤ 10: the column is settled as warm ones
  EXPECT_GT(first_step_sweeps(3, 8), 8u);     // 3² > 8
  EXPECT_GT(first_step_sweeps(4, 10), 10u);   // 4² > 10
  World w;
  const BodyId top = build_stack(w, 5, false);
  w.step(1.0 / 60.0);
  const std::size_t iterations = static_cast<std::size_t>(w.contact_settings().iterations);
  EXPECT_GT(w.solver_report().size(), iterations);
  EXPECT_LT(w.solver_report().back(), 1e-6 * w.solver_report().front());
  w.step(1.0 / 60.0, 59);
  // Warm and at rest: no sweeping on, and the sweeps have converged after two
  // (Solver::settled).
  EXPECT_EQ(w.solver_report().size(), 2u);
  // A box set on the resting column: its new points land on a body held by warm ones (n = 1).
  Body box = make_box_body(1.0, Vec3(1, 1, 1));
  box.position = w.store().get(top).position + Vec3(0, 1, 0);
  w.add(box);
  w.step(1.0 / 60.0);
  EXPECT_EQ(w.solver_report().size(), iterations);
}

TEST(ColdStart, SettlingHeapKeepsItsSweeps) {
  // New points every step, but each lands on bodies held by warm ones (chains of at most 2):
  // the heap's steps keep `iterations` sweeps (bench/contacts_bench.cpp settle/N times them),
  // no more and, while it settles, no fewer.
  World w;
  fill_heap(w, 256, 0.0);
  const std::size_t iterations = static_cast<std::size_t>(w.contact_settings().iterations);
  // Before any sphere touches there is nothing to solve, and soft_step stops after two
  // sweeps (Solver::settled); from the step after the first touch on, it is never settled.
  bool touched_before = false;
  for (int k = 0; k < 90; ++k) {
    w.step(1.0 / 60.0);
    ASSERT_EQ(w.solver_report().size(), touched_before ? iterations : 2) << "step " << k;
    for (const ContactInfo& c : w.contacts()) touched_before = touched_before || c.depth >= 0.0;
  }
}

INSTANTIATE_FOR_BOTH_SOLVERS(PyramidCreep);

}  // namespace
}  // namespace rigidlab
