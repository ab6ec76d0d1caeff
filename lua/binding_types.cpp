// The binding toolbox, sections 4-5 of lua/binding.hpp: registering functions (each inside
// the exception bridge) with their help, and userdata types whose fields are properties.
//
// Registry layout: entries_key -> {function or topic value = light userdata Entry*};
// types_key -> {light userdata TypeSpec* = record, public table = record}, where a record is
// {methods = {name = function}, properties = {name = light userdata Property*, [i] = name in
// the order added}, public = the type's table}.
#include <cstring>
#include <exception>
#include <new>

#include "lua/binding.hpp"

namespace rigidlab::lua {

namespace {
const char entries_key = 0;
const char types_key = 0;

void push_registry_table(lua_State* L, const void* key) {
  if (lua_rawgetp(L, LUA_REGISTRYINDEX, key) != LUA_TTABLE) {
    lua_pop(L, 1);
    lua_newtable(L);
    lua_pushvalue(L, -1);
    lua_rawsetp(L, LUA_REGISTRYINDEX, key);
  }
}

// The exception bridge around every registered function: the Entry is the closure's last
// upvalue (after the N of the function itself), so the function sees its own upvalues at
// 1..N as if it were pushed alone. No std::exception ever reaches Lua, whose C++ build would
// take it for an error without a message ("(error object is not a string)").
template <int N>
int bridged(lua_State* L) {
  const auto* entry = static_cast<const Entry*>(lua_touserdata(L, lua_upvalueindex(N + 1)));
  Failure failure;
  try {
    return entry->function(L);
  } catch (const std::bad_alloc& e) {
    failure.hold(e);
  } catch (const std::exception& e) {
    failure.hold(e);
  }
  failure.raise(L);
}

constexpr lua_CFunction bridges[] = {bridged<0>, bridged<1>, bridged<2>, bridged<3>};

// Pushes the closure of `entry` with the `upvalues` values at first_upvalue.. and records it.
void push_entry(lua_State* L, const Entry* entry, int first_upvalue, int upvalues) {
  luaL_argcheck(L, upvalues < 4, 1, "register_entries: at most 3 upvalues");
  for (int i = 0; i < upvalues; ++i) lua_pushvalue(L, first_upvalue + i);
  lua_pushlightuserdata(L, const_cast<Entry*>(entry));
  lua_pushcclosure(L, bridges[upvalues], upvalues + 1);
  push_registry_table(L, &entries_key);
  lua_pushvalue(L, -2);
  lua_pushlightuserdata(L, const_cast<Entry*>(entry));
  lua_rawset(L, -3);
  lua_pop(L, 1);
}
}  // namespace

const char* running_function_name(lua_State* L, bool& is_method) {
  is_method = false;
  lua_Debug ar;
  if (!lua_getstack(L, 0, &ar)) return nullptr;
  lua_getinfo(L, "nf", &ar);
  const Entry* entry = find_entry(L, -1);
  lua_pop(L, 1);
  is_method = ar.namewhat != nullptr && std::strcmp(ar.namewhat, "method") == 0;
  if (entry != nullptr) return entry->qualified;
  return ar.name != nullptr ? ar.name : "?";
}

void register_entries(lua_State* L, int table_index, const Entry* entries, int upvalues) {
  table_index = lua_absindex(L, table_index);
  const int first_upvalue = lua_gettop(L) - upvalues + 1;
  for (const Entry* e = entries; e->name != nullptr; ++e) {
    push_entry(L, e, first_upvalue, upvalues);
    lua_setfield(L, table_index, e->name);
  }
  lua_pop(L, upvalues);
}

void register_topic(lua_State* L, int value_index, const char* qualified, const char* doc) {
  // Topics need an Entry that outlives the state: they are static strings, so a small
  // userdata kept alive by the entries table holds the Entry.
  value_index = lua_absindex(L, value_index);
  push_registry_table(L, &entries_key);
  lua_pushvalue(L, value_index);
  auto* entry = static_cast<Entry*>(lua_newuserdatauv(L, sizeof(Entry), 0));
  *entry = Entry{qualified, nullptr, qualified, qualified, doc};
  lua_rawset(L, -3);
  lua_pop(L, 1);
}

const Entry* find_entry(lua_State* L, int index) {
  index = lua_absindex(L, index);
  push_registry_table(L, &entries_key);
  lua_pushvalue(L, index);
  lua_rawget(L, -2);
  const Entry* entry = static_cast<const Entry*>(lua_touserdata(L, -1));
  lua_pop(L, 2);
  return entry;
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

// ==== 5. types ==================================================================================

namespace {
constexpr int properties_upvalue = 1;  // of __index and __newindex
constexpr int methods_upvalue = 2;     // of __index
constexpr int type_upvalue = 3;

// Pushes the record of `type` (see the top of this file).
void push_record(lua_State* L, const TypeSpec& type) {
  push_registry_table(L, &types_key);
  lua_rawgetp(L, -1, &type);
  lua_remove(L, -2);
  luaL_argcheck(L, lua_istable(L, -1), 1, "binding: the type was not made with new_type");
}

const TypeSpec& upvalue_type(lua_State* L) {
  return *static_cast<const TypeSpec*>(lua_touserdata(L, lua_upvalueindex(type_upvalue)));
}

// The Property named by the key at `key`, looked up in the properties table at `table`.
const Property* find_property(lua_State* L, int table, int key) {
  if (lua_type(L, key) != LUA_TSTRING) return nullptr;
  lua_pushvalue(L, key);
  lua_rawget(L, table);
  const auto* p = static_cast<const Property*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  return p;
}

// The names of the properties in the table at `table`, joined by ", "; pushed.
const char* push_property_list(lua_State* L, int table, bool settable_only) {
  table = lua_absindex(L, table);
  luaL_Buffer list;
  luaL_buffinit(L, &list);
  bool first = true;
  for (lua_Integer i = 1; lua_rawgeti(L, table, i) == LUA_TSTRING; ++i) {
    lua_pushvalue(L, -1);
    lua_rawget(L, table);
    const auto* p = static_cast<const Property*>(lua_touserdata(L, -1));
    lua_pop(L, 2);
    if (settable_only && p->set == nullptr) continue;
    if (!first) luaL_addstring(&list, ", ");
    luaL_addstring(&list, p->name);
    first = false;
  }
  lua_pop(L, 1);
  luaL_pushresult(&list);
  return lua_tostring(L, -1);
}

int type_index(lua_State* L) {
  const int properties = lua_upvalueindex(properties_upvalue);
  if (const Property* p = find_property(L, properties, 2)) {
    lua_settop(L, 2);
    p->get(L, 1, *p);
    return 1;
  }
  if (lua_type(L, 2) == LUA_TSTRING) {
    lua_pushvalue(L, 2);
    if (lua_rawget(L, lua_upvalueindex(methods_upvalue)) != LUA_TNIL) return 1;
  }
  const TypeSpec& type = upvalue_type(L);
  const char* key = push_key_name(L, 2);
  field_error(L, type.name, key,
              "no such field; the fields are %s, the methods are in help(\"%s\")",
              push_property_list(L, properties, false), type.name);
}

int type_newindex(lua_State* L) {
  const int properties = lua_upvalueindex(properties_upvalue);
  const TypeSpec& type = upvalue_type(L);
  const Property* p = find_property(L, properties, 2);
  if (p == nullptr) {
    const char* key = push_key_name(L, 2);
    field_error(L, type.name, key, "no such field; the settable fields are %s",
                push_property_list(L, properties, true));
  }
  if (p->set == nullptr) field_error(L, type.name, p->name, "read-only: %s", p->fixed);
  const Where where = Where::property(type.name, p->name);
  lua_settop(L, 3);
  if (type.check_settable != nullptr) type.check_settable(L, 1, where);
  p->set(L, 1, 3, where, *p);
  return 0;
}

// The Entries of __index and __newindex of one type, named "world.__index": kept alive by the
// record, which also holds their names.
void push_accessors(lua_State* L, const TypeSpec& type, int metatable, int record) {
  auto* entries = static_cast<Entry*>(lua_newuserdatauv(L, 2 * sizeof(Entry), 0));
  lua_setfield(L, record, "accessors");
  const char* index_name = lua_pushfstring(L, "%s.__index", type.name);
  lua_setfield(L, record, "index_name");  // the record keeps the string alive
  const char* newindex_name = lua_pushfstring(L, "%s.__newindex", type.name);
  lua_setfield(L, record, "newindex_name");
  entries[0] = Entry{"__index", type_index, index_name, "x.field, x:method()",
                     "Fields (properties) and methods."};
  entries[1] = Entry{"__newindex", type_newindex, newindex_name, "x.field = value",
                     "Sets a property; see the type's help for which are settable."};
  lua_getfield(L, record, "properties");
  lua_getfield(L, record, "methods");
  lua_pushlightuserdata(L, const_cast<TypeSpec*>(&type));
  push_entry(L, &entries[0], lua_gettop(L) - 2, 3);
  lua_setfield(L, metatable, "__index");
  push_entry(L, &entries[1], lua_gettop(L) - 2, 3);  // the same upvalues
  lua_setfield(L, metatable, "__newindex");
  lua_pop(L, 3);
}
}  // namespace

void new_type(lua_State* L, const TypeSpec& type, int public_index, const Entry* metamethods) {
  public_index = lua_absindex(L, public_index);
  new_metatable(L, type.name, type.metatable_key);
  const int metatable = lua_gettop(L);
  register_entries(L, metatable, metamethods);
  lua_createtable(L, 0, 4);  // the record
  const int record = lua_gettop(L);
  lua_newtable(L);
  lua_setfield(L, record, "methods");
  lua_newtable(L);
  lua_setfield(L, record, "properties");
  lua_pushvalue(L, public_index);
  lua_setfield(L, record, "public");
  push_registry_table(L, &types_key);
  lua_pushvalue(L, record);
  lua_rawsetp(L, -2, &type);
  lua_pushvalue(L, public_index);
  lua_pushvalue(L, record);
  lua_rawset(L, -3);
  lua_pop(L, 1);
  push_accessors(L, type, metatable, record);
  lua_pop(L, 2);  // record, metatable
}

void add_methods(lua_State* L, const TypeSpec& type, const Entry* methods) {
  push_record(L, type);
  lua_getfield(L, -1, "methods");
  register_entries(L, -1, methods);
  lua_getfield(L, -2, "public");
  register_entries(L, -1, methods);  // world.step(w, dt) works as w:step(dt)
  lua_pop(L, 3);
}

void add_properties(lua_State* L, const TypeSpec& type, const Property* properties) {
  push_record(L, type);
  lua_getfield(L, -1, "properties");
  for (const Property* p = properties; p->name != nullptr; ++p) {
    lua_pushstring(L, p->name);
    if (lua_rawget(L, -2) == LUA_TNIL) {  // a new name goes at the end of the order
      lua_pushstring(L, p->name);
      lua_rawseti(L, -3, static_cast<lua_Integer>(lua_rawlen(L, -3)) + 1);
    }
    lua_pop(L, 1);
    lua_pushlightuserdata(L, const_cast<Property*>(p));
    lua_setfield(L, -2, p->name);
  }
  lua_pop(L, 2);
}

namespace {
// The properties of the record on top of the stack (left there).
std::vector<const Property*> properties_of_record(lua_State* L, bool settable_only) {
  std::vector<const Property*> list;
  lua_getfield(L, -1, "properties");
  for (lua_Integer i = 1; lua_rawgeti(L, -1, i) == LUA_TSTRING; ++i) {
    lua_rawget(L, -2);
    const auto* p = static_cast<const Property*>(lua_touserdata(L, -1));
    lua_pop(L, 1);
    if (!settable_only || p->set != nullptr) list.push_back(p);
  }
  lua_pop(L, 2);
  return list;
}
}  // namespace

std::vector<const Property*> type_properties(lua_State* L, const TypeSpec& type,
                                             bool settable_only) {
  push_record(L, type);
  std::vector<const Property*> list = properties_of_record(L, settable_only);
  lua_pop(L, 1);
  return list;
}

std::vector<const Property*> topic_properties(lua_State* L, int index) {
  index = lua_absindex(L, index);
  push_registry_table(L, &types_key);
  lua_pushvalue(L, index);
  const bool found = lua_rawget(L, -2) == LUA_TTABLE;
  std::vector<const Property*> list;
  if (found) list = properties_of_record(L, false);  // leaves the record
  lua_pop(L, 2);  // the record (or nil) and the types table
  return list;
}

std::vector<const char*> constructor_fields(lua_State* L, const TypeSpec& type,
                                            const char* const* extra) {
  std::vector<const char*> allowed;
  for (const char* const* name = extra; name != nullptr && *name != nullptr; ++name)
    allowed.push_back(*name);
  for (const Property* p : type_properties(L, type, true)) allowed.push_back(p->name);
  return allowed;
}

void set_from_table(lua_State* L, const TypeSpec& type, int object, int arg) {
  object = lua_absindex(L, object);
  arg = lua_absindex(L, arg);
  const std::vector<const Property*> settable = type_properties(L, type, true);
  for (const Property* p : settable) {
    if (get_field(L, arg, p->name) != LUA_TNIL)
      p->set(L, object, lua_gettop(L), Where::field(arg, p->name), *p);
    lua_pop(L, 1);
  }
}

// ==== stopping long C loops =====================================================================

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
