// The Lua world object, for the binding files that extend it: a joints, recorder, viewer or
// solver binding adds its methods and properties to every world with one line each, from its
// own open_* function (called after open_world in lua/rigidlab.cpp):
//
//   const Entry joint_methods[] = {{"add_joint", world_add_joint, "world:add_joint", ...}, ...};
//   void open_joints(lua_State* L, int lib) {
//     add_methods(L, world_type, joint_methods);        // w:add_joint{...}, help("world")
//     add_properties(L, world_type, solver_properties);  // w.solver, world{solver = ...}
//   }
//
// A method that changes the world reads every argument and option field first (their
// metamethods may run any Lua code, even the world's __gc by hand), then calls
// check_world_unlocked, then takes engine references, and leaves everything as it was when it
// fails (lua/binding.hpp, sections 3 and 4).
#pragma once

#include <lua.hpp>

#include <cstddef>

#include "engine/world.hpp"
#include "lua/binding.hpp"

namespace rigidlab::lua {

// The world userdata's C++ object (placement-new in the userdata; destroyed by __gc).
struct LuaWorld {
  World world;
  lua_State* running = nullptr;  // the thread running w:step, for the force callbacks
};

// The world type: add_methods / add_properties extend it (lua/binding.hpp section 5).
extern const TypeSpec world_type;

// The world at `index`, or nullptr.
LuaWorld* test_world(lua_State* L, int index);
// The world at `arg`; else "world expected, got number", or for a world whose __gc has run
// "the world was finalised (...)".
LuaWorld& check_world(lua_State* L, int arg);
// check_world for a call that changes the world: refuses while it steps (a force callback
// may only apply forces): "calling 'world:add_joint' on bad self (the world is stepping:
// cannot `what` until world:step returns; ...)".
LuaWorld& check_world_unlocked(lua_State* L, int arg, const char* what);

// The body at stack index `value`, which must be in world `w`: its index in w.world.bodies()
// (0-based, valid until a body is added or removed). Errors in the form of `where`: "field 'a'
// must be a body, got number", "... is a body that is not in this world (w:add it first)".
std::size_t check_member(lua_State* L, const LuaWorld& w, int value, const Where& where);
// Pushes the Lua object of the body at engine index `index` of the world at stack `world`.
void push_world_body(lua_State* L, int world, std::size_t index);
// Pushes a table in which an extension keeps its own Lua values for the world at stack index
// `world` (its joint objects, its recorders), under `key` (the address of a static of the
// extension's file); made empty the first time. It lives as long as the world.
void push_world_table(lua_State* L, int world, const void* key);

// The force elements, planes, contacts and w:step (lua/world_forces.cpp), added by open_world.
void open_world_forces(lua_State* L);

}  // namespace rigidlab::lua
