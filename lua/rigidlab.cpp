#include "lua/rigidlab.hpp"

#include <cstring>

#include "lua/modules.hpp"
#include "lua/text_only.hpp"

namespace rigidlab::lua {

int open_library(lua_State* L) {
  lua_newtable(L);
  const int lib = lua_gettop(L);
  open_vec3(L, lib);
  open_mat3(L, lib);
  open_quat(L, lib);
  open_inertia(L, lib);
  open_help(L, lib);
  open_lesson(L, lib);
  open_plot(L, lib);
  open_csv(L, lib);
  open_motion(L, lib);
  open_ode(L, lib);
  open_collide(L, lib);
  open_body(L, lib);
  open_world(L, lib);
  open_articulation(L, lib);
  open_render(L, lib);
  open_record(L, lib);
  open_export_html(L, lib);
  open_view(L, lib);
  open_joint(L, lib);
  lua_pushliteral(L, RIGIDLAB_VERSION);
  lua_setfield(L, lib, "version");
  return 1;
}

void open_all(lua_State* L) {
  luaL_openlibs(L);
  install_text_only_loaders(L);
  luaL_requiref(L, "rigidlab", open_library, 0);
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {  // copy every name but `version` to the globals
    if (lua_type(L, -2) == LUA_TSTRING && std::strcmp(lua_tostring(L, -2), "version") != 0)
      lua_setglobal(L, lua_tostring(L, -2));
    else
      lua_pop(L, 1);
  }
  lua_pop(L, 1);
}

int traceback_handler(lua_State* L) {
  const char* message = lua_tostring(L, 1);
  if (message == nullptr) {
    if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING) return 1;
    message = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
  }
  luaL_traceback(L, L, message, 1);
  return 1;
}

}  // namespace rigidlab::lua
