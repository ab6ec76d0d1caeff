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
    // Option tables whose fields run code while a binding reads them (see the prelude): bodies
    // added (vectors grow) and removed (an argument may go), garbage collected, proxies whose
    // fields come from __index alone.
    "setmetatable({}, {__index = function() grow() end})",
    "setmetatable({mass = 1, radius = 0.5}, {__index = function() shrink() end})",
    "setmetatable({point = vec3(), normal = vec3(0, 1, 0)}, {__index = function() shrink() grow() collectgarbage() end})",
    "setmetatable({}, {__index = function(_, k) shrink() return proxy_field(k) end})",
    "setmetatable({}, {__index = function(_, k) grow() return proxy_field(k) end})",
    "setmetatable({k = 10, anchor = vec3()}, {__index = function(_, k) shrink() return proxy_field(k) end})",
    "setmetatable({}, {__index = function() error('mt') end, __len = function() return 2^31 end, __pairs = function() error('p') end})",
    "W", "W:bodies()[1]", "W:bodies()[2]", "K",
    // Articulations (A in the prelude): link specifications, a free base, its links, controls
    // that return wrong torques, raise, or try to change the articulation that calls them.
    "A", "A.links[1]", "A.links[#A.links]", "{base = 'free', integrator = 'rk4'}",
    "{joint = 'revolute', axis = vec3(0, 0, 1), mass = 1, com = vec3(0, -1, 0)}",
    "{joint = 'prismatic', axis = vec3(), mass = 1}", "{joint = 'fixed', parent = r[1]}",
    "{parent = A.links[1], joint = 'hinge', inertia = mat3.diag(1, 2, 3), name = 'x'}",
    "function(a, t) return a.qd end", "function(a, t) return {1e308, 0/0} end",
    "function(a) a:step(0.01) return {0} end",
    "function(a) a:set_state(a.q, a.qd) end",
    "function() shrink() grow() return {} end",
    "{1, 2}", "{0, 0, 0, 0, 0, 0, 0, 0}",
};

// Steps tables for lesson{...}; %s is where the body of a run function goes.
const char* const steps_templates[] = {
    "{ {title = 'a', text = 'b', run = function(ctx) %s end} }",
    "setmetatable({ {title = 'a', text = 'b', run = function(ctx) %s end} }, {__len = function() "
    "return 2^31 - 1 end, __index = function() shrink() return {title = 'x', text = 'y', run = "
    "function(ctx) ctx:say('i') end} end})",
    "{ setmetatable({title = 'a', text = 'b'}, {__index = function(_, k) grow() if k == 'run' then "
    "return function(ctx) %s end end end}) }",
    "{ {title = 'a', text = 'b', run = function(ctx) K = ctx setmetatable({}, {__gc = function() "
    "pcall(K.expect, K, 'late', 1, 1) pcall(K.show, K, 'late', 1) end}) %s end}, {title = 'c', "
    "text = 'd', run = function(ctx) collectgarbage() %s end} }",
    "setmetatable({}, {__index = function(_, i) if i == 1 then return {title = 'a', text = 'b', "
    "run = function(ctx) %s end} end end})",
};

// What a run function does with its ctx (%s: a value, %t: another).
const char* const ctx_calls[] = {
    "ctx:show(%s, %t)", "ctx:expect(%s, %t, %s)", "ctx:expect('e', %s, %t, %s)",
    "ctx:expect_range(%s, %t, %s, %t)", "ctx:table(%s, %t)", "ctx:say(%s)", "ctx:plot(%s)",
    "ctx:expect('w', W, W, %s)", "ctx:show('t', setmetatable({1, x = W}, {__index = function() grow() end}))",
    "shrink() ctx:expect('n', #W:bodies(), #W:bodies())",
};

const char* const tolerances[] = {
    "", "tolerance = {rel = 1e-3, reason = 'r'}, ",
    "tolerance = setmetatable({rel = 1e-3, reason = 'r'}, {__index = function() shrink() end}), ",
    "tolerance = {abs = 0/0, reason = ''}, ",
};

// Fields written as r[i].f = a: those of vec3, quat, body, world (its contact settings and
// sleeping too), joint and articulation (fields are not Entries, so they are listed here;
// API.md and the types' help list them).
const char* const fields[] = {"x", "y", "z", "w", "position", "velocity", "angular_velocity",
                              "orientation", "mass", "inv_mass", "inertia", "restitution",
                              "friction", "static", "shape", "time", "gravity", "integrator",
                              "gyroscopic", "substeps", "iterations", "restitution_threshold",
                              "q", "qd", "links", "base", "solver", "contact_hertz",
                              "contact_damping_ratio", "contact_push_speed", "joint_hertz",
                              "joint_damping_ratio", "relax_iterations", "speculative_distance",
                              "slop", "sleeping", "sleep_linear", "sleep_angular", "sleep_time",
                              "sleeping_count", "collide", "length", "hertz"};

