// The engine tests that run once per solver (world.solver): a TEST_P suite over SolverKind is
// instantiated for both with INSTANTIATE_FOR_BOTH_SOLVERS(Suite), its tests named
// Solvers/Suite.Test/soft_step and .../sequential_impulses.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "engine/solver_settings.hpp"

namespace rigidlab {

inline std::string solver_test_name(const testing::TestParamInfo<SolverKind>& info) {
  return solver_names[static_cast<int>(info.param)];
}

}  // namespace rigidlab

#define INSTANTIATE_FOR_BOTH_SOLVERS(suite)                                                \
  INSTANTIATE_TEST_SUITE_P(Solvers, suite,                                                 \
                           testing::Values(rigidlab::SolverKind::soft_step,                \
                                           rigidlab::SolverKind::sequential_impulses),     \
                           rigidlab::solver_test_name)
