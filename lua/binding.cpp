// The binding toolbox, sections 1-4 of lua/binding.hpp: messages, checks, the math types'
// helpers and the exception bridge. Types and registration are in lua/binding_types.cpp.
#include "lua/binding.hpp"

#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace rigidlab::lua {

const char vec3_metatable_key = 0;
const char mat3_metatable_key = 0;
const char quat_metatable_key = 0;

// Defined in lua/binding_types.cpp: the qualified name of the running C function (nullptr
// outside one) and whether it was called as a method.
const char* running_function_name(lua_State* L, bool& is_method);

// ==== 1. messages ===============================================================================

namespace {

// arg_error with the reason already pushed as a string.
[[noreturn]] void raise_argument(lua_State* L, int arg, const char* reason) {
  bool is_method = false;
  const char* name = running_function_name(L, is_method);
  if (name == nullptr) luaL_error(L, "bad argument #%d (%s)", arg, reason);
  if (is_method) {
    --arg;  // do not count self, as luaL_argerror
    if (arg == 0) luaL_error(L, "calling '%s' on bad self (%s)", name, reason);
  }
  luaL_error(L, "bad argument #%d to '%s' (%s)", arg, name, reason);
  std::abort();  // luaL_error does not return
}

[[noreturn]] void raise_field(lua_State* L, const char* type, const char* name,
                              const char* reason) {
  luaL_error(L, "bad field '%s' of %s (%s)", name, type, reason);
  std::abort();
}

// "a number", "an integer": the article for a type name in "field 'x' must be a number".
const char* article(const char* noun) {
  return std::strchr("aeiou", noun[0]) != nullptr && noun[0] != '\0' ? "an" : "a";
}

}  // namespace

void arg_error(lua_State* L, int arg, const char* format, ...) {
  va_list args;
  va_start(args, format);
  const char* reason = lua_pushvfstring(L, format, args);
  va_end(args);
  raise_argument(L, arg, reason);
}

void type_error(lua_State* L, int arg, const char* expected) {
  arg_error(L, arg, "%s expected, got %s", expected, value_type_name(L, arg));
}

void field_error(lua_State* L, const char* type, const char* name, const char* format, ...) {
  va_list args;
  va_start(args, format);
  const char* reason = lua_pushvfstring(L, format, args);
  va_end(args);
  raise_field(L, type, name, reason);
}

void function_error(lua_State* L, const char* format, ...) {
  va_list args;
  va_start(args, format);
  const char* message = lua_pushvfstring(L, format, args);
  va_end(args);
  bool is_method = false;
  const char* name = running_function_name(L, is_method);
  luaL_error(L, "'%s': %s", name != nullptr ? name : "?", message);
  std::abort();
}

void Where::error(lua_State* L, const char* format, ...) const {
  va_list args;
  va_start(args, format);
  const char* reason = lua_pushvfstring(L, format, args);
  va_end(args);
  switch (kind_) {
    case Kind::argument:
      if (name_ != nullptr) reason = lua_pushfstring(L, "%s %s", name_, reason);
      raise_argument(L, arg_, reason);
    case Kind::field:
      raise_argument(L, arg_, lua_pushfstring(L, "field '%s' %s", name_, reason));
    case Kind::property:
      break;
  }
  raise_field(L, type_, name_, reason);
}

void Where::type_error(lua_State* L, int value, const char* expected) const {
  value = lua_absindex(L, value);
  const char* got = value_type_name(L, value);
  if (kind_ == Kind::field)
    raise_argument(L, arg_, lua_pushfstring(L, "field '%s' must be %s %s, got %s", name_,
                                            article(expected), expected, got));
  const char* reason = lua_pushfstring(L, "%s expected, got %s", expected, got);
  if (kind_ == Kind::argument) raise_argument(L, arg_, reason);
  raise_field(L, type_, name_, reason);
}

