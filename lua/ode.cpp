// ode.step(method, f, t, y, dt): one step of an explicit integrator (engine/ode.hpp) for a
// first-order system y' = f(t, y), with y a number, a vec3 or a table of numbers. Also the
// state helpers of lua/ode_state.hpp, which motion.simulate shares.
#include <cmath>
#include <iterator>

#include "engine/ode.hpp"
#include "lua/modules.hpp"
#include "lua/ode_state.hpp"

namespace rigidlab::lua {

void push_state(lua_State* L, double x) { lua_pushnumber(L, x); }
void push_state(lua_State* L, const Vec3& x) { push_vec3(L, x); }
void push_state(lua_State* L, const Eigen::VectorXd& x) {
  const int size = static_cast<int>(x.size());
  lua_createtable(L, size, 0);
  for (int i = 0; i < size; ++i) {
    lua_pushnumber(L, x[i]);
    lua_rawseti(L, -2, i + 1);
  }
}

bool read_state_like(lua_State* L, int index, double, double& out) {
  index = lua_absindex(L, index);
  if (lua_type(L, index) != LUA_TNUMBER) {
    lua_pushstring(L, value_type_name(L, index));
    lua_pushliteral(L, "number");
    return false;
  }
  out = lua_tonumber(L, index);
  if (std::isfinite(out)) return true;
  lua_pushstring(L, format_number(out).c_str());
  lua_pushliteral(L, "a finite number");
  return false;
}

bool read_state_like(lua_State* L, int index, const Vec3&, Vec3& out) {
  index = lua_absindex(L, index);
  const Vec3* v = test_vec3(L, index);
  if (v == nullptr) {
    lua_pushstring(L, value_type_name(L, index));
    lua_pushliteral(L, "vec3");
    return false;
  }
  out = *v;
  if (is_finite(out)) return true;
  lua_pushliteral(L, "a vec3 with a non-finite component");
  lua_pushliteral(L, "a finite vec3");
  return false;
}

bool read_state_like(lua_State* L, int index, const Eigen::VectorXd& like, Eigen::VectorXd& out) {
  index = lua_absindex(L, index);
  const int size = static_cast<int>(like.size());
  if (lua_type(L, index) != LUA_TTABLE) {
    lua_pushstring(L, value_type_name(L, index));
    lua_pushfstring(L, "a table of %d numbers", size);
    return false;
  }
  const lua_Unsigned length = lua_rawlen(L, index);
  if (length != static_cast<lua_Unsigned>(size)) {
    lua_pushfstring(L, "a table of %d value%s", static_cast<int>(length), length == 1 ? "" : "s");
    lua_pushfstring(L, "a table of %d numbers", size);
    return false;
  }
  out.resize(size);
  for (int i = 0; i < size; ++i) {
    const bool number = lua_rawgeti(L, index, i + 1) == LUA_TNUMBER;
    const double x = lua_tonumber(L, -1);
    if (!number || !std::isfinite(x)) {
      const char* what = number                ? lua_pushstring(L, format_number(x).c_str())
                         : lua_isnil(L, -1) ? lua_pushliteral(L, "nil")
                                            : lua_pushfstring(L, "a %s", value_type_name(L, -1));
      lua_pushfstring(L, "a table with %s at index %d", what, i + 1);
      lua_replace(L, -3);  // drop the entry, keep the description
      lua_pop(L, 1);
      lua_pushfstring(L, "a table of %d finite numbers", size);
      return false;
    }
    lua_pop(L, 1);
    out[i] = x;
  }
  return true;
}

namespace {

using ode::FirstOrderMethod;


FirstOrderMethod check_method(lua_State* L, int arg) {
  return static_cast<FirstOrderMethod>(
      check_option(L, arg, Where::argument(arg, "method"), ode::first_order_method_names));
}

// y given as a table: a non-empty list of finite numbers, with no other keys (a named field
// would not be integrated, and f would not see it).
Eigen::VectorXd check_list(lua_State* L, int arg) {
  const int size = static_cast<int>(
      check_sequence(L, arg, "number, vec3 or table of numbers", "y (a list of numbers)"));
  if (size == 0) arg_error(L, arg, "y must be a number, a vec3 or a non-empty list of numbers");
  Eigen::VectorXd y(size);
  for (int i = 0; i < size; ++i) {
    if (lua_rawgeti(L, arg, i + 1) != LUA_TNUMBER)
      arg_error(L, arg, "y[%d] must be a number, got %s", i + 1, value_type_name(L, -1));
    y[i] = lua_tonumber(L, -1);
    if (!std::isfinite(y[i]))
      arg_error(L, arg, "y[%d] must be finite, got %s", i + 1, format_number(y[i]).c_str());
    lua_pop(L, 1);
  }
  return y;
}

// One step with the callable at stack index 2; pushes the new state.
template <class State>
int step_state(lua_State* L, FirstOrderMethod method, double t, const State& y, double dt) {
  const auto f = [L](double time, const State& state) -> State {
    lua_pushvalue(L, 2);
    lua_pushnumber(L, time);
    push_state(L, state);
    lua_call(L, 2, 1);
    State slope;
    if (!read_state_like(L, -1, state, slope))
      arg_error(L, 2, "f returned %s at t = %s, expected %s", lua_tostring(L, -2),
                format_number(time).c_str(), lua_tostring(L, -1));
    lua_pop(L, 1);
    return slope;
  };
  const State next = ode::step(method, t, y, dt, f);
  if (!state_is_finite(next))
    function_error(L, "the new y is not finite (overflow): try a smaller dt");
  push_state(L, next);
  return 1;
}

int ode_step(lua_State* L) {
  check_no_extra_args(L, 5);
  const FirstOrderMethod method = check_method(L, 1);
  if (lua_type(L, 2) != LUA_TFUNCTION) type_error(L, 2, "function");
  const double t = check_finite(L, 3, "t");
  const int y_type = lua_type(L, 4);
  const Vec3* y_vec3 = test_vec3(L, 4);
  if (y_type != LUA_TNUMBER && y_type != LUA_TTABLE && y_vec3 == nullptr)
    type_error(L, 4, "number, vec3 or table of numbers");
  if (y_type == LUA_TNUMBER) {
    const double y = check_finite(L, 4, "y");
    return step_state(L, method, t, y, check_positive(L, 5, "dt"));
  }
  if (y_vec3 != nullptr) {
    const Vec3 y = *y_vec3;
    return step_state(L, method, t, y, check_positive(L, 5, "dt"));
  }
  const Eigen::VectorXd y = check_list(L, 4);
  return step_state(L, method, t, y, check_positive(L, 5, "dt"));
}

const Entry functions[] = {
    {"step", ode_step, "ode.step", "ode.step(method, f, t, y, dt) -> y_next",
     "One step, from t to t + dt (s, dt > 0), of an explicit integrator for the first-order\n"
     "system y' = f(t, y). y is a number, a vec3 or a table of numbers; f(t, y) must return\n"
     "the derivative as the same kind (a table of the same length). y is not modified.\n"
     "Methods (003 \"Fourth-Order Runge-Kutta\"; Butcher 2016):\n"
     "  \"euler\"     y + dt f(t, y)                                   order 1\n"
     "  \"midpoint\"  y + dt f(t + dt/2, y + dt/2 f(t, y))             order 2\n"
     "  \"heun\"      y + dt/2 (k1 + k2), k2 = f(t + dt, y + dt k1)    order 2\n"
     "  \"rk4\"       y + dt/6 (k1 + 2k2 + 2k3 + k4)                   order 4\n"
     "Example: ode.step(\"rk4\", function(t, y) return y end, 0, 1, 0.1)  --> 1.1051708333333"},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const char* const module_doc =
    "ode: one step of an explicit integrator for y' = f(t, y) (see also motion.simulate for\n"
    "second-order systems x'' = a(t, x, v)).";

}  // namespace

void open_ode(lua_State* L, int lib) {
  lua_newtable(L);
  register_entries(L, -1, functions);
  register_topic(L, -1, "ode", module_doc);
  lua_setfield(L, lib, "ode");
}

}  // namespace rigidlab::lua
