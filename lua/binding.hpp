// The binding toolbox: the one place that says how a rigidlab binding checks what it is given,
// reports what is wrong, calls the engine and exposes a type. Every file in lua/ uses it, so
// that a new binding (joints, recorders, ...) is a list of short functions and two tables.
//
// A binding function (STYLE.md "Take" 2-4, LÖVE's w_Body_getMass): check the arguments, call
// the engine, push the results.
//
//   int body_apply_torque(lua_State* L) {
//     const Body& b = check_body(L, 1);              // self: "calling 'body:apply_torque' on
//     const Vec3 t = check_vec3(L, 2);               //   bad self (body expected, got number)"
//     check_no_extra_args(L, 2);
//     protect(L, [&] { apply_torque(b, t); });       // engine exceptions -> Lua errors
//     return 0;
//   }
//
// 1. Messages. Three forms, all prefixed with the script's position as luaL_error does:
//      bad argument #2 to 'inertia.solid_box' (width must be > 0, got -1)   arg_error
//      calling 'world:add' on bad self (...)                                 arg_error(L, 1, ...)
//      bad field 'x' of vec3 (...)                                          field_error
//    The function's name comes from its Entry (register_entries), so it is 'vec3:cross', not
//    '?'. A value being checked comes from somewhere, and the same check must speak in the
//    form of that place: a `Where` says which (an argument, a field of an option table, an
//    assignment to a property), and every check below takes one:
//      Where::argument(2, "dt")         bad argument #2 to 'world:step' (dt must be > 0, got 0)
//      Where::field(1, "substeps")      bad argument #1 to 'world' (field 'substeps' must ...)
//      Where::property("world", "slop") bad field 'slop' of world (must be ...)
// 2. Checks, one of each kind: check_number (finite, optionally in a range), check_integer
//    (2 and 2.0 alike, everywhere: luaL_checkinteger's rule), check_option (luaL_checkoption,
//    listing the choices), check_name (a string without NUL bytes: names and paths), the math
//    types, check_fields (the one validator of option-table keys: a misspelt key is an
//    error, never ignored), check_sequence (lists).
// 3. Reading option tables. Fields are read with lua_getfield, so a table's __index runs:
//    it may run any Lua code (add or remove bodies, collect garbage). So read every argument
//    and every field into plain values FIRST, and only then take pointers or indices into the
//    engine (Body&, BodyStore indices), and never keep one across a call into Lua.
// 4. The exception bridge (LÖVE's luax_catchexcept). Engine exceptions never cross Lua: every
//    registered function runs inside it (register_entries), and `protect` runs one engine
//    call inside it to choose the message: std::bad_alloc becomes Lua's own memory error
//    ("not enough memory", status LUA_ERRMEM, exactly what Lua's allocator raises, so pcall,
//    coroutine.wrap and the CLI's --max-memory treat both alike); any other std::exception
//    (std::invalid_argument, std::logic_error, ...) becomes an error naming the function or
//    the argument blamed, raised after the catch (STYLE.md 4). A binding that changes two
//    things (the engine and a Lua list) uses `try_call` to undo the first when the second
//    fails: every binding is all-or-nothing.
// 5. Types with properties. A userdata type (body, world; joints and recorders next) is a
//    TypeSpec, a table of methods (Entry) and a table of properties (Property: name, getter,
//    setter, help). __index, __newindex, their error messages ("no such field; the fields
//    are ...") and help() are generated from them, and a constructor's option table is read
//    through the same setters (set_from_table). Another file adds methods and properties to
//    a type with one line (lua/world.hpp):
//      add_methods(L, world_type, joint_methods);      // w:add_joint{...}
//      add_properties(L, world_type, solver_property); // w.solver, world{solver = ...}
#pragma once

#include <lua.hpp>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "engine/format.hpp"
#include "engine/math.hpp"

