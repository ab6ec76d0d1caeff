// The names the program generator calls, read from the library itself: every documented
// function of `require("rigidlab")` (the Entry tables of the bindings, which help() shows), so
// a function added to the API is fuzzed without editing a list here.
#pragma once

#include <string>
#include <vector>

namespace rigidlab::fuzz {

struct ApiNames {
  std::vector<std::string> functions;  // called as f(a, b, c): "vec3", "inertia.solid_box"
  std::vector<std::string> methods;    // called as r[i]:m(a, b): "dot", "add_plane", "step"
};

// Sorted and without repeats, so the same input gives the same program.
const ApiNames& api_names();

}  // namespace rigidlab::fuzz