namespace {
// rigidlab's userdata types: the tag that starts each value, and its name.
struct TaggedType {
  std::uint64_t tag;
  const char* name;
};
constexpr TaggedType tagged_types[] = {
    {vec3_tag, "vec3"}, {mat3_tag, "mat3"}, {quat_tag, "quat"},
    {body_tag, "body"}, {world_tag, "world"}, {lesson_context_tag, "lesson context"}};

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

const char* push_shown_value(lua_State* L, int index) {
  index = lua_absindex(L, index);
  switch (lua_type(L, index)) {
    case LUA_TNUMBER:
      if (lua_isinteger(L, index)) return lua_pushfstring(L, "%I", lua_tointeger(L, index));
      return lua_pushstring(L, format_number(lua_tonumber(L, index)).c_str());
    case LUA_TSTRING: {
      std::size_t length = 0;
      const char* s = lua_tolstring(L, index, &length);
      constexpr std::size_t shown = 40;  // a message quotes the start of a long string
      if (length <= shown) return lua_pushfstring(L, "'%s'", s);
      lua_pushliteral(L, "'");
      lua_pushlstring(L, s, shown);
      lua_pushfstring(L, "...' (%I bytes)", static_cast<lua_Integer>(length));
      lua_concat(L, 3);
      return lua_tostring(L, -1);
    }
    default: break;
  }
  if (const Vec3* v = test_vec3(L, index))
    return lua_pushfstring(L, "(%s, %s, %s)", format_number(v->x()).c_str(),
                           format_number(v->y()).c_str(), format_number(v->z()).c_str());
  if (const Mat3* m = test_mat3(L, index)) {
    luaL_Buffer text;
    luaL_buffinit(L, &text);
    for (int k = 0; k < 9; ++k) {
      luaL_addstring(&text, k == 0 ? "((" : k % 3 == 0 ? "), (" : ", ");
      luaL_addstring(&text, format_number((*m)(k / 3, k % 3)).c_str());
    }
    luaL_addstring(&text, "))");
    luaL_pushresult(&text);
    return lua_tostring(L, -1);
  }
  if (const Quat* q = test_quat(L, index))
    return lua_pushfstring(L, "quat(%s, %s, %s, %s)", format_number(q->w()).c_str(),
                           format_number(q->x()).c_str(), format_number(q->y()).c_str(),
                           format_number(q->z()).c_str());
  return lua_pushstring(L, value_type_name(L, index));
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

void check_no_extra_args(lua_State* L, int max_args) {
  const int top = lua_gettop(L);
  if (top > max_args)
    arg_error(L, max_args + 1, "no more than %d argument%s expected, got %d", max_args,
              max_args == 1 ? "" : "s", top);
}

void immutable_error(lua_State* L, const char* type, int key_index, const char* how) {
  field_error(L, type, push_key_name(L, key_index),
              "read-only: %s values are immutable, like numbers; build a new one, e.g. %s", type,
              how);
}

// ==== 2. checks =================================================================================

double check_number(lua_State* L, int index, const Where& where) {
  if (lua_type(L, index) != LUA_TNUMBER) where.type_error(L, index, "number");
  const double x = lua_tonumber(L, index);
  if (!std::isfinite(x)) where.error(L, "must be finite, got %s", format_number(x).c_str());
  return x;
}

double check_number(lua_State* L, int index, const Where& where, double min, double max,
                    const char* rule) {
  if (lua_type(L, index) != LUA_TNUMBER) where.type_error(L, index, "number");
  const double x = lua_tonumber(L, index);
  if (x >= min && x <= max && std::isfinite(x)) return x;
  const std::string got = format_number(x);
  if (rule != nullptr) where.error(L, "must be %s, got %s", rule, got.c_str());
  if (!std::isfinite(x)) where.error(L, "must be finite, got %s", got.c_str());
  if (std::isinf(max))
    where.error(L, "must be >= %s, got %s", format_number(min).c_str(), got.c_str());
  if (std::isinf(min))
    where.error(L, "must be <= %s, got %s", format_number(max).c_str(), got.c_str());
  where.error(L, "must be in [%s, %s], got %s", format_number(min).c_str(),
              format_number(max).c_str(), got.c_str());
}

bool to_integer(lua_State* L, int index, lua_Integer& out) {
  if (lua_type(L, index) != LUA_TNUMBER) return false;
  int is_integer = 0;
  out = lua_tointegerx(L, index, &is_integer);  // 2.0 converts; 2.5, 1e100, nan do not
  return is_integer != 0;
}

lua_Integer check_integer(lua_State* L, int index, const Where& where, lua_Integer min,
                          lua_Integer max) {
  index = lua_absindex(L, index);
  lua_Integer n = 0;
  if (!to_integer(L, index, n) || n < min || n > max)
    where.error(L, "must be an integer from %I to %I, got %s", min, max,
                push_shown_value(L, index));
  return n;
}

int check_option(lua_State* L, int index, const Where& where, const char* const* names,
                 std::size_t count) {
  index = lua_absindex(L, index);
  if (lua_type(L, index) == LUA_TSTRING) {
    const char* value = lua_tostring(L, index);
    std::size_t length = 0;
    lua_tolstring(L, index, &length);
    for (std::size_t i = 0; i < count && names[i] != nullptr; ++i)
      if (std::strlen(names[i]) == length && std::strcmp(value, names[i]) == 0)
        return static_cast<int>(i);
  }
  luaL_Buffer choices;
  luaL_buffinit(L, &choices);
  for (std::size_t i = 0; i < count && names[i] != nullptr; ++i) {
    if (i > 0) luaL_addstring(&choices, ", ");
    luaL_addchar(&choices, '\'');
    luaL_addstring(&choices, names[i]);
    luaL_addchar(&choices, '\'');
  }
  luaL_pushresult(&choices);
  const char* list = lua_tostring(L, -1);
  const char* got = lua_type(L, index) == LUA_TSTRING ? push_shown_value(L, index)
                                                      : value_type_name(L, index);
  where.error(L, "must be one of %s, got %s", list, got);
}

bool check_boolean(lua_State* L, int index, const Where& where) {
  if (!lua_isboolean(L, index)) where.type_error(L, index, "boolean");
  return lua_toboolean(L, index) != 0;
}

const char* check_name(lua_State* L, int index, const Where& where, std::size_t* length) {
  if (lua_type(L, index) != LUA_TSTRING) where.type_error(L, index, "string");
  std::size_t size = 0;
  const char* s = lua_tolstring(L, index, &size);
  if (const void* nul = std::memchr(s, '\0', size))
    where.error(L, "must not contain a NUL byte ('\\0' at byte %I of %I; C reads the name "
                "only up to it)",
                static_cast<lua_Integer>(static_cast<const char*>(nul) - s + 1),
                static_cast<lua_Integer>(size));
  if (length != nullptr) *length = size;
  return s;
}

const Vec3& check_vec3(lua_State* L, int index, const Where& where) {
  const Vec3* v = test_vec3(L, index);
  if (v == nullptr) where.type_error(L, index, "vec3");
  if (!is_finite(*v)) where.error(L, "must be finite, got %s", push_shown_value(L, index));
  return *v;
}

double check_finite(lua_State* L, int arg, const char* what) {
  return check_number(L, arg, Where::argument(arg, what));
}

namespace {
// A finite number that `holds` (> 0, >= 0), else "must be RULE, got x".
template <class Rule>
double check_finite_where(lua_State* L, int index, const Where& where, Rule holds,
                          const char* rule) {
  const double x = check_number(L, index, where);
  if (!holds(x)) where.error(L, "must be %s, got %s", rule, format_number(x).c_str());
  return x;
}
}  // namespace

double check_positive(lua_State* L, int arg, const char* what) {
  return check_finite_where(L, arg, Where::argument(arg, what), [](double x) { return x > 0; },
                            "> 0");
}

double check_nonnegative(lua_State* L, int arg, const char* what) {
  return check_finite_where(L, arg, Where::argument(arg, what), [](double x) { return x >= 0; },
                            ">= 0");
}

void check_fields(lua_State* L, int arg, const char* const* allowed) {
  check_fields(L, arg, allowed, Where::argument(arg));
}

void check_fields(lua_State* L, int table, const char* const* allowed, const Where& where) {
  table = lua_absindex(L, table);
  lua_pushnil(L);
  while (lua_next(L, table) != 0) {
    lua_pop(L, 1);  // value
    bool known = false;
    if (lua_type(L, -1) == LUA_TSTRING) {
      std::size_t length = 0;
      const char* key = lua_tolstring(L, -1, &length);
      for (const char* const* a = allowed; *a != nullptr && !known; ++a)
        known = std::strlen(*a) == length && std::strcmp(*a, key) == 0;
    }
    if (known) continue;
    luaL_Buffer list;
    luaL_buffinit(L, &list);
    for (const char* const* a = allowed; *a != nullptr; ++a) {
      if (a != allowed) luaL_addstring(&list, ", ");
      luaL_addstring(&list, *a);
    }
    luaL_pushresult(&list);
    const int list_index = lua_gettop(L);
    const char* key = push_key_name(L, -2);  // no __tostring runs
    where.error(L, "unknown field '%s' (fields are: %s)", key, lua_tostring(L, list_index));
  }
}

void check_fields(lua_State* L, int arg, const std::vector<const char*>& allowed) {
  std::vector<const char*> terminated(allowed);
  terminated.push_back(nullptr);
  check_fields(L, arg, terminated.data());
}

lua_Integer check_sequence(lua_State* L, int arg, const char* expected, const char* what) {
  arg = lua_absindex(L, arg);
  if (lua_type(L, arg) != LUA_TTABLE) type_error(L, arg, expected);
  const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, arg));
  lua_pushnil(L);
  while (lua_next(L, arg) != 0) {
    lua_pop(L, 1);
    if (lua_isinteger(L, -1) && lua_tointeger(L, -1) >= 1 && lua_tointeger(L, -1) <= n) continue;
    const char* key = push_key_name(L, -1);
    if (n == 0)
      arg_error(L, arg, "%s: unexpected key '%s' (the entries of a list are numbered 1, 2, ...; "
                        "this one has none)", what, key);
    arg_error(L, arg, "%s: unexpected key '%s' (entries must be numbered 1 to %I)", what, key, n);
  }
  return n;
}