namespace rigidlab::lua {

// ==== 1. messages ===============================================================================

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
// are popped. Each function runs inside the exception bridge (section 4).
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
// "bad field 'NAME' of TYPE (REASON)": an assignment to, or a read of, a field of a rigidlab
// object that refuses it (b.mass = 5, v.w, w.gravity = 1). REASON says what is allowed and
// what came, as an argument error's does.
[[noreturn]] void field_error(lua_State* L, const char* type, const char* name,
                              const char* format, ...);
// luaL_error prefixed with the qualified name of the running function: "'world:step': ...".
// For failures that are no argument's fault (a step that would leave a NaN).
[[noreturn]] void function_error(lua_State* L, const char* format, ...);

// Where a value being checked came from, so that one check serves every place (see the top).
class Where {
 public:
  // Argument `arg` (self is 1 in a method); `name` ("dt") starts the reason, or nullptr.
  static Where argument(int arg, const char* name = nullptr) {
    return {Kind::argument, arg, name, nullptr};
  }
  // Field `name` of the option table that is argument `arg`: world{substeps = 0}.
  static Where field(int arg, const char* name) { return {Kind::field, arg, name, nullptr}; }
  // An assignment to property `name` of a `type` object: w.substeps = 0.
  static Where property(const char* type, const char* name) {
    return {Kind::property, 0, name, type};
  }
  // Raises the error in this place's form; `format` is the reason, e.g. "must be > 0, got %s".
  [[noreturn]] void error(lua_State* L, const char* format, ...) const;
  // "number expected, got string" (an argument, a property), "field 'x' must be a number,
  // got string" (an option field); the type as value_type_name names the value at `value`.
  [[noreturn]] void type_error(lua_State* L, int value, const char* expected) const;
  const char* name() const { return name_; }

