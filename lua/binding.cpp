#include "lua/binding.hpp"

#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>

namespace rigidlab::lua {

const char vec3_metatable_key = 0;
const char mat3_metatable_key = 0;
const char quat_metatable_key = 0;

namespace {
// Registry table: function (or topic table) -> light userdata pointing at its Entry.
const char entries_key = 0;

void push_entries_table(lua_State* L) {
  if (lua_rawgetp(L, LUA_REGISTRYINDEX, &entries_key) != LUA_TTABLE) {
    lua_pop(L, 1);
    lua_newtable(L);
    lua_pushvalue(L, -1);
    lua_rawsetp(L, LUA_REGISTRYINDEX, &entries_key);
  }
}

// The qualified name of the running C function and whether it was called as a method.
const char* running_function_name(lua_State* L, lua_Debug& ar, bool& is_method) {
  is_method = false;
  if (!lua_getstack(L, 0, &ar)) return nullptr;
  lua_getinfo(L, "nf", &ar);
  const Entry* entry = find_entry(L, -1);
  lua_pop(L, 1);
  is_method = ar.namewhat != nullptr && std::strcmp(ar.namewhat, "method") == 0;
  if (entry != nullptr) return entry->qualified;
  return ar.name != nullptr ? ar.name : "?";
}
}  // namespace

void register_entries(lua_State* L, int table_index, const Entry* entries, int upvalues) {
  table_index = lua_absindex(L, table_index);
  const int first_upvalue = lua_gettop(L) - upvalues + 1;
  push_entries_table(L);
  for (const Entry* e = entries; e->name != nullptr; ++e) {
    for (int i = 0; i < upvalues; ++i) lua_pushvalue(L, first_upvalue + i);
    lua_pushcclosure(L, e->function, upvalues);
    lua_pushvalue(L, -1);
    lua_setfield(L, table_index, e->name);
    lua_pushlightuserdata(L, const_cast<Entry*>(e));
    lua_rawset(L, -3);
  }
  lua_pop(L, 1 + upvalues);
}

void register_topic(lua_State* L, int value_index, const char* qualified, const char* doc) {
  // Topics need an Entry that outlives the state: they are static strings, so a small
  // userdata kept alive by the entries table holds the Entry.
  value_index = lua_absindex(L, value_index);
  push_entries_table(L);
  lua_pushvalue(L, value_index);
  auto* entry = static_cast<Entry*>(lua_newuserdatauv(L, sizeof(Entry), 0));
  *entry = Entry{qualified, nullptr, qualified, qualified, doc};
  lua_rawset(L, -3);
  lua_pop(L, 1);
}

const Entry* find_entry(lua_State* L, int index) {
  index = lua_absindex(L, index);
  push_entries_table(L);
  lua_pushvalue(L, index);
  lua_rawget(L, -2);
  const Entry* entry = static_cast<const Entry*>(lua_touserdata(L, -1));
  lua_pop(L, 2);
  return entry;
}

void arg_error(lua_State* L, int arg, const char* format, ...) {
  va_list args;
  va_start(args, format);
  const char* message = lua_pushvfstring(L, format, args);
  va_end(args);
  lua_Debug ar;
  bool is_method = false;
  const char* name = running_function_name(L, ar, is_method);
  if (name == nullptr) luaL_error(L, "bad argument #%d (%s)", arg, message);
  if (is_method) {
    --arg;  // do not count self, as luaL_argerror
    if (arg == 0) luaL_error(L, "calling '%s' on bad self (%s)", name, message);
  }
  luaL_error(L, "bad argument #%d to '%s' (%s)", arg, name, message);
  std::abort();  // luaL_error does not return
}

void type_error(lua_State* L, int arg, const char* expected) {
  arg_error(L, arg, "%s expected, got %s", expected, value_type_name(L, arg));
}

namespace {
// rigidlab's userdata types: the tag that starts each value, and its name.
struct TaggedType {
  std::uint64_t tag;
  const char* name;
};
constexpr TaggedType tagged_types[] = {
    {vec3_tag, "vec3"}, {mat3_tag, "mat3"}, {quat_tag, "quat"},
    {body_tag, "body"}, {world_tag, "world"}};

// The rigidlab type whose tag starts the userdata at `index`, or nullptr.
const char* tagged_type_name(lua_State* L, int index) {
  if (lua_rawlen(L, index) < sizeof(std::uint64_t)) return nullptr;
  std::uint64_t tag = 0;
  std::memcpy(&tag, lua_touserdata(L, index), sizeof tag);
  for (const TaggedType& type : tagged_types)
    if (type.tag == tag) return type.name;
  return nullptr;
}

bool is_rigidlab_type_name(const char* name) {
  for (const TaggedType& type : tagged_types)
    if (std::strcmp(name, type.name) == 0) return true;
  return false;
}
}  // namespace

const char* value_type_name(lua_State* L, int index) {
  const int type = lua_type(L, index);
  if (type == LUA_TLIGHTUSERDATA) return "light userdata";
  if (type != LUA_TUSERDATA) return lua_typename(L, type);
  if (const char* name = tagged_type_name(L, index)) return name;
  const char* name = "userdata";
  const int field = luaL_getmetafield(L, index, "__name");  // pushes nothing when absent
  if (field == LUA_TSTRING && !is_rigidlab_type_name(lua_tostring(L, -1)))
    name = lua_tostring(L, -1);  // stays alive in the metatable
  if (field != LUA_TNIL) lua_pop(L, 1);
  return name;
}

void field_error(lua_State* L, const char* type, const char* name, const char* format, ...) {
  va_list args;
  va_start(args, format);
  const char* reason = lua_pushvfstring(L, format, args);
  va_end(args);
  luaL_error(L, "bad field '%s' of %s (%s)", name, type, reason);
  std::abort();  // luaL_error does not return
}

void field_type_error(lua_State* L, const char* type, const char* name, const char* expected,
                      int value_index) {
  field_error(L, type, name, "%s expected, got %s", expected, value_type_name(L, value_index));
}

double check_field_finite(lua_State* L, const char* type, const char* name, int value_index) {
  if (lua_type(L, value_index) != LUA_TNUMBER)
    field_type_error(L, type, name, "number", value_index);
  const double x = lua_tonumber(L, value_index);
  if (!std::isfinite(x))
    field_error(L, type, name, "must be finite, got %s", format_number(x).c_str());
  return x;
}

const Vec3& check_field_vec3(lua_State* L, const char* type, const char* name, int value_index) {
  const Vec3* v = test_vec3(L, value_index);
  if (v == nullptr) field_type_error(L, type, name, "vec3", value_index);
  if (!is_finite(*v))
    field_error(L, type, name, "must be finite, got %s", luaL_tolstring(L, value_index, nullptr));
  return *v;
}

const char* push_key_name(lua_State* L, int index) {
  switch (lua_type(L, index)) {
    case LUA_TSTRING:
      lua_pushvalue(L, index);
      return lua_tostring(L, -1);
    case LUA_TNUMBER:
      lua_pushvalue(L, index);
      return lua_tostring(L, -1);  // converts the copy, not the key
    case LUA_TBOOLEAN: return lua_pushstring(L, lua_toboolean(L, index) ? "true" : "false");
    default:
      return lua_pushfstring(L, "%s: %p", value_type_name(L, index), lua_topointer(L, index));
  }
}

void overflow_error(lua_State* L, int arg, const char* result, const char* part) {
  arg_error(L, arg, "%s is not finite (%s overflows the largest double, 1.8e308)", result, part);
}

void stepping_error(lua_State* L, int arg, const char* what) {
  arg_error(L, arg,
            "the world is stepping: cannot %s until world:step returns; force callbacks may only "
            "apply forces", what);
}

void function_error(lua_State* L, const char* format, ...) {
  va_list args;
  va_start(args, format);
  const char* message = lua_pushvfstring(L, format, args);
  va_end(args);
  lua_Debug ar;
  bool is_method = false;
  const char* name = running_function_name(L, ar, is_method);
  luaL_error(L, "'%s': %s", name != nullptr ? name : "?", message);
  std::abort();
}

void check_no_extra_args(lua_State* L, int max_args) {
  const int top = lua_gettop(L);
  if (top > max_args)
    arg_error(L, max_args + 1, "no more than %d argument%s expected, got %d", max_args,
              max_args == 1 ? "" : "s", top);
}

double check_finite(lua_State* L, int arg, const char* what) {
  if (lua_type(L, arg) != LUA_TNUMBER) type_error(L, arg, "number");
  const double x = lua_tonumber(L, arg);
  if (!std::isfinite(x))
    arg_error(L, arg, "%s must be finite, got %s", what, format_number(x).c_str());
  return x;
}

double check_positive(lua_State* L, int arg, const char* what) {
  const double x = check_finite(L, arg, what);
  if (!(x > 0.0)) arg_error(L, arg, "%s must be > 0, got %s", what, format_number(x).c_str());
  return x;
}

double check_nonnegative(lua_State* L, int arg, const char* what) {
  const double x = check_finite(L, arg, what);
  if (!(x >= 0.0)) arg_error(L, arg, "%s must be >= 0, got %s", what, format_number(x).c_str());
  return x;
}

bool to_integer(lua_State* L, int index, lua_Integer& out) {
  if (lua_type(L, index) != LUA_TNUMBER) return false;
  int is_integer = 0;
  out = lua_tointegerx(L, index, &is_integer);
  return is_integer != 0;
}

lua_Integer check_sequence(lua_State* L, int arg, const char* expected, const char* what) {
  arg = lua_absindex(L, arg);
  if (lua_type(L, arg) != LUA_TTABLE) type_error(L, arg, expected);
  const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, arg));
  lua_pushnil(L);
  while (lua_next(L, arg) != 0) {
    lua_pop(L, 1);
    if (lua_isinteger(L, -1) && lua_tointeger(L, -1) >= 1 && lua_tointeger(L, -1) <= n) continue;
    const char* key = luaL_tolstring(L, -1, nullptr);
    if (n == 0)
      arg_error(L, arg, "%s: unexpected key '%s' (the entries of a list are numbered 1, 2, ...; "
                        "this one has none)", what, key);
    arg_error(L, arg, "%s: unexpected key '%s' (entries must be numbered 1 to %I)", what, key, n);
  }
  return n;
}