int get_field(lua_State* L, int arg, const char* name) { return lua_getfield(L, arg, name); }

namespace {
// Field `name` of the table at `arg` checked by `check` (value index, Where), popped again.
template <class T, class Check>
T read_field(lua_State* L, int arg, const char* name, const T& fallback, bool required,
             Check&& check) {
  arg = lua_absindex(L, arg);
  if (get_field(L, arg, name) == LUA_TNIL) {
    lua_pop(L, 1);
    if (required) arg_error(L, arg, "field '%s' is required", name);
    return fallback;
  }
  const T value = check(lua_gettop(L), Where::field(arg, name));
  lua_pop(L, 1);
  return value;
}
}  // namespace

double field_finite(lua_State* L, int arg, const char* name, double fallback, bool required) {
  return read_field(L, arg, name, fallback, required,
                    [L](int i, const Where& w) { return check_number(L, i, w); });
}

double field_positive(lua_State* L, int arg, const char* name, double fallback, bool required) {
  return read_field(L, arg, name, fallback, required, [L](int i, const Where& w) {
    return check_finite_where(L, i, w, [](double x) { return x > 0; }, "> 0");
  });
}

double field_nonnegative(lua_State* L, int arg, const char* name, double fallback,
                         bool required) {
  return read_field(L, arg, name, fallback, required, [L](int i, const Where& w) {
    return check_finite_where(L, i, w, [](double x) { return x >= 0; }, ">= 0");
  });
}

