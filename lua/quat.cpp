// quat: a quaternion value w + xi + yj + zk (four doubles in a userdata), mainly as a rotation.
// Fields w, x, y, z (read-only: a quat is immutable, API.md "Conventions"). Rotations use the
// normalised quaternion, so a slightly drifted one still rotates correctly; the zero
// quaternion, which is no rotation, is refused wherever a rotation is needed.
#include <cmath>

#include "lua/binding.hpp"
#include "lua/modules.hpp"

namespace rigidlab::lua {
namespace {

// The quaternion at `arg` as a unit rotation; error for the zero quaternion.
Quat check_rotation(lua_State* L, int arg) {
  const Quat& q = check_quat(L, arg);
  if (is_zero(q)) arg_error(L, arg, "the zero quaternion is not a rotation");
  return unit(q);
}

// quat(w, x, y, z); quat() is the identity. The first missing component is named: "bad
// argument #4 to 'quat' (number expected, got no value)".
int quat_call(lua_State* L) {
  lua_remove(L, 1);  // the quat table itself
  if (lua_gettop(L) == 0) {
    push_quat(L, Quat::Identity());
    return 1;
  }
  check_no_extra_args(L, 4);
  static const char* const names[] = {"w", "x", "y", "z"};
  double c[4];
  for (int i = 0; i < 4; ++i) c[i] = check_finite(L, i + 1, names[i]);  // in order
  push_quat(L, Quat(c[0], c[1], c[2], c[3]));
  return 1;
}

int quat_identity(lua_State* L) {
  check_no_extra_args(L, 0);
  push_quat(L, Quat::Identity());
  return 1;
}

int quat_axis_angle_new(lua_State* L) {
  const Vec3& axis = check_vec3(L, 1);
  const double angle = check_finite(L, 2, "angle");
  check_no_extra_args(L, 2);
  if (!is_finite(axis))  // a vec3 can hold inf: a row of a static body's infinite tensor
    arg_error(L, 1, "axis must be finite, got %s", luaL_tolstring(L, 1, nullptr));
  if (is_zero(axis)) arg_error(L, 1, "axis must be non-zero");
  push_quat(L, quat_from_axis_angle(axis, angle));
  return 1;
}

// quat.from_mat3(R): R must be a rotation matrix (orthonormal, det +1).
int quat_from_mat3(lua_State* L) {
  const Mat3& r = check_mat3(L, 1);
  check_no_extra_args(L, 1);
  // A mat3 can hold inf (a static body's tensor): its products would hold NaN, which no
  // comparison refuses, and the quaternion would be NaN.
  if (!is_finite(r)) arg_error(L, 1, "matrix must be finite, got %s", push_shown_value(L, 1));
  const double orthonormality = (r.transpose() * r - Mat3::Identity()).cwiseAbs().maxCoeff();
  if (!(orthonormality <= 1e-9))
    arg_error(L, 1, "matrix is not orthonormal (largest |RᵀR - E| entry = %s)",
              format_number(orthonormality).c_str());
  if (r.determinant() < 0.0) arg_error(L, 1, "matrix is a reflection (det = -1), not a rotation");
  Quat q(r);
  if (q.w() < 0.0) q.coeffs() *= -1.0;
  push_quat(L, unit(q));
  return 1;
}

int component_index(lua_State* L, int key_index) {
  size_t length = 0;
  if (lua_type(L, key_index) != LUA_TSTRING) return -1;
  const char* key = lua_tolstring(L, key_index, &length);
  if (length != 1) return -1;
  switch (key[0]) {
    case 'w': return 0;
    case 'x': return 1;
    case 'y': return 2;
    case 'z': return 3;
    default: return -1;
  }
}

double& component(Quat& q, int i) { return i == 0 ? q.w() : q.vec()[i - 1]; }

int quat_index(lua_State* L) {
  Quat& q = check_quat(L, 1);
  const int i = component_index(L, 2);
  if (i >= 0) {
    lua_pushnumber(L, component(q, i));
    return 1;
  }
  lua_pushvalue(L, 2);
  if (lua_type(L, 2) == LUA_TSTRING && lua_rawget(L, lua_upvalueindex(1)) != LUA_TNIL) return 1;
  field_error(L, "quat", push_key_name(L, 2),
              "no such field; the fields are w, x, y, z, the methods are in help(\"quat\")");
}

// quat values are immutable, as vec3 (lua/vec3.cpp): the error says what to write instead.
int quat_newindex(lua_State* L) {
  check_quat(L, 1);
  const int i = component_index(L, 2);
  if (i < 0)
    field_error(L, "quat", push_key_name(L, 2), "no such field; the fields are w, x, y, z");
  const char* value = lua_type(L, 3) == LUA_TNUMBER ? push_shown_value(L, 3) : "new";
  static const char* const forms[] = {"%s, q.x, q.y, q.z", "q.w, %s, q.y, q.z",
                                      "q.w, q.x, %s, q.z", "q.w, q.x, q.y, %s"};
  const char* how = lua_pushfstring(
      L, "q = quat(%s), or for a body b.orientation = quat.axis_angle(axis, angle)",
      lua_pushfstring(L, forms[i], value));
  immutable_error(L, "quat", 2, how);
}

void check_two_quat(lua_State* L, const Quat*& a, const Quat*& b) {
  a = test_quat(L, 1);
  b = test_quat(L, 2);
  if (a == nullptr) type_error(L, 1, "quat");
  if (b == nullptr) type_error(L, 2, "quat");
}

int quat_add(lua_State* L) {
  const Quat *a, *b;
  check_two_quat(L, a, b);
  push_finite(L, Quat(a->coeffs() + b->coeffs()), 2);
  return 1;
}

int quat_sub(lua_State* L) {
  const Quat *a, *b;
  check_two_quat(L, a, b);
  push_finite(L, Quat(a->coeffs() - b->coeffs()), 2);
  return 1;
}

int quat_unm(lua_State* L) {
  push_quat(L, Quat(-check_quat(L, 1).coeffs()));
  return 1;
}

// q * r (Hamilton product), q * s, s * q.
int quat_mul(lua_State* L) {
  const Quat* a = test_quat(L, 1);
  const Quat* b = test_quat(L, 2);
  if (a != nullptr && b != nullptr) {
    push_finite(L, *a * *b, 2);
  } else if (a != nullptr) {
    if (test_vec3(L, 2) != nullptr)
      arg_error(L, 2, "quat * vec3 is not defined: use q:rotate(v)");
    if (lua_type(L, 2) != LUA_TNUMBER) type_error(L, 2, "quat or number");
    const double s = check_finite(L, 2, "factor");
    push_finite(L, Quat(a->coeffs() * s), 2);
  } else {
    if (lua_type(L, 1) != LUA_TNUMBER) type_error(L, 1, "quat or number");
    const double s = check_finite(L, 1, "factor");
    push_finite(L, Quat(check_quat(L, 2).coeffs() * s), 1);
  }
  return 1;
}

int quat_div(lua_State* L) {
  const Quat& q = check_quat(L, 1);
  const double s = check_finite(L, 2, "divisor");
  if (s == 0.0) arg_error(L, 2, "division of a quat by zero");
  push_finite(L, Quat(q.coeffs() / s), 2);
  return 1;
}

int quat_eq(lua_State* L) {
  const Quat* a = test_quat(L, 1);
  const Quat* b = test_quat(L, 2);
  lua_pushboolean(L, a != nullptr && b != nullptr && a->coeffs() == b->coeffs());
  return 1;
}

int quat_tostring(lua_State* L) {
  const Quat& q = check_quat(L, 1);
  lua_pushfstring(L, "quat(%s, %s, %s, %s)", format_number(q.w()).c_str(),
                  format_number(q.x()).c_str(), format_number(q.y()).c_str(),
                  format_number(q.z()).c_str());
  return 1;
}

int quat_concat(lua_State* L) {
  luaL_tolstring(L, 1, nullptr);
  luaL_tolstring(L, 2, nullptr);
  lua_concat(L, 2);
  return 1;
}

int quat_rotate(lua_State* L) {
  const Quat q = check_rotation(L, 1);
  const Vec3& v = check_vec3(L, 2);
  check_no_extra_args(L, 2);
  push_vec3(L, q * v);
  return 1;
}

int quat_conj(lua_State* L) {
  const Quat& q = check_quat(L, 1);
  check_no_extra_args(L, 1);
  push_quat(L, q.conjugate());
  return 1;
}

int quat_inverse(lua_State* L) {
  const Quat& q = check_quat(L, 1);
  check_no_extra_args(L, 1);
  if (!(q.squaredNorm() > 0.0)) arg_error(L, 1, "the zero quaternion has no inverse");
  push_finite(L, Quat(q.conjugate().coeffs() / q.squaredNorm()), 1);
  return 1;
}

int quat_norm(lua_State* L) {
  const Quat& q = check_quat(L, 1);
  check_no_extra_args(L, 1);
  lua_pushnumber(L, stable_norm(q));
  return 1;
}

int quat_normalized(lua_State* L) {
  const Quat q = check_rotation(L, 1);
  check_no_extra_args(L, 1);
  push_quat(L, q);
  return 1;
}

int quat_to_mat3(lua_State* L) {
  const Quat q = check_rotation(L, 1);
  check_no_extra_args(L, 1);
  push_mat3(L, q.toRotationMatrix());
  return 1;
}

int quat_axis_angle(lua_State* L) {
  const Quat q = check_rotation(L, 1);
  check_no_extra_args(L, 1);
  Vec3 axis;
  double angle;
  quat_to_axis_angle(q, axis, angle);
  push_vec3(L, axis);
  lua_pushnumber(L, angle);
  return 2;
}

int quat_dot(lua_State* L) {
  const Quat& a = check_quat(L, 1);
  const Quat& b = check_quat(L, 2);
  check_no_extra_args(L, 2);
  lua_pushnumber(L, a.coeffs().dot(b.coeffs()));
  return 1;
}

int quat_unpack(lua_State* L) {
  const Quat& q = check_quat(L, 1);
  check_no_extra_args(L, 1);
  lua_pushnumber(L, q.w());
  lua_pushnumber(L, q.x());
  lua_pushnumber(L, q.y());
  lua_pushnumber(L, q.z());
  return 4;
}

const Entry methods[] = {
    {"rotate", quat_rotate, "quat:rotate", "q:rotate(v) -> vec3",
     "v rotated by q (q normalised first): q v q*."},
    {"conj", quat_conj, "quat:conj", "q:conj() -> quat", "Conjugate (w, -x, -y, -z)."},
    {"inverse", quat_inverse, "quat:inverse", "q:inverse() -> quat", "q⁻¹ = q* / |q|²."},
    {"norm", quat_norm, "quat:norm", "q:norm() -> number", "√(w² + x² + y² + z²)."},
    {"normalized", quat_normalized, "quat:normalized", "q:normalized() -> quat",
     "q / |q|. Error for the zero quaternion."},
    {"to_mat3", quat_to_mat3, "quat:to_mat3", "q:to_mat3() -> mat3",
     "The rotation matrix R of q (normalised first): R * v == q:rotate(v)."},
    {"axis_angle", quat_axis_angle, "quat:axis_angle", "q:axis_angle() -> axis, angle",
     "Unit axis and angle in [0, π] of the rotation (axis +x for the identity)."},
    {"dot", quat_dot, "quat:dot", "q:dot(r) -> number", "4-vector dot product."},
    {"unpack", quat_unpack, "quat:unpack", "q:unpack() -> w, x, y, z", "The four components."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry functions[] = {
    {"identity", quat_identity, "quat.identity", "quat.identity() -> quat", "quat(1, 0, 0, 0)."},
    {"axis_angle", quat_axis_angle_new, "quat.axis_angle", "quat.axis_angle(axis, angle) -> quat",
     "Rotation by angle (radians) about axis (any non-zero length), right-hand rule."},
    {"from_mat3", quat_from_mat3, "quat.from_mat3", "quat.from_mat3(R) -> quat",
     "The unit quaternion (w >= 0) of a rotation matrix R (orthonormal, det +1)."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry metamethods[] = {
    {"__add", quat_add, "quat.__add", "q + r", "4-vector sum (for integrating dq/dt)."},
    {"__sub", quat_sub, "quat.__sub", "q - r", "4-vector difference."},
    {"__unm", quat_unm, "quat.__unm", "-q", "Negation (the same rotation)."},
    {"__mul", quat_mul, "quat.__mul", "q * r, q * s, s * q", "Hamilton product; scaling."},
    {"__div", quat_div, "quat.__div", "q / s", "Division by a non-zero number."},
    {"__eq", quat_eq, "quat.__eq", "q == r", "Exact equality of all components."},
    {"__tostring", quat_tostring, "quat.__tostring", "tostring(q)", "quat(w, x, y, z)."},
    {"__concat", quat_concat, "quat.__concat", "s .. q", "Concatenation as tostring."},
    {"__newindex", quat_newindex, "quat.__newindex", "q.w = n",
     "An error: quat values are immutable; build a new one, e.g. q = quat(n, q.x, q.y, q.z)."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry index_entry[] = {
    {"__index", quat_index, "quat.__index", "q.w, q:method()", "Fields and methods."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry constructor[] = {
    {"__call", quat_call, "quat", "quat(w, x, y, z) -> quat",
     "A quaternion w + xi + yj + zk; quat() is the identity. A quat is a value, like a number:\n"
     "fields .w .x .y .z are read-only (build a new one: q = quat(w, q.x, q.y, q.z), and set a\n"
     "body's b.orientation = quat.axis_angle(axis, angle)).\n"
     "Functions: quat.identity(), quat.axis_angle(axis, angle), quat.from_mat3(R).\n"
     "Operators: q * r (Hamilton product), q + r, q - r, -q, q * s, s * q, q / s, q == r.\n"
     "Methods: rotate, conj, inverse, norm, normalized, to_mat3, axis_angle, dot, unpack.\n"
     "Rotations use q normalised; the zero quaternion is refused where a rotation is needed."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void open_quat(lua_State* L, int lib) {
  new_metatable(L, "quat", &quat_metatable_key);
  register_entries(L, -1, metamethods);
  lua_newtable(L);  // methods, the upvalue of __index
  register_entries(L, -1, methods);
  register_entries(L, -2, index_entry, 1);
  lua_pop(L, 1);

  lua_newtable(L);  // the callable `quat` table
  register_entries(L, -1, methods);  // quat.rotate(q, v) works as q:rotate(v)
  register_entries(L, -1, functions);  // after methods: quat.axis_angle(axis, angle) constructs
  lua_newtable(L);
  register_entries(L, -1, constructor);
  lua_pushliteral(L, "quat");
  lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, -2);
  register_topic(L, -1, "quat", constructor[0].doc);
  lua_setfield(L, lib, "quat");
}

}  // namespace rigidlab::lua