 private:
  enum class Kind { argument, field, property };
  Where(Kind kind, int arg, const char* name, const char* type)
      : kind_(kind), arg_(arg), name_(name), type_(type) {}
  Kind kind_;
  int arg_;
  const char* name_;
  const char* type_;
};

// The name of the type of the value at `index` as messages show it: rigidlab's values (vec3,
// mat3, quat, body, world) by their tag, which a script cannot forge (it can replace a
// metatable with debug.setmetatable, or give a table a __name); other userdata by their
// __name when it is not one of rigidlab's ("FILE*"), else "userdata"; everything else by its
// Lua type ("table", "no value"). Pushes nothing; the string lives as long as the value's
// metatable.
const char* value_type_name(lua_State* L, int index);
// The value at `index` as a message shows what came: a number as Lua prints it but %.14g for
// floats (1e+12, not 1000000000000.0), a string quoted ('verlet'), a vec3, mat3 or quat as
// tostring gives it, anything else by its type name ("table"). Pushes the string.
const char* push_shown_value(lua_State* L, int index);
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
// Raises an error for arguments past the last one a function takes: a silently ignored
// argument hides a typo. `max_args` counts self for methods.
void check_no_extra_args(lua_State* L, int max_args);

// ==== 2. checks =================================================================================

// A number (not a numeric string), finite: "must be finite, got nan".
double check_number(lua_State* L, int index, const Where& where);
// A finite number in [min, max] (either may be ±HUGE_VAL). A value that is not finite or out
// of range gets "must be RULE, got x" with `rule` ("in [0, 1]", "a finite number >= 0 (m)"),
// or without one "must be finite" or the range; one that is not a number a type error.
double check_number(lua_State* L, int index, const Where& where, double min, double max,
                    const char* rule = nullptr);
// An integer from min to max: 2 and 2.0 alike (an integral float counts, as in
// luaL_checkinteger), not 2.5, not "2": "must be an integer from 1 to 1000, got 2.5".
lua_Integer check_integer(lua_State* L, int index, const Where& where, lua_Integer min,
                          lua_Integer max);
// The value at `index` as an integer when it is a number with an integral value (2, 2.0).
bool to_integer(lua_State* L, int index, lua_Integer& out);
// luaL_checkoption: the position in `names` of the string at `index`, else "must be one of
// 'euler', 'semi_implicit', 'rk4', got 'verlet'" (or "got number"). `names` has `count`
// entries (or ends earlier at a nullptr).
int check_option(lua_State* L, int index, const Where& where, const char* const* names,
                 std::size_t count);
template <std::size_t N>
int check_option(lua_State* L, int index, const Where& where, const char* const (&names)[N]) {
  return check_option(L, index, where, names, N);
}
// A boolean (true/false, not any value): "must be a boolean, got number".
bool check_boolean(lua_State* L, int index, const Where& where);
// A string that is a name or a path for C code: Lua strings may hold NUL bytes, which C
// stops at, so 'vec3\0junk' would silently be read as 'vec3' (a file 'a\0b' written as 'a').
// Refused: "must not contain a NUL byte ('\0' at byte 5)". `length` receives the length.
const char* check_name(lua_State* L, int index, const Where& where, std::size_t* length = nullptr);
// A vec3 with finite components (a vec3 can hold inf, e.g. a row of a static body's infinite
// tensor; no input takes one): "vec3 expected, got number", "must be finite, got (inf, 0, 0)".
const Vec3& check_vec3(lua_State* L, int index, const Where& where);

// Argument forms (Where::argument(arg, what)): a finite number, > 0, >= 0.
double check_finite(lua_State* L, int arg, const char* what);
double check_positive(lua_State* L, int arg, const char* what);
double check_nonnegative(lua_State* L, int arg, const char* what);

// The one validator of option-table keys: refuses keys of the table at `arg` that are not in
// `allowed` (nullptr-terminated), listing them: "unknown field 'radious' (fields are: mass,
// radius, ...)". A misspelt field would otherwise be silently ignored. Reads raw (lua_next).
void check_fields(lua_State* L, int arg, const char* const* allowed);
void check_fields(lua_State* L, int arg, const std::vector<const char*>& allowed);
// The same for a table at any stack index (an entry of a list), the error in `where`'s form:
// Where::argument(1, "entry 2:") gives "bad argument #1 to 'f' (entry 2: unknown field ...)".
void check_fields(lua_State* L, int table, const char* const* allowed, const Where& where);
// The length n of the list at `arg` (a table, else a type error naming `expected`), whose keys
// must be exactly 1..n: a named field ({1, x = 5}) or an entry past a hole would otherwise be
// ignored. Messages start with `what`: "list of vec3: unexpected key 'x' (...)". n may be 0.
lua_Integer check_sequence(lua_State* L, int arg, const char* expected, const char* what);

// Option-table fields (Where::field): push field `name` of the table at `arg` (its __index
// runs) and return its Lua type (LUA_TNIL when absent). The field_* readers pop it again.
int get_field(lua_State* L, int arg, const char* name);
double field_finite(lua_State* L, int arg, const char* name, double fallback, bool required);
double field_positive(lua_State* L, int arg, const char* name, double fallback, bool required);
double field_nonnegative(lua_State* L, int arg, const char* name, double fallback, bool required);
Vec3 field_vec3(lua_State* L, int arg, const char* name, const Vec3& fallback, bool required);

// ==== the math types ============================================================================

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
inline constexpr std::uint64_t lesson_context_tag = 0x6374'7872'6967'646cULL;  // lua/lesson.cpp

template <class T>
T* test_tagged(lua_State* L, int index, std::uint64_t tag) {
  auto* box = static_cast<Tagged<T>*>(lua_touserdata(L, index));
  if (box == nullptr || lua_rawlen(L, index) != sizeof(Tagged<T>) || box->tag != tag)
    return nullptr;
  return &box->value;
}

// `value` is taken by copy before the allocation: the allocation may run a finaliser (any Lua
// code), which may move or free what a reference would point into (a body's store).
template <class T>
T& push_tagged(lua_State* L, T value, std::uint64_t tag, const void* metatable_key) {
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
// "bad field 'x' of vec3 (read-only: vec3 values are immutable; build a new one, e.g. ...)":
// vec3 and quat are values like numbers (API.md "Conventions"), so assigning a component is
// an error that says how to build the changed value. `how` is that example.
[[noreturn]] void immutable_error(lua_State* L, const char* type, int key_index, const char* how);

// ==== 4. the exception bridge ===================================================================

// What a C++ call threw, held without allocating (so that a std::bad_alloc can be held too).
class Failure {
 public:
  // Only the first byte is set: every bound call makes one (the bridge), so no memset.
  Failure() { message_[0] = '\0'; }
  explicit operator bool() const { return kind_ != Kind::none; }
  bool out_of_memory() const { return kind_ == Kind::memory; }
  const char* what() const { return message_; }
  // Raises the Lua error: Lua's memory error, else "bad argument #blame to 'f' (what)" when
  // `blame` > 0 (the argument at fault), else "'f': what" (function_error).
  [[noreturn]] void raise(lua_State* L, int blame = 0) const;

  void hold(const std::bad_alloc&) { kind_ = Kind::memory; }
  void hold(const std::exception& e);

 private:
  enum class Kind { none, memory, other };
  Kind kind_ = Kind::none;
  char message_[480];
};

// Runs `f` and returns what it threw (an empty Failure when nothing). Lua errors (which the
// C++ build of Lua throws as its own type, not a std::exception) pass through untouched.
template <class F>
Failure try_call(F&& f) {
  Failure failure;
  try {
    f();
  } catch (const std::bad_alloc& e) {
    failure.hold(e);
  } catch (const std::exception& e) {
    failure.hold(e);
  }
  return failure;
}

// Runs an engine call and returns its result; what it throws is raised as a Lua error after
// the catch (Failure::raise: the memory error, or a message blaming argument `blame`, or the
// function when `blame` is 0).
template <class F>
auto protect(lua_State* L, int blame, F&& f) -> decltype(f()) {
  Failure failure;
  try {
    return f();
  } catch (const std::bad_alloc& e) {
    failure.hold(e);
  } catch (const std::exception& e) {
    failure.hold(e);
  }
  failure.raise(L, blame);
}
template <class F>
auto protect(lua_State* L, F&& f) -> decltype(f()) {
  return protect(L, 0, static_cast<F&&>(f));
}
// Raises Lua's own memory error (status LUA_ERRMEM, message "not enough memory"), as if
// Lua's allocator had failed: what std::bad_alloc from C++ code becomes.
[[noreturn]] void memory_error(lua_State* L);

// ==== 5. types with methods and properties ======================================================

struct Property;
// Pushes the value of property `p` of the object at stack index `object`.
using Getter = void (*)(lua_State* L, int object, const Property& p);
// Checks the value at stack index `value` and stores it in the object at `object`; errors in
// the form of `where`. Must change nothing when it raises.
using Setter = void (*)(lua_State* L, int object, int value, const Where& where,
                        const Property& p);

// A field of a userdata type: w.gravity, b.position.
struct Property {
  const char* name;
  Getter get;
  Setter set;           // nullptr: read-only
  const char* doc;      // one line for help: what it is, its unit and frame
  const char* fixed;    // read-only ones: why it cannot be set ("it advances with w:step")
  const void* data;     // for getters and setters shared by several properties, or nullptr
};

// A userdata type whose fields are properties. One static TypeSpec per type; its address is
// the type's identity (the key of its records in the registry).
struct TypeSpec {
  const char* name;                 // "world": in messages and help
  const void* metatable_key;        // the registry key of its metatable (has_metatable)
  // Raises (in `where`'s form) when the object at `object` cannot be changed now, e.g. its
  // world is stepping; nullptr: always settable. Run before every assignment.
  void (*check_settable)(lua_State* L, int object, const Where& where);
};

// Creates the type's metatable (protected: __metatable = name) with __index and __newindex
// that serve its properties and methods, plus `metamethods` (__tostring, __gc, ...), and
// records the type. `public_index` is the type's table seen by scripts (the callable
// `world`): methods are set there too (world.step(w, dt) works as w:step(dt)), and help()
// lists the properties of that table's topic.
void new_type(lua_State* L, const TypeSpec& type, int public_index, const Entry* metamethods);
// Adds methods (nullptr-terminated) to a type made by new_type: one line from any file.
void add_methods(lua_State* L, const TypeSpec& type, const Entry* methods);
// Adds properties (ended by one whose name is nullptr), after those there already.
void add_properties(lua_State* L, const TypeSpec& type, const Property* properties);
// The type's properties in the order added; with `settable_only`, only those with a setter.
std::vector<const Property*> type_properties(lua_State* L, const TypeSpec& type,
                                             bool settable_only = false);
// The properties of the type whose public table is at `index` (for help), or empty.
std::vector<const Property*> topic_properties(lua_State* L, int index);
// The keys a constructor of `type` takes, for check_fields: `extra` (nullptr-terminated:
// constructor-only fields such as "mass"; may be nullptr), then the settable properties.
std::vector<const char*> constructor_fields(lua_State* L, const TypeSpec& type,
                                            const char* const* extra = nullptr);
// A constructor's option table: every settable property of `type` that the table at `arg`
// has (read with its __index) is set on the new object at `object` through its setter, in
// the order the properties were added, with errors as "bad argument #arg to 'world' (field
// 'substeps' must be ...)". The new object must not be reachable from Lua yet (the table's
// metamethods run in between). Validate the keys first (check_fields, constructor_fields).
void set_from_table(lua_State* L, const TypeSpec& type, int object, int arg);

// Creates a protected metatable for a userdata type and stores it in the registry under
// `key`: `__name` is `type_name`, `__metatable` hides it from getmetatable/setmetatable.
// Leaves the metatable on the stack. (new_type builds on it; plain value types use it.)
void new_metatable(lua_State* L, const char* type_name, const void* key);
// True when the value at `index` is a userdata whose metatable is the one stored under `key`.
bool has_metatable(lua_State* L, int index, const void* key);

// ==== stopping long C loops =====================================================================

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
