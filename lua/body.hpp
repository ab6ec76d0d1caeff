// The Lua body object, shared by the binding files that take bodies (world, collide).
//
// Ownership: a body userdata is a handle, {shared_ptr<BodyStore>, id}. A lone body has a store
// of its own; w:add(b) moves the body into the world's store (contiguous, for the step loops)
// and repoints the handle; w:remove(b) moves it back into a new store of its own. The handle
// keeps its store alive, so a body stays valid whatever the collector does: bodies in a world
// are also referenced from the world's userdata (so w:bodies() returns the same objects), and
// a body whose world was collected keeps that world's store alive and stays readable.
#pragma once

#include <lua.hpp>

#include <cstdint>
#include <memory>

#include "engine/world.hpp"
#include "lua/binding.hpp"

namespace rigidlab::lua {

struct BodyHandle {
  std::shared_ptr<BodyStore> store;
  BodyStore::Id id;
  Body& body() const { return store->get(id); }
};

// The body type: add_methods / add_properties extend it (lua/binding.hpp section 5).
extern const TypeSpec body_type;

// The handle of the body at `index`, or nullptr when it is not a body.
BodyHandle* test_body(lua_State* L, int index);
// The handle, or a "body expected, got <type>" argument error ("the body was finalised" for
// one whose __gc has run); the second form reports in the form of `where`.
BodyHandle& check_body_handle(lua_State* L, int arg);
BodyHandle& check_body_handle(lua_State* L, int index, const Where& where);
// The body itself. The reference is valid until a body is added to or removed from its store,
// which Lua code can do: take it after reading every argument and option field, and do not
// keep it across a Lua allocation (a finaliser may run there) or a call into Lua.
inline Body& check_body(lua_State* L, int arg) { return check_body_handle(L, arg).body(); }
// A new Lua body holding a copy of b in a store of its own.
BodyHandle& push_new_body(lua_State* L, const Body& b);

// Reads the optional fields restitution (in [0, 1]) and friction (>= 0) of the table at `arg`,
// with the defaults of engine/plane.hpp; an argument error names the field.
void read_material_fields(lua_State* L, int arg, double& restitution, double& friction);

// Raises stepping_error blaming argument `arg` (the body) when the body's world is stepping:
// only apply_force and apply_torque make sense at an RK4 stage.
void check_not_stepping(lua_State* L, int arg, const BodyHandle& handle, const char* what);

}  // namespace rigidlab::lua