void new_metatable(lua_State* L, const char* type_name, const void* key) {
  lua_createtable(L, 0, 16);
  lua_pushstring(L, type_name);
  lua_setfield(L, -2, "__name");
  lua_pushstring(L, type_name);
  lua_setfield(L, -2, "__metatable");
  lua_pushvalue(L, -1);
  lua_rawsetp(L, LUA_REGISTRYINDEX, key);
}

bool has_metatable(lua_State* L, int index, const void* key) {
  if (lua_type(L, index) != LUA_TUSERDATA || !lua_getmetatable(L, index)) return false;
  lua_rawgetp(L, LUA_REGISTRYINDEX, key);
  const bool same = lua_rawequal(L, -1, -2);
  lua_pop(L, 2);
  return same;
}

Vec3& check_vec3(lua_State* L, int arg) {
  Vec3* v = test_vec3(L, arg);
  if (v == nullptr) type_error(L, arg, "vec3");
  return *v;
}
Mat3& check_mat3(lua_State* L, int arg) {
  Mat3* m = test_mat3(L, arg);
  if (m == nullptr) type_error(L, arg, "mat3");
  return *m;
}
Quat& check_quat(lua_State* L, int arg) {
  Quat* q = test_quat(L, arg);
  if (q == nullptr) type_error(L, arg, "quat");
  return *q;
}

