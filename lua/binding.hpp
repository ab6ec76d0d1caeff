// The one toolbox every binding file uses: argument checking in luaL_argerror's style with the
// qualified function name ('inertia.solid_box', 'vec3:cross'), the userdata of the math types,
// and the registration of functions together with their help text.
//
// Conventions (see STYLE.md "Take" 2-4): a binding function checks its arguments, calls the
// engine, pushes results. Engine exceptions never cross Lua: wrap engine calls that may throw
// in `call_engine`. Every registered function has an `Entry` with its signature and doc, so
// `help()` and error messages find it by the function value.
#pragma once

#include <lua.hpp>

#include <cstdint>
#include <new>
#include <string>

#include "engine/format.hpp"
#include "engine/math.hpp"

namespace rigidlab::lua {

// A documented Lua function. `name` is the key in its table; `qualified` the name users see
// in errors and help ('vec3:cross', 'inertia.solid_box'); `signature` and `doc` feed help().
struct Entry {
  const char* name;
  lua_CFunction function;
  const char* qualified;
  const char* signature;
  const char* doc;
};

// Sets each entry's function as field `name` of the table at `table_index` and records it for
// help() and for error messages. The array ends with an entry whose name is nullptr. Like
// luaL_setfuncs, `upvalues` values on top of the stack become every function's upvalues and
// are popped.
void register_entries(lua_State* L, int table_index, const Entry* entries, int upvalues = 0);
// Records a documented topic that is not a function (a type or module table) for help().
void register_topic(lua_State* L, int value_index, const char* qualified, const char* doc);
// The Entry of the C function at `index`, or nullptr.
const Entry* find_entry(lua_State* L, int index);

// luaL_argerror with the qualified name of the running C function: in a method call
// (`v:cross(5)`) `arg` counts from the first argument after self, as Lua's own does.
[[noreturn]] void arg_error(lua_State* L, int arg, const char* format, ...);
// "<expected> expected, got <type>", the type as value_type_name gives it.
[[noreturn]] void type_error(lua_State* L, int arg, const char* expected);
// The name of the type of the value at `index` as messages show it: rigidlab's values (vec3,
// mat3, quat, body, world) by their tag, which a script cannot forge (it can replace a
// metatable with debug.setmetatable, or give a table a __name); other userdata by their
// __name when it is not one of rigidlab's ("FILE*"), else "userdata"; everything else by its
// Lua type ("table", "no value"). Pushes nothing; the string lives as long as the value's
// metatable.
const char* value_type_name(lua_State* L, int index);

// "bad field 'NAME' of TYPE (REASON)": an assignment to, or a read of, a field of a rigidlab
// object that refuses it (b.mass = 5, v.w, w.gravity = 1). REASON says what is allowed and
// what came, as an argument error's does: "vec3 expected, got number", "read-only: ...",
// "no such field; the fields are x, y, z". Prefixed with the script's position, as arg_error.
[[noreturn]] void field_error(lua_State* L, const char* type, const char* name,
                              const char* format, ...);
// field_error with "<expected> expected, got <type of the value at value_index>".
[[noreturn]] void field_type_error(lua_State* L, const char* type, const char* name,
                                   const char* expected, int value_index);
// The value at `value_index` assigned to field NAME of a TYPE, checked as field_error reports
// it: a finite number (v.x = n: "number expected, got string", "must be finite, got nan"), or a
// vec3 with finite components (b.position = p, w.gravity = g; a vec3 can hold inf, e.g. a row
// of a static body's infinite tensor).
double check_field_finite(lua_State* L, const char* type, const char* name, int value_index);
const Vec3& check_field_vec3(lua_State* L, const char* type, const char* name, int value_index);
// The key at `index` as a field name in messages, pushed: a string or a number as itself,
// other values as "table: 0x..." (no __tostring is run). For "bad field '1' of vec3".
const char* push_key_name(lua_State* L, int index);

// An operation on finite values whose result overflowed: "bad argument #2 to 'vec3.__add'
// (the result is not finite (a component overflows the largest double, 1.8e308))". `arg` is
// the operand blamed: the one that made the result too large (the second of a binary
// operator, the scalar of a product). `result` is "the result", "the inverse", ...; `part`
// is "a component", "an entry".
[[noreturn]] void overflow_error(lua_State* L, int arg, const char* result, const char* part);
// A call that changes a world while it steps (from a force callback): "calling 'world:add' on
// bad self (the world is stepping: cannot add a body until world:step returns; force callbacks
// may only apply forces)", or "bad argument #2 to ..." when the body is not self.
[[noreturn]] void stepping_error(lua_State* L, int arg, const char* what);
// luaL_error prefixed with the qualified name of the running function: "'world:step': ...".
[[noreturn]] void function_error(lua_State* L, const char* format, ...);
// Raises an error for arguments past the last one a function takes: a silently ignored
// argument hides a typo. `max_args` counts self for methods.
void check_no_extra_args(lua_State* L, int max_args);

// Numbers: must be a number (not a numeric string), finite.
double check_finite(lua_State* L, int arg, const char* what);
double check_positive(lua_State* L, int arg, const char* what);      // finite and > 0
double check_nonnegative(lua_State* L, int arg, const char* what);   // finite and >= 0
// The value at `index` as an integer when it is a number with an integral value: 2 and 2.0,
// as luaL_checkinteger accepts (not 2.5, not the string "2"). False otherwise.
bool to_integer(lua_State* L, int index, lua_Integer& out);
// The length n of the list at `arg` (a table, else a type error naming `expected`), whose keys
// must be exactly 1..n: a named field ({1, x = 5}) or an entry past a hole would otherwise be
// ignored. Messages start with `what`: "list of vec3: unexpected key 'x' (...)". n may be 0.
lua_Integer check_sequence(lua_State* L, int arg, const char* expected, const char* what);

// Registry keys of the metatables (their addresses are the keys; see lua_rawgetp).
extern const char vec3_metatable_key;
extern const char mat3_metatable_key;
extern const char quat_metatable_key;

// The math values are the hottest userdata: `a + b` checks two and creates one. Instead of
// comparing metatables (five API calls per argument) each value starts with a type tag, and
// the size must match too, so no other userdata (io's files, light userdata) can pass. Only C
// code creates userdata, so a script cannot forge a tag. Inline for the same reason.
template <class T>
struct Tagged {
  std::uint64_t tag;
  T value;
};
inline constexpr std::uint64_t vec3_tag = 0x7633'7269'6769'646cULL;  // arbitrary, distinct
inline constexpr std::uint64_t mat3_tag = 0x6d33'7269'6769'646cULL;
inline constexpr std::uint64_t quat_tag = 0x7174'7269'6769'646cULL;
inline constexpr std::uint64_t body_tag = 0x626f'6479'7269'646cULL;   // lua/body.cpp
inline constexpr std::uint64_t world_tag = 0x776f'726c'6472'6c62ULL;  // lua/world.cpp

template <class T>
T* test_tagged(lua_State* L, int index, std::uint64_t tag) {
  auto* box = static_cast<Tagged<T>*>(lua_touserdata(L, index));
  if (box == nullptr || lua_rawlen(L, index) != sizeof(Tagged<T>) || box->tag != tag)
    return nullptr;
  return &box->value;
}

template <class T>
T& push_tagged(lua_State* L, const T& value, std::uint64_t tag, const void* metatable_key) {
  void* memory = lua_newuserdatauv(L, sizeof(Tagged<T>), 0);
  auto* box = new (memory) Tagged<T>{tag, value};
  lua_rawgetp(L, LUA_REGISTRYINDEX, metatable_key);
  lua_setmetatable(L, -2);
  return box->value;
}

// Math userdata. `test_*` returns nullptr when the value is not of that type; `check_*`
// raises "vec3 expected, got number". `push_*` creates a new value.
inline Vec3* test_vec3(lua_State* L, int index) { return test_tagged<Vec3>(L, index, vec3_tag); }
inline Mat3* test_mat3(lua_State* L, int index) { return test_tagged<Mat3>(L, index, mat3_tag); }
inline Quat* test_quat(lua_State* L, int index) { return test_tagged<Quat>(L, index, quat_tag); }
Vec3& check_vec3(lua_State* L, int arg);
Mat3& check_mat3(lua_State* L, int arg);
Quat& check_quat(lua_State* L, int arg);
// Raises overflow_error (blaming `arg`) unless the result of an operation is finite.
inline void check_result(lua_State* L, const Vec3& v, int arg) {
  if (!is_finite(v)) overflow_error(L, arg, "the result", "a component");
}
inline void check_result(lua_State* L, const Mat3& m, int arg) {
  if (!is_finite(m)) overflow_error(L, arg, "the result", "an entry");
}
inline void check_result(lua_State* L, const Quat& q, int arg) {
  if (!is_finite(q)) overflow_error(L, arg, "the result", "a component");
}
inline Vec3& push_vec3(lua_State* L, const Vec3& v) {
  return push_tagged(L, v, vec3_tag, &vec3_metatable_key);
}
inline Mat3& push_mat3(lua_State* L, const Mat3& m) {
  return push_tagged(L, m, mat3_tag, &mat3_metatable_key);
}
inline Quat& push_quat(lua_State* L, const Quat& q) {
  return push_tagged(L, q, quat_tag, &quat_metatable_key);
}
// Pushes a result that must be finite (a vec3, mat3 or quat never holds NaN or Inf); an
// overflow is blamed on argument `arg`: the operand that made it too large, the point of
// b:to_world(p), self for a total such as w:linear_momentum().
inline Vec3& push_finite(lua_State* L, const Vec3& v, int arg) {
  check_result(L, v, arg);
  return push_vec3(L, v);
}
inline Mat3& push_finite(lua_State* L, const Mat3& m, int arg) {
  check_result(L, m, arg);
  return push_mat3(L, m);
}
inline Quat& push_finite(lua_State* L, const Quat& q, int arg) {
  check_result(L, q, arg);
  return push_quat(L, q);
}

// Creates a protected metatable for a userdata type and stores it in the registry under
// `key`: `__name` is `type_name`, `__metatable` hides it from getmetatable/setmetatable.
// Leaves the metatable on the stack.
void new_metatable(lua_State* L, const char* type_name, const void* key);
// 1 when the value at `index` is a userdata whose metatable is the one stored under `key`.
bool has_metatable(lua_State* L, int index, const void* key);

// Table-argument helpers for constructors like body{mass = 1, ...}: push field `name` of the
// table at `arg` and return its Lua type (LUA_TNIL when absent).
int get_field(lua_State* L, int arg, const char* name);
// Refuses keys of the table at `arg` that are not in `allowed` (nullptr-terminated): a
// misspelt field ("radious") would otherwise be silently ignored.
void check_fields(lua_State* L, int arg, const char* const* allowed);
// Field errors read "bad argument #1 to 'body' (field 'mass' must be > 0, got -1)".
double field_finite(lua_State* L, int arg, const char* name, double fallback, bool required);
double field_positive(lua_State* L, int arg, const char* name, double fallback, bool required);
Vec3 field_vec3(lua_State* L, int arg, const char* name, const Vec3& fallback, bool required);

// Long C loops (the engine's, in w:step) poll a stop check, because a Lua hook cannot
// interrupt C code. The embedding program (the CLI) installs a StopCheck that raises a Lua
// error (luaL_error) when the user pressed Ctrl-C or a time limit passed; loops call it often,
// so it must be cheap (read a flag). Without one, nothing happens. A loop must leave its
// objects consistent when the check raises (World::step undoes the step).
using StopCheck = void (*)(lua_State* L, void* data);
void set_stop_check(lua_State* L, StopCheck check, void* data);

// The state's stop check, looked up once for a loop: each poll() is one indirect call.
class StopPoller {
 public:
  explicit StopPoller(lua_State* L);
  void poll() const {
    if (check_ != nullptr) check_(L_, data_);
  }

 private:
  lua_State* L_;
  StopCheck check_ = nullptr;
  void* data_ = nullptr;
};

// Formats a number the way Lua's tostring does ("%.14g"), nan/inf/-inf for the non-finite
// (engine/format.hpp: one formatter for engine and binding messages).
using rigidlab::format_number;

}  // namespace rigidlab::lua
