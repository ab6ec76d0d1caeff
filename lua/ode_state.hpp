// Lua values as states of an ODE, shared by motion.simulate (lua/motion.cpp) and ode.step
// (lua/ode.cpp): a number (double), a vec3 (Vec3) or a list of numbers (Eigen::VectorXd).
// The engine integrators (engine/ode.hpp) are templates over the state type; these overloads
// push a state to Lua and read one back from a callback's result, checking its kind, length
// and finiteness so that a wrong result gets a message saying what came and what was expected.
#pragma once

#include <Eigen/Core>

#include "lua/binding.hpp"

namespace rigidlab::lua {

void push_state(lua_State* L, double x);
void push_state(lua_State* L, const Vec3& x);
void push_state(lua_State* L, const Eigen::VectorXd& x);  // a new table {x[0], x[1], ...}

// Reads the value at `index` into `out` when it is of the kind of `like` (and, for a list, of
// its length) and finite. Otherwise returns false and pushes two strings: what was there
// ("nil", "nan", "a table of 2 numbers") and what was expected ("number", "a list of 3
// numbers").
bool read_state_like(lua_State* L, int index, double like, double& out);
bool read_state_like(lua_State* L, int index, const Vec3& like, Vec3& out);
bool read_state_like(lua_State* L, int index, const Eigen::VectorXd& like, Eigen::VectorXd& out);

inline bool state_is_finite(double x) { return x - x == 0.0; }
inline bool state_is_finite(const Vec3& x) { return is_finite(x); }
inline bool state_is_finite(const Eigen::VectorXd& x) { return x.allFinite(); }

}  // namespace rigidlab::lua
