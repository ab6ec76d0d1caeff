// The open functions of every binding file. Each sets its names as fields of the table at
// `lib` (the table `require("rigidlab")` returns). Add one line here and one in rigidlab.cpp
// per new binding file.
#pragma once

#include <lua.hpp>

namespace rigidlab::lua {

void open_vec3(lua_State* L, int lib);
void open_mat3(lua_State* L, int lib);
void open_quat(lua_State* L, int lib);
void open_inertia(lua_State* L, int lib);
void open_help(lua_State* L, int lib);
void open_lesson(lua_State* L, int lib);
void open_plot(lua_State* L, int lib);
void open_csv(lua_State* L, int lib);
void open_motion(lua_State* L, int lib);
void open_ode(lua_State* L, int lib);
void open_collide(lua_State* L, int lib);
void open_body(lua_State* L, int lib);
void open_world(lua_State* L, int lib);
void open_articulation(lua_State* L, int lib);
void open_render(lua_State* L, int lib);  // after open_world: world methods
void open_record(lua_State* L, int lib);  // after open_world: world methods
void open_export_html(lua_State* L, int lib);  // after open_world: world methods
void open_view(lua_State* L, int lib);  // after open_world: world methods
void open_joint(lua_State* L, int lib);  // after open_world: world methods

}  // namespace rigidlab::lua
