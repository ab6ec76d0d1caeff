#include "tests/fuzz/program_generator.hpp"

#include <string>
#include <vector>

#include "tests/fuzz/api_names.hpp"

namespace rigidlab::fuzz {
namespace {

// Values an argument can take. r[i] are the results of earlier calls.
const char* const values[] = {
    "nil", "true", "0", "-1", "1", "2.5", "1e308", "-1e308", "1e-320", "0/0", "math.huge",
    "-math.huge", "math.maxinteger", "'x'", "''", "{}", "{1, 2, 3}", "{{1,2,3},{4,5,6},{7,8,9}}",
    "function() end", "function() error('cb') end", "function(...) return ... end",
    "vec3()", "vec3(1, 2, 3)", "vec3(1e300, 1e300, 1e300)", "vec3(0, -9.81, 0)",
    "mat3.identity()", "mat3(1, 2, 3, 4, 5, 6, 7, 8, 9)", "mat3.diag(1, 2, 3)",
    "mat3.diag(1, 1, 3)", "mat3.zero()", "quat()", "quat(0, 0, 0, 0)", "quat(1, 2, 3, 4)",
    "quat.axis_angle(vec3(0, 1, 0), 1)",
    "{mass = 1, inertia = mat3.identity()}", "{mass = 0, inertia = mat3.identity()}",
    "{mass = 1, radius = 0.5}", "{mass = 2, size = vec3(1, 2, 3)}", "{mass = math.huge}",
    "{static = true}", "{mass = 1, com = vec3(), inertia = mat3.identity()}",
    "{mass = 1, pos = vec3(1, 0, 0)}", "{{mass = 1, pos = vec3(1, 0, 0)}}",
    "{point = vec3(), normal = vec3(0, 1, 0), restitution = 0.5, friction = 0.5}",
    "{point = vec3(), normal = vec3(), restitution = 2}", "{normal = vec3(0, 1, 0), offset = 0}",
    "{gravity = vec3(0, -9.81, 0), integrator = 'rk4'}", "{integrator = 'nope'}",
    "{method = 'rk4', accel = function(t, x, v) return -x end, x0 = 1, v0 = 0, dt = 0.1, steps = 5}",
    "{method = 'euler', accel = function() return nil end, x0 = 1, v0 = 0, dt = 0.1, steps = 3}",
    "{a = r[1], k = 10, anchor = vec3()}", "{body = r[1], linear = 1}",
    "{x = {1, 2}, y = {1, 2}}", "setmetatable({}, {__index = function() error('mt') end})",
    "0.01", "100", "1e-300", "-0.0", "'rk4'", "'euler'", "{1, 0/0}", "{{y = {1, 2}}, width = 10}",
    "{normal = vec3(0, 1, 0), offset = -1, restitution = 0.5, friction = 0.3}",
    "{gravity = vec3(), substeps = 3, iterations = 5, restitution_threshold = 0.1}",
    "{body = r[2], linear = 1, angular = 1}", "{a = r[1], b = r[2], k = 10, a_point = vec3(1, 0, 0)}",
    "{mass = 1, radius = 0.5, position = vec3(0, 0.4, 0), restitution = 1, friction = 1}",
    "setmetatable({}, {__len = function() return 'x' end})",
    "r[1]", "r[2]", "r[3]", "r[4]", "r[5]", "r[6]", "r[7]", "r[8]",
};

// Fields written as r[i].f = a: those of vec3, quat, body and world (fields are not Entries,
// so they are listed here; API.md and the types' help list them).
const char* const fields[] = {"x", "y", "z", "w", "position", "velocity", "angular_velocity",
                              "orientation", "mass", "inv_mass", "inertia", "restitution",
                              "friction", "static", "shape", "time", "gravity", "integrator",
                              "gyroscopic", "substeps", "iterations", "restitution_threshold"};

template <class T, std::size_t N>
const char* pick(const T (&table)[N], std::uint8_t byte) {
  return table[byte % N];
}

const char* pick(const std::vector<std::string>& names, unsigned index) {
  return names.empty() ? "print" : names[index % names.size()].c_str();
}

}  // namespace

std::string generate_program(const std::uint8_t* data, std::size_t size) {
  std::string program = "local r = {}\nlocal function keep(ok, v) if ok then r[#r % 8 + 1] = v end end\n";
  for (std::size_t i = 0; i + 3 < size; i += 4) {
    const std::uint8_t kind = data[i], a = data[i + 1], b = data[i + 2], c = data[i + 3];
    std::string line;
    switch (kind % 8) {
      case 0: case 1: case 2:
        line = std::string("keep(pcall(") + pick(api_names().functions, kind / 8 + a) + ", " +
               pick(values, b) +
               ", " + pick(values, c) + ", " + pick(values, a) + "))";
        break;
      case 3: case 4: case 5:
        line = std::string("keep(pcall(function() return r[") + std::to_string(a % 8 + 1) + "]:" +
               pick(api_names().methods, b) + "(" + pick(values, c) + ", " + pick(values, kind) +
               ") end))";
        break;
      case 6:
        line = std::string("pcall(function() r[") + std::to_string(a % 8 + 1) + "]." +
               pick(fields, b) + " = " + pick(values, c) + " end)";
        break;
      default:  // operators between earlier results and values
        static const char* const ops[] = {"+", "-", "*", "/", "==", "..", "<", "%", "^"};
        line = std::string("keep(pcall(function() return r[") + std::to_string(a % 8 + 1) + "] " +
               pick(ops, b) + " " + pick(values, c) + " end))";
    }
    program += line + "\n";
  }
  program += "collectgarbage()\n";
  return program;
}

}  // namespace rigidlab::fuzz
