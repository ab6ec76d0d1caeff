// The fuzz harness calls what the library documents (api_names.cpp reads the names from
// `require("rigidlab")`): every function and method of API.md's "Articulated bodies" section is
// among them, so articulations, their links and their controls are fuzzed; and a generated
// program builds the prelude's articulation and may call those methods on it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "tests/fuzz/api_names.hpp"
#include "tests/fuzz/program_generator.hpp"

namespace rigidlab::fuzz {
namespace {

bool has(const std::vector<std::string>& names, const std::string& name) {
  return std::binary_search(names.begin(), names.end(), name);
}

TEST(FuzzApiNames, AreSortedWithoutRepeats) {
  for (const auto* list : {&api_names().functions, &api_names().methods}) {
    EXPECT_TRUE(std::is_sorted(list->begin(), list->end()));
    EXPECT_EQ(std::adjacent_find(list->begin(), list->end()), list->end());
  }
}

// API.md, "Articulated bodies": articulation{...}, the art:... and link:... methods.
TEST(FuzzApiNames, IncludeTheArticulationContract) {
  EXPECT_TRUE(has(api_names().functions, "articulation"));
  for (const char* method :
       {"add_link", "set_state", "step", "forward_dynamics", "inverse_dynamics", "mass_matrix",
        "bias_forces", "set_torques", "add_control", "jacobian", "virtual_force",
        "kinetic_energy", "potential_energy", "energy", "record",
        // link:...
        "position", "orientation", "to_world", "point_velocity", "angular_velocity"})
    EXPECT_TRUE(has(api_names().methods, method)) << method;
}

// Bytes that pick the `articulation` function (kind 0: functions[kind / 8 + a]) and the
// `add_link` method (kind 3: methods[b]) give a program that calls them.
TEST(FuzzApiNames, GeneratedProgramsCallThem) {
  const auto& functions = api_names().functions;
  const auto& methods = api_names().methods;
  const auto f = std::find(functions.begin(), functions.end(), "articulation") - functions.begin();
  const auto m = std::find(methods.begin(), methods.end(), "add_link") - methods.begin();
  ASSERT_LT(f, 256);
  ASSERT_LT(m, 256);
  const std::uint8_t bytes[] = {0, static_cast<std::uint8_t>(f), 0, 0,
                                3, 0, static_cast<std::uint8_t>(m), 0};
  const std::string program = generate_program(bytes, sizeof bytes);
  EXPECT_NE(program.find("local A = articulation{"), std::string::npos);
  EXPECT_NE(program.find("keep(pcall(articulation, "), std::string::npos) << program;
  EXPECT_NE(program.find("]:add_link("), std::string::npos) << program;
}

}  // namespace
}  // namespace rigidlab::fuzz