Vec3 field_vec3(lua_State* L, int arg, const char* name, const Vec3& fallback, bool required) {
  return read_field(L, arg, name, fallback, required,
                    [L](int i, const Where& w) { return Vec3(check_vec3(L, i, w)); });
}

// ==== the math types ============================================================================

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

// ==== 4. the exception bridge ===================================================================

void Failure::hold(const std::exception& e) {
  kind_ = Kind::other;
  std::snprintf(message_, sizeof message_, "%s", e.what());  // no allocation
}

void Failure::raise(lua_State* L, int blame) const {
  if (kind_ == Kind::memory) memory_error(L);
  if (blame > 0) arg_error(L, blame, "%s", message_);
  function_error(L, "%s", message_);
}

namespace {
// An allocator that refuses to grow anything and passes frees and shrinks to the state's own.
struct Refusing {
  lua_Alloc original;
  void* data;
  static void* allocate(void* self, void* block, std::size_t old_size, std::size_t new_size) {
    const auto* r = static_cast<const Refusing*>(self);
    if (new_size != 0 && (block == nullptr || new_size > old_size)) return nullptr;
    return r->original(r->data, block, old_size, new_size);
  }
};

// Puts the state's allocator back however the scope is left (Lua's errors are C++ exceptions
// in the C++ build of Lua that rigidlab links, so the destructor runs as the error unwinds).
class RefuseGrowth {
 public:
  explicit RefuseGrowth(lua_State* L) : L_(L) {
    refusing_.original = lua_getallocf(L, &refusing_.data);
    lua_setallocf(L, &Refusing::allocate, &refusing_);
  }
  ~RefuseGrowth() { lua_setallocf(L_, refusing_.original, refusing_.data); }
  RefuseGrowth(const RefuseGrowth&) = delete;
  RefuseGrowth& operator=(const RefuseGrowth&) = delete;

 private:
  lua_State* L_;
  Refusing refusing_{};
};
}  // namespace

void memory_error(lua_State* L) {
  // Lua has no API to raise its memory error (LUA_ERRMEM with the preallocated "not enough
  // memory"); an allocation that fails raises it. So one is made to fail: Lua collects
  // garbage, tries once more, and raises exactly the error its allocator failing would.
  {
    RefuseGrowth refuse(L);
    lua_newuserdatauv(L, 64, 0);
  }
  // Not reached; as lauxlib's own fallback (lauxlib.c resizebox) should it ever be.
  lua_pushliteral(L, "not enough memory");
  lua_error(L);
  std::abort();
}

}  // namespace rigidlab::lua
