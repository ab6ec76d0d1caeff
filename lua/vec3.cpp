// vec3: a 3-vector value (Eigen::Vector3d in a userdata). Fields x, y, z (read-only: a vec3
// is immutable, API.md "Conventions"); arithmetic by
// metamethods; dot, cross, norm, normalized, outer, skew. Components are always finite: a
// construction or an operation that would produce NaN or Inf raises an error instead.
#include <cmath>

#include "lua/binding.hpp"
#include "lua/modules.hpp"

namespace rigidlab::lua {
namespace {

// vec3(x, y, z): missing components are 0.
int vec3_call(lua_State* L) {
  lua_remove(L, 1);  // the vec3 table itself
  check_no_extra_args(L, 3);
  static const char* const names[] = {"x", "y", "z"};
  Vec3 v = Vec3::Zero();
  for (int i = 0; i < 3; ++i)
    if (!lua_isnoneornil(L, i + 1)) v[i] = check_finite(L, i + 1, names[i]);
  push_vec3(L, v);
  return 1;
}

// The component index of a key "x", "y" or "z", or -1.
int component_index(lua_State* L, int key_index) {
  size_t length = 0;
  const char* key = lua_tolstring(L, key_index, &length);
  if (lua_type(L, key_index) != LUA_TSTRING || length != 1) return -1;
  switch (key[0]) {
    case 'x': return 0;
    case 'y': return 1;
    case 'z': return 2;
    default: return -1;
  }
}

int vec3_index(lua_State* L) {
  const Vec3& v = check_vec3(L, 1);
  const int i = component_index(L, 2);
  if (i >= 0) {
    lua_pushnumber(L, v[i]);
    return 1;
  }
  lua_pushvalue(L, 2);
  if (lua_type(L, 2) == LUA_TSTRING && lua_rawget(L, lua_upvalueindex(1)) != LUA_TNIL) return 1;
  field_error(L, "vec3", push_key_name(L, 2),
              "no such field; the fields are x, y, z, the methods are in help(\"vec3\")");
}

// vec3 values are immutable (API.md "Conventions"): v.x = 1 would change every alias of v,
// and b.position.x = 5 would change a copy and be lost. The error says what to write instead.
int vec3_newindex(lua_State* L) {
  check_vec3(L, 1);
  const int i = component_index(L, 2);
  if (i < 0) field_error(L, "vec3", push_key_name(L, 2), "no such field; the fields are x, y, z");
  const char* value = lua_type(L, 3) == LUA_TNUMBER ? push_shown_value(L, 3) : "new";
  static const char* const forms[] = {"%s, v.y, v.z", "v.x, %s, v.z", "v.x, v.y, %s"};
  static const char* const body_forms[] = {"%s, b.position.y, b.position.z",
                                           "b.position.x, %s, b.position.z",
                                           "b.position.x, b.position.y, %s"};
  const char* how = lua_pushfstring(L, "v = vec3(%s), or for a body b.position = vec3(%s)",
                                    lua_pushfstring(L, forms[i], value),
                                    lua_pushfstring(L, body_forms[i], value));
  immutable_error(L, "vec3", 2, how);
}

// The operands of a binary operator; raises an error that says which operand is wrong.
void check_two_vec3(lua_State* L, const Vec3*& a, const Vec3*& b) {
  a = test_vec3(L, 1);
  b = test_vec3(L, 2);
  if (a == nullptr) type_error(L, 1, "vec3");
  if (b == nullptr) type_error(L, 2, "vec3");
}

int vec3_add(lua_State* L) {
  const Vec3 *a, *b;
  check_two_vec3(L, a, b);
  push_finite(L, Vec3(*a + *b), 2);
  return 1;
}

int vec3_sub(lua_State* L) {
  const Vec3 *a, *b;
  check_two_vec3(L, a, b);
  push_finite(L, Vec3(*a - *b), 2);
  return 1;
}

int vec3_unm(lua_State* L) {
  push_vec3(L, -check_vec3(L, 1));
  return 1;
}

// v * s and s * v. A vec3 times a vec3 is refused with a pointer to dot and cross.
int vec3_mul(lua_State* L) {
  const Vec3* a = test_vec3(L, 1);
  const Vec3* b = test_vec3(L, 2);
  if (a != nullptr && b != nullptr)
    arg_error(L, 2, "vec3 * vec3 is not defined: use a:dot(b), a:cross(b) or a:outer(b)");
  if (a != nullptr && test_mat3(L, 2) != nullptr)
    arg_error(L, 2, "vec3 * mat3 is not defined (vectors are columns): use M * v or "
                    "M:transpose() * v");
  const int vector_arg = a != nullptr ? 1 : 2;
  const int scalar_arg = 3 - vector_arg;
  if (lua_type(L, scalar_arg) != LUA_TNUMBER)
    type_error(L, scalar_arg, vector_arg == 1 ? "number (vec3 * number)" : "number");
  const double s = check_finite(L, scalar_arg, "factor");
  push_finite(L, Vec3(check_vec3(L, vector_arg) * s), scalar_arg);
  return 1;
}

int vec3_div(lua_State* L) {
  const Vec3& v = check_vec3(L, 1);
  const double s = check_finite(L, 2, "divisor");
  if (s == 0.0) arg_error(L, 2, "division of a vec3 by zero");
  push_finite(L, Vec3(v / s), 2);
  return 1;
}

int vec3_eq(lua_State* L) {
  const Vec3* a = test_vec3(L, 1);
  const Vec3* b = test_vec3(L, 2);
  lua_pushboolean(L, a != nullptr && b != nullptr && *a == *b);
  return 1;
}

int vec3_tostring(lua_State* L) {
  const Vec3& v = check_vec3(L, 1);
  lua_pushfstring(L, "(%s, %s, %s)", format_number(v.x()).c_str(),
                  format_number(v.y()).c_str(), format_number(v.z()).c_str());
  return 1;
}

// "v = " .. v reads as naturally as print(v).
int vec3_concat(lua_State* L) {
  luaL_tolstring(L, 1, nullptr);
  luaL_tolstring(L, 2, nullptr);
  lua_concat(L, 2);
  return 1;
}

int vec3_dot(lua_State* L) {
  const Vec3& a = check_vec3(L, 1);
  const Vec3& b = check_vec3(L, 2);
  check_no_extra_args(L, 2);
  lua_pushnumber(L, a.dot(b));
  return 1;
}

int vec3_cross(lua_State* L) {
  const Vec3& a = check_vec3(L, 1);
  const Vec3& b = check_vec3(L, 2);
  check_no_extra_args(L, 2);
  push_finite(L, Vec3(a.cross(b)), 2);
  return 1;
}

int vec3_norm(lua_State* L) {
  const Vec3& a = check_vec3(L, 1);
  check_no_extra_args(L, 1);
  lua_pushnumber(L, stable_norm(a));
  return 1;
}

int vec3_normalized(lua_State* L) {
  const Vec3& a = check_vec3(L, 1);
  check_no_extra_args(L, 1);
  if (is_zero(a)) arg_error(L, 1, "cannot normalize the zero vector");
  push_finite(L, unit(a), 1);
  return 1;
}

int vec3_outer(lua_State* L) {
  const Vec3& a = check_vec3(L, 1);
  const Vec3& b = check_vec3(L, 2);
  check_no_extra_args(L, 2);
  const Mat3 m = a * b.transpose();
  check_result(L, m, 2);
  push_mat3(L, m);
  return 1;
}

int vec3_skew(lua_State* L) {
  const Vec3& a = check_vec3(L, 1);
  check_no_extra_args(L, 1);
  push_mat3(L, skew(a));
  return 1;
}

int vec3_unpack(lua_State* L) {
  const Vec3& a = check_vec3(L, 1);
  check_no_extra_args(L, 1);
  lua_pushnumber(L, a.x());
  lua_pushnumber(L, a.y());
  lua_pushnumber(L, a.z());
  return 3;
}

const Entry methods[] = {
    {"dot", vec3_dot, "vec3:dot", "a:dot(b) -> number", "Dot product a·b."},
    {"cross", vec3_cross, "vec3:cross", "a:cross(b) -> vec3",
     "Cross product a×b (right-handed)."},
    {"norm", vec3_norm, "vec3:norm", "a:norm() -> number", "Euclidean length |a|."},
    {"normalized", vec3_normalized, "vec3:normalized", "a:normalized() -> vec3",
     "a/|a|, the unit vector along a. Error for the zero vector."},
    {"outer", vec3_outer, "vec3:outer", "a:outer(b) -> mat3",
     "Outer product a⊗b = a bᵀ, the matrix with entries a_i b_j."},
    {"skew", vec3_skew, "vec3:skew", "a:skew() -> mat3",
     "The hat operator: the skew-symmetric matrix â with â * b == a:cross(b)."},
    {"unpack", vec3_unpack, "vec3:unpack", "a:unpack() -> x, y, z", "The three components."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry metamethods[] = {
    {"__add", vec3_add, "vec3.__add", "a + b", "Component-wise sum."},
    {"__sub", vec3_sub, "vec3.__sub", "a - b", "Component-wise difference."},
    {"__unm", vec3_unm, "vec3.__unm", "-a", "Negation."},
    {"__mul", vec3_mul, "vec3.__mul", "a * s, s * a", "Scaling by a number."},
    {"__div", vec3_div, "vec3.__div", "a / s", "Division by a non-zero number."},
    {"__eq", vec3_eq, "vec3.__eq", "a == b", "Exact equality of all components."},
    {"__tostring", vec3_tostring, "vec3.__tostring", "tostring(a)", "Short form: (x, y, z)."},
    {"__concat", vec3_concat, "vec3.__concat", "s .. a", "Concatenation as tostring."},
    {"__newindex", vec3_newindex, "vec3.__newindex", "a.x = n",
     "An error: vec3 values are immutable; build a new one, e.g. a = vec3(n, a.y, a.z)."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry index_entry[] = {
    {"__index", vec3_index, "vec3.__index", "a.x, a:method()", "Fields and methods."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry constructor[] = {
    {"__call", vec3_call, "vec3", "vec3(x, y, z) -> vec3",
     "A 3-vector. Missing components are 0: vec3() is the zero vector, vec3(1) is (1, 0, 0).\n"
     "A vec3 is a value, like a number: fields .x .y .z are read-only and operators make new\n"
     "vectors. To change a component build a new one: v = vec3(5, v.y, v.z), and for a body\n"
     "b.position = vec3(5, b.position.y, b.position.z) (b.position.x = 5 is an error).\n"
     "Operators: a + b, a - b, -a, a * s, s * a, a / s, a == b (exact).\n"
     "Methods: dot, cross, norm, normalized, outer, skew, unpack."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void open_vec3(lua_State* L, int lib) {
  new_metatable(L, "vec3", &vec3_metatable_key);
  register_entries(L, -1, metamethods);
  lua_newtable(L);  // methods, the upvalue of __index
  register_entries(L, -1, methods);
  register_entries(L, -2, index_entry, 1);
  lua_pop(L, 1);

  lua_newtable(L);  // the callable `vec3` table
  lua_newtable(L);
  register_entries(L, -1, constructor);
  lua_pushliteral(L, "vec3");
  lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, -2);
  register_entries(L, -1, methods);  // vec3.cross(a, b) works as a:cross(b)
  register_topic(L, -1, "vec3", constructor[0].doc);
  lua_setfield(L, lib, "vec3");
}

}  // namespace rigidlab::lua
