// motion.simulate{...}: integrates a particle (or any second-order system x'' = a(t, x, v))
// with one of the integrators of engine/ode.hpp and returns the whole trajectory, so a learner
// can compare methods against the closed form (003_* "Explicit Euler" and "Fourth-Order
// Runge-Kutta").
#include <cmath>
#include <iterator>

#include "engine/ode.hpp"
#include "lua/modules.hpp"
#include "lua/ode_state.hpp"

namespace rigidlab::lua {
namespace {

// The trajectory is kept in memory: 10⁶ steps of vec3 states are about 200 MB of Lua values.
constexpr lua_Integer max_steps = 1'000'000;

struct Options {
  Integrator method = Integrator::semi_implicit;
  int accel_index = 0;  // stack index of the acceleration function
  double dt = 0.0;      // s
  double t0 = 0.0;      // s
  int steps = 0;
};

Integrator field_method(lua_State* L) {
  Integrator method = Integrator::semi_implicit;
  if (get_field(L, 1, "method") != LUA_TNIL)
    method = static_cast<Integrator>(
        check_option(L, -1, Where::field(1, "method"), integrator_names));
  lua_pop(L, 1);
  return method;
}

// Leaves the function on the stack and returns its index.
int field_accel(lua_State* L) {
  const int type = get_field(L, 1, "accel");
  if (type == LUA_TNIL) arg_error(L, 1, "field 'accel' is required");
  if (type != LUA_TFUNCTION)
    arg_error(L, 1, "field 'accel' must be a function, got %s", value_type_name(L, -1));
  return lua_gettop(L);
}

int field_steps(lua_State* L) {
  if (get_field(L, 1, "steps") == LUA_TNIL) arg_error(L, 1, "field 'steps' is required");
  // The whole trajectory is kept: at most max_steps.
  const lua_Integer n = check_integer(L, -1, Where::field(1, "steps"), 0, max_steps);
  lua_pop(L, 1);
  return static_cast<int>(n);
}

// The initial state field `name`: a finite number or a vec3, pushed on the stack. With
// `like_index` (the index of x0), it must be of the same kind as that value, and defaults to
// its zero.
void push_initial_state(lua_State* L, const char* name, int like_index) {
  const int type = get_field(L, 1, name);
  const bool like_vec3 = like_index != 0 && test_vec3(L, like_index) != nullptr;
  if (type == LUA_TNIL && like_index != 0) {
    lua_pop(L, 1);
    if (like_vec3) push_vec3(L, Vec3::Zero());
    else lua_pushnumber(L, 0.0);
    return;
  }
  if (type == LUA_TNIL) arg_error(L, 1, "field '%s' is required", name);
  const bool is_vec3 = test_vec3(L, -1) != nullptr;
  if (type != LUA_TNUMBER && !is_vec3)
    arg_error(L, 1, "field '%s' must be a number or a vec3, got %s", name, value_type_name(L, -1));
  if (like_index != 0 && is_vec3 != like_vec3)
    arg_error(L, 1, "field '%s' must be a %s like x0, got %s", name,
              like_vec3 ? "vec3" : "number", value_type_name(L, -1));
  if (!is_vec3 && !std::isfinite(lua_tonumber(L, -1)))
    arg_error(L, 1, "field '%s' must be finite, got %s", name,
              format_number(lua_tonumber(L, -1)).c_str());
}


// Integrates and pushes {t = {...}, x = {...}, v = {...}} (steps + 1 entries each).
template <class State>
void simulate(lua_State* L, const Options& o, State x, State v) {
  lua_createtable(L, 0, 3);
  lua_createtable(L, o.steps + 1, 0);
  lua_createtable(L, o.steps + 1, 0);
  lua_createtable(L, o.steps + 1, 0);
  const int times = lua_gettop(L) - 2, positions = times + 1, velocities = times + 2;
  const auto record = [&](int n, double t) {
    lua_pushnumber(L, t);
    lua_rawseti(L, times, n + 1);
    push_state(L, x);
    lua_rawseti(L, positions, n + 1);
    push_state(L, v);
    lua_rawseti(L, velocities, n + 1);
  };
  int step_number = 0;
  const auto accel = [&](double t, const State& position, const State& velocity) -> State {
    lua_pushvalue(L, o.accel_index);
    lua_pushnumber(L, t);
    push_state(L, position);
    push_state(L, velocity);
    lua_call(L, 3, 1);
    State a;
    if (!read_state_like(L, -1, velocity, a))
      arg_error(L, 1, "accel returned %s at step %d (t = %s), expected %s", lua_tostring(L, -2),
                step_number, format_number(t).c_str(), lua_tostring(L, -1));
    lua_pop(L, 1);
    return a;
  };
  record(0, o.t0);
  for (int n = 1; n <= o.steps; ++n) {
    step_number = n;
    ode::step(o.method, o.t0 + (n - 1) * o.dt, x, v, o.dt, accel);
    const double t = o.t0 + n * o.dt;  // not accumulated: no drift in the time column
    if (!state_is_finite(x) || !state_is_finite(v))
      function_error(L, "the state is not finite after step %d (t = %s): the motion diverged "
                        "(try a smaller dt)", n, format_number(t).c_str());
    record(n, t);
  }
  lua_setfield(L, times - 1, "v");
  lua_setfield(L, times - 1, "x");
  lua_setfield(L, times - 1, "t");
}

int motion_simulate(lua_State* L) {
  check_no_extra_args(L, 1);
  if (lua_type(L, 1) != LUA_TTABLE) type_error(L, 1, "table");
  static const char* const fields[] = {"method", "accel", "x0", "v0", "dt", "steps", "t0",
                                       nullptr};
  check_fields(L, 1, fields);
  Options o;
  o.method = field_method(L);
  o.accel_index = field_accel(L);
  push_initial_state(L, "x0", 0);
  const int x0 = lua_gettop(L);
  push_initial_state(L, "v0", x0);
  o.dt = field_positive(L, 1, "dt", 0.0, true);
  o.steps = field_steps(L);
  o.t0 = field_finite(L, 1, "t0", 0.0, false);
  // The time column t0 + n dt, n = 0 .. steps, must stay finite: it grows monotonically, so
  // checking the last entry is enough.
  if (!std::isfinite(o.t0 + o.steps * o.dt))
    arg_error(L, 1, "the last time t0 + steps·dt overflows (t0 = %s, dt = %s, steps = %d): use "
                    "a smaller dt or fewer steps", format_number(o.t0).c_str(),
              format_number(o.dt).c_str(), o.steps);
  if (const Vec3* x = test_vec3(L, x0))
    simulate<Vec3>(L, o, *x, *test_vec3(L, x0 + 1));
  else
    simulate<double>(L, o, lua_tonumber(L, x0), lua_tonumber(L, x0 + 1));
  return 1;
}

const Entry functions[] = {
    {"simulate", motion_simulate, "motion.simulate",
     "motion.simulate{method =, accel =, x0 =, v0 =, dt =, steps =, t0 =} -> {t =, x =, v =}",
     "Integrates x'' = accel(t, x, v) from x(t0) = x0, x'(t0) = v0 with `steps` steps of dt\n"
     "(s, > 0) and returns the trajectory: lists t, x, v of steps + 1 entries (the first is\n"
     "the initial state). x0 and v0 are numbers or vec3 (the same kind; v0 defaults to zero);\n"
     "accel must return that kind. t0 defaults to 0; steps is at most 1e6.\n"
     "Methods (003 \"Explicit Euler\", \"Fourth-Order Runge-Kutta\"):\n"
     "  \"euler\"          x += dt v_old, v += dt a        (explicit Euler, order 1)\n"
     "  \"semi_implicit\"  v += dt a, then x += dt v_new   (symplectic Euler, order 1; default)\n"
     "  \"rk4\"            classical Runge-Kutta on (x, v)' = (v, a)   (order 4)\n"
     "Example, the car of document 003 (a = 10 m/s², dt = 1 s, 10 s; exact x = 500 m):\n"
     "  r = motion.simulate{method = \"euler\", accel = function() return 10 end,\n"
     "                      x0 = 0, dt = 1, steps = 10}\n"
     "  r.x[11]  --> 450   (semi_implicit: 550, rk4: 500)"},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const char* const module_doc =
    "motion: integrate the motion of a particle, or any second-order system x'' = a(t, x, v),\n"
    "with a chosen method, and get the whole trajectory (see also ode.step).";

}  // namespace

void open_motion(lua_State* L, int lib) {
  lua_newtable(L);
  register_entries(L, -1, functions);
  register_topic(L, -1, "motion", module_doc);
  lua_setfield(L, lib, "motion");
}

}  // namespace rigidlab::lua