int get_field(lua_State* L, int arg, const char* name) { return lua_getfield(L, arg, name); }

void check_fields(lua_State* L, int arg, const char* const* allowed) {
  arg = lua_absindex(L, arg);
  lua_pushnil(L);
  while (lua_next(L, arg) != 0) {
    lua_pop(L, 1);  // value
    bool known = false;
    if (lua_type(L, -1) == LUA_TSTRING) {
      const char* key = lua_tostring(L, -1);
      for (const char* const* a = allowed; *a != nullptr && !known; ++a)
        known = std::strcmp(*a, key) == 0;
    }
    if (!known) {
      luaL_Buffer list;
      luaL_buffinit(L, &list);
      for (const char* const* a = allowed; *a != nullptr; ++a) {
        if (a != allowed) luaL_addstring(&list, ", ");
        luaL_addstring(&list, *a);
      }
      luaL_pushresult(&list);
      const int list_index = lua_gettop(L);  // luaL_tolstring below pushes one more
      const char* key = lua_type(L, -2) == LUA_TSTRING ? lua_tostring(L, -2)
                                                        : luaL_tolstring(L, -2, nullptr);
      arg_error(L, arg, "unknown field '%s' (fields are: %s)", key, lua_tostring(L, list_index));
    }
  }
}

namespace {
double field_number(lua_State* L, int arg, const char* name, double fallback, bool required,
                    bool positive) {
  const int type = get_field(L, arg, name);
  if (type == LUA_TNIL) {
    lua_pop(L, 1);
    if (required) arg_error(L, arg, "field '%s' is required", name);
    return fallback;
  }
  if (type != LUA_TNUMBER)
    arg_error(L, arg, "field '%s' must be a number, got %s", name, luaL_typename(L, -1));
  const double x = lua_tonumber(L, -1);
  lua_pop(L, 1);
  if (!std::isfinite(x))
    arg_error(L, arg, "field '%s' must be finite, got %s", name, format_number(x).c_str());
  if (positive && !(x > 0.0))
    arg_error(L, arg, "field '%s' must be > 0, got %s", name, format_number(x).c_str());
  return x;
}
}  // namespace

