#include "cli/hook_guard.hpp"

#include <algorithm>

namespace rigidlab::cli {
namespace {

lua_Hook limits_hook = nullptr;
// Registry: a table with weak keys, thread -> ScriptHook userdata, of the threads with a
// script hook.
const char script_hooks_key = 0;
// Whether any thread ever had a script hook: until then, the hook looks nothing up.
bool any_script_hook = false;

struct ScriptHook {
  lua_Hook hook;  // debug library's hook function, which calls the script's Lua function
  int mask;
  int count;
  int left;  // instructions to its next count event
};

// The ScriptHook of the thread at the top of the stack, which is popped; nullptr if none.
ScriptHook* pop_and_find(lua_State* L) {
  if (lua_rawgetp(L, LUA_REGISTRYINDEX, &script_hooks_key) != LUA_TTABLE) {
    lua_pop(L, 2);
    return nullptr;
  }
  lua_insert(L, -2);
  lua_rawget(L, -2);
  auto* script = static_cast<ScriptHook*>(lua_touserdata(L, -1));
  lua_pop(L, 2);
  return script;
}

ScriptHook* find(lua_State* L) {
  if (!any_script_hook) return nullptr;
  lua_pushthread(L);
  return pop_and_find(L);
}

int count_for(const ScriptHook* script) {
  if (script == nullptr || (script->mask & LUA_MASKCOUNT) == 0) return limits_hook_interval;
  return std::min(script->left, limits_hook_interval);
}

// Puts the limits' hook back on thread L1 after the original debug.sethook has set L1's hook;
// what it set becomes L1's script hook. `thread` is the stack index of L1 (in L's stack).
void take_over(lua_State* L, lua_State* L1, int thread) {
  const lua_Hook hook = lua_gethook(L1);
  const int mask = lua_gethookmask(L1), count = lua_gethookcount(L1);
  if (lua_rawgetp(L, LUA_REGISTRYINDEX, &script_hooks_key) != LUA_TTABLE)
    luaL_error(L, "the hooks' registry is missing");
  lua_pushvalue(L, thread);
  ScriptHook* script = nullptr;
  if (hook != nullptr && hook != limits_hook) {
    script = static_cast<ScriptHook*>(lua_newuserdatauv(L, sizeof(ScriptHook), 0));
    *script = ScriptHook{hook, mask, count, count};
    any_script_hook = true;
  } else {
    lua_pushnil(L);
  }
  lua_rawset(L, -3);
  lua_pop(L, 1);
  lua_sethook(L1, limits_hook, LUA_MASKCOUNT | (script != nullptr ? script->mask : 0),
              count_for(script));
}

// The thread a debug function acts on: its argument 1 when that is a thread, else L. Pushes
// the thread.
lua_State* push_target_thread(lua_State* L) {
  if (lua_type(L, 1) == LUA_TTHREAD) {
    lua_pushvalue(L, 1);
    return lua_tothread(L, 1);
  }
  lua_pushthread(L);
  return L;
}

// debug.sethook([thread,] hook, mask [, count]); upvalue 1: the original.
int guarded_sethook(lua_State* L) {
  const int arguments = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  for (int i = 1; i <= arguments; ++i) lua_pushvalue(L, i);
  lua_call(L, arguments, 0);
  lua_State* L1 = push_target_thread(L);
  take_over(L, L1, lua_gettop(L));
  return 0;
}

// debug.gethook([thread]); upvalue 1: the original, run with the script hook in place.
int guarded_gethook(lua_State* L) {
  const int arguments = lua_gettop(L);
  lua_State* L1 = push_target_thread(L);
  const ScriptHook* script = pop_and_find(L);
  const lua_Hook own = lua_gethook(L1);
  const int own_mask = lua_gethookmask(L1), own_count = lua_gethookcount(L1);
  lua_sethook(L1, script != nullptr ? script->hook : nullptr, script != nullptr ? script->mask : 0,
              script != nullptr ? script->count : 0);
  lua_pushvalue(L, lua_upvalueindex(1));
  for (int i = 1; i <= arguments; ++i) lua_pushvalue(L, i);
  const int status = lua_pcall(L, arguments, LUA_MULTRET, 0);
  lua_sethook(L1, own, own_mask, own_count);
  if (status != LUA_OK) return lua_error(L);
  return lua_gettop(L) - arguments;
}

void replace(lua_State* L, int debug, const char* name, lua_CFunction guarded) {
  lua_pushstring(L, name);
  lua_rawget(L, debug);
  if (lua_tocfunction(L, -1) == guarded || !lua_isfunction(L, -1)) {
    lua_pop(L, 1);
    return;
  }
  lua_pushcclosure(L, guarded, 1);
  lua_pushstring(L, name);
  lua_insert(L, -2);
  lua_rawset(L, debug);
}

int guard_protected(lua_State* L) {
  if (lua_rawgetp(L, LUA_REGISTRYINDEX, &script_hooks_key) != LUA_TTABLE) {
    lua_newtable(L);
    lua_createtable(L, 0, 1);
    lua_pushliteral(L, "k");
    lua_setfield(L, -2, "__mode");
    lua_setmetatable(L, -2);
    lua_rawsetp(L, LUA_REGISTRYINDEX, &script_hooks_key);
  }
  lua_getfield(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
  if (lua_type(L, -1) != LUA_TTABLE) return 0;
  lua_pushliteral(L, "debug");
  if (lua_rawget(L, -2) != LUA_TTABLE) return 0;
  const int debug = lua_gettop(L);
  replace(L, debug, "sethook", guarded_sethook);
  replace(L, debug, "gethook", guarded_gethook);
  return 0;
}

}  // namespace

void install_limits_hook(lua_State* L, lua_Hook hook) {
  limits_hook = hook;
  lua_sethook(L, hook, LUA_MASKCOUNT, limits_hook_interval);
}

void guard_hooks(lua_State* L) {
  if (limits_hook == nullptr || !lua_checkstack(L, 8)) return;
  lua_pushcfunction(L, guard_protected);
  if (lua_pcall(L, 0, 0, 0) != LUA_OK) lua_pop(L, 1);  // no memory left: tried again next time
}

void run_script_hook(lua_State* L, lua_Debug* ar) {
  ScriptHook* script = find(L);
  if (script == nullptr) {
    // A thread created under a script hook inherited its mask, not the script hook (as with
    // the debug library alone, that hook does nothing there): back to counting only.
    if (lua_gethookmask(L) != LUA_MASKCOUNT)
      lua_sethook(L, limits_hook, LUA_MASKCOUNT, limits_hook_interval);
    return;
  }
  if (ar->event != LUA_HOOKCOUNT) {
    const int wanted = ar->event == LUA_HOOKTAILCALL ? LUA_MASKCALL : 1 << ar->event;
    if ((script->mask & wanted) != 0) script->hook(L, ar);
    return;
  }
  if ((script->mask & LUA_MASKCOUNT) == 0) return;
  script->left -= lua_gethookcount(L);
  if (script->left <= 0) {
    script->left = script->count;
    script->hook(L, ar);
    script = find(L);  // the script's hook may have changed its hook
    if (script == nullptr) return;
  }
  if (count_for(script) != lua_gethookcount(L))
    lua_sethook(L, limits_hook, LUA_MASKCOUNT | script->mask, count_for(script));
}

}  // namespace rigidlab::cli