template <class T, std::size_t N>
const char* pick(const T (&table)[N], unsigned byte) {
  return table[byte % N];
}

// `pattern` with each %s replaced by the value picked by one byte and each %t by another.
std::string fill(const char* pattern, unsigned first, unsigned second) {
  std::string result;
  for (const char* c = pattern; *c != '\0'; ++c) {
    if (c[0] == '%' && (c[1] == 's' || c[1] == 't')) {
      result += pick(values, c[1] == 's' ? first : second);
      ++c;
    } else {
      result += *c;
    }
  }
  return result;
}

// A lesson whose steps (and their tables, and the lesson's tolerance) may have metatables, and
// whose run functions use their ctx with hostile values, keep it past the lesson and mutate
// the world; the harness runs the lessons the program returns as `rigidlab check` does.
std::string lesson_line(std::uint8_t kind, std::uint8_t a, std::uint8_t b, std::uint8_t c) {
  const std::string body = fill(pick(ctx_calls, b), a + c, b ^ c) + "; " +
                           fill(pick(ctx_calls, c), b + kind, a ^ b);
  std::string steps = pick(steps_templates, a);
  for (std::size_t at; (at = steps.find("%s")) != std::string::npos;) steps.replace(at, 2, body);
  return std::string("keep(pcall(function() local l = lesson{id = 'f', title = 't', source = "
                     "'s', ") + pick(tolerances, kind / 16) + "steps = " + steps +
         "} lessons[#lessons + 1] = l return l end))";
}

const char* pick(const std::vector<std::string>& names, unsigned index) {
  return names.empty() ? "print" : names[index % names.size()].c_str();
}

// Every program starts with: r, the results kept; W, a world with two bodies; A, an
// articulation of two links; grow and shrink, which add bodies to and remove bodies from W and
// the worlds in r, and grow adds links to A (its q, q̇ and torques grow while a binding reads an
// option table: the option tables' metamethods above); proxy_field, the fields a proxy option table hands out; lessons, the
// lessons made, which the program returns.
const char* const prelude = R"(local r, lessons = {}, {}
local function keep(ok, v) if ok then r[#r % 8 + 1] = v end end
local W = world{}
W:add(body.sphere{mass = 1, radius = 0.5})
W:add(body.box{mass = 2, size = vec3(1, 1, 1), position = vec3(2, 0, 0)})
local A = articulation{gravity = vec3(0, -9.81, 0)}
A:add_link{joint = 'revolute', axis = vec3(0, 0, 1), mass = 1, com = vec3(0, -1, 0)}
A:add_link{parent = A.links[1], joint = 'prismatic', axis = vec3(0, -1, 0), mass = 1,
           origin = vec3(0, -1, 0)}
local function grow()
  pcall(function() W:add(body.sphere{mass = 1, radius = 0.5, position = vec3(0, 3, 0)}) end)
  pcall(function() if #A.links < 32 then A:add_link{parent = A.links[#A.links], mass = 1} end end)
  for i = 1, 8 do pcall(function() r[i]:add(body.sphere{mass = 1, radius = 0.25}) end) end
end
local function shrink()
  pcall(function() local bs = W:bodies() W:remove(bs[#bs]) end)
  for i = 1, 8 do pcall(function() r[i]:remove(r[i]:bodies()[1]) end) end
end
local function proxy_field(k)
  return ({mass = 1, radius = 0.5, normal = vec3(0, 1, 0), point = vec3(), k = 10,
           a = W:bodies()[1], b = W:bodies()[2], x = {1, 2}, y = {1, 2}, linear = 1,
           restitution = 0.5, friction = 0.5, offset = 0, anchor = vec3()})[k]
end
)";

}  // namespace

std::string generate_program(const std::uint8_t* data, std::size_t size) {
  std::string program = prelude;
  for (std::size_t i = 0; i + 3 < size; i += 4) {
    const std::uint8_t kind = data[i], a = data[i + 1], b = data[i + 2], c = data[i + 3];
    std::string line;
    switch (kind % 10) {
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
      case 8: case 9:
        line = lesson_line(kind, a, b, c);
        break;
      default:  // operators between earlier results and values
        static const char* const ops[] = {"+", "-", "*", "/", "==", "..", "<", "%", "^"};
        line = std::string("keep(pcall(function() return r[") + std::to_string(a % 8 + 1) + "] " +
               pick(ops, b) + " " + pick(values, c) + " end))";
    }
    program += line + "\n";
  }
  program += "collectgarbage()\nreturn lessons\n";
  return program;
}

}  // namespace rigidlab::fuzz
