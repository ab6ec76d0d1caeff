// The Lua side of articulated bodies (engine/articulation.hpp), shared by its three files:
// lua/articulation.cpp (the type: constructor, properties, links, state, controls, step),
// lua/articulation_dynamics.cpp (the algorithms' queries) and lua/articulation_link.cpp (the
// link type).
//
// An articulation userdata holds a LuaArticulation (placement-new, destroyed by __gc) and two
// user values: 1 = the list of its link objects (in the order added, so art.links and every
// query return the same objects), 2 = the list of its control functions. A link userdata holds
// its index and, as user value 1, its articulation, which it keeps alive.
#pragma once

#include <lua.hpp>

#include <Eigen/Core>

#include "engine/articulation.hpp"
#include "lua/binding.hpp"

namespace rigidlab::lua {

struct LuaArticulation {
  Articulation art;
  lua_State* running = nullptr;  // the thread whose call evaluates the controls, or nullptr
};

extern const TypeSpec articulation_type;
extern const TypeSpec link_type;

// The articulation at `index`, or nullptr (also for one finalised).
LuaArticulation* test_articulation(lua_State* L, int index);
// The articulation at `arg`, else a type error (or "was finalised").
LuaArticulation& check_articulation(lua_State* L, int arg);
// The same, refusing with the stepping error when a control is running its step.
LuaArticulation& check_articulation_unlocked(lua_State* L, int arg, const char* what);

// The link index (0-based) named by the value at `value` for the articulation at `object`: a
// link object of that articulation, its 1-based number or its name; errors in `where`'s form.
int check_link_of(lua_State* L, int object, int value, const Where& where);
// A link object: its articulation (pushed) and index.
bool test_link(lua_State* L, int index, int* link);
// Pushes link object `link` (0-based) of the articulation at `object`.
void push_link(lua_State* L, int object, int link);
// Creates the link object for a new link and appends it to the articulation's list.
void append_link_object(lua_State* L, int object, int link);

// A list of numbers (the argument at `arg`, a table with keys 1..n, each a finite number):
// "bad argument #2 to 'articulation:set_state' (qd[2] must be a finite number, got nan)".
Eigen::VectorXd check_numbers(lua_State* L, int arg, const char* what);
// Pushes a new list of numbers, and a list of rows for a matrix.
void push_numbers(lua_State* L, const Eigen::Ref<const Eigen::VectorXd>& x);
void push_rows(lua_State* L, const Eigen::Ref<const Eigen::MatrixXd>& m);

// Sets the thread whose stack the controls run on for the lifetime of the object (RAII: Lua
// errors, thrown as C++ exceptions, unwind through it).
class ControlThread {
 public:
  ControlThread(LuaArticulation& a, lua_State* L) : a_(a), previous_(a.running) { a.running = L; }
  ~ControlThread() { a_.running = previous_; }
  ControlThread(const ControlThread&) = delete;
  ControlThread& operator=(const ControlThread&) = delete;

 private:
  LuaArticulation& a_;
  lua_State* previous_;
};

void open_articulation_dynamics(lua_State* L);
void open_articulation_link(lua_State* L, int lib);

}  // namespace rigidlab::lua