double field_finite(lua_State* L, int arg, const char* name, double fallback, bool required) {
  return field_number(L, arg, name, fallback, required, false);
}

double field_positive(lua_State* L, int arg, const char* name, double fallback, bool required) {
  return field_number(L, arg, name, fallback, required, true);
}

Vec3 field_vec3(lua_State* L, int arg, const char* name, const Vec3& fallback, bool required) {
  const int type = get_field(L, arg, name);
  if (type == LUA_TNIL) {
    lua_pop(L, 1);
    if (required) arg_error(L, arg, "field '%s' is required", name);
    return fallback;
  }
  const Vec3* v = test_vec3(L, -1);
  if (v == nullptr)
    arg_error(L, arg, "field '%s' must be a vec3, got %s", name, value_type_name(L, -1));
  // A vec3 can hold inf (a row of a static body's infinite tensor); no field takes one.
  if (!is_finite(*v))
    arg_error(L, arg, "field '%s' must be finite, got %s", name, luaL_tolstring(L, -1, nullptr));
  const Vec3 result = *v;
  lua_pop(L, 1);
  return result;
}

namespace {
const char stop_check_key = 0;
struct StopCheckEntry {
  StopCheck check;
  void* data;
};
}  // namespace

void set_stop_check(lua_State* L, StopCheck check, void* data) {
  auto* entry = static_cast<StopCheckEntry*>(lua_newuserdatauv(L, sizeof(StopCheckEntry), 0));
  *entry = StopCheckEntry{check, data};
  lua_rawsetp(L, LUA_REGISTRYINDEX, &stop_check_key);
}

StopPoller::StopPoller(lua_State* L) : L_(L) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &stop_check_key);
  if (const auto* entry = static_cast<const StopCheckEntry*>(lua_touserdata(L, -1))) {
    check_ = entry->check;
    data_ = entry->data;
  }
  lua_pop(L, 1);
}

}  // namespace rigidlab::lua
