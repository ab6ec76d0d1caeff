// mat3: a 3x3 matrix value (Eigen::Matrix3d in a userdata), immutable like a number: every
// operation returns a new matrix. Built from 9 numbers in row-major order or from a table of
// three rows. Entries are always finite.
#include <Eigen/LU>
#include <cmath>
#include <string>

#include "lua/binding.hpp"
#include "lua/modules.hpp"

namespace rigidlab::lua {
namespace {

// One row of mat3{{..},{..},{..}}: a table of three finite numbers. Raw access: a table's
// metamethods (__len, __index) are not run, so they cannot raise errors of their own here.
void read_row(lua_State* L, int row, Mat3& m) {
  if (lua_rawgeti(L, 1, row + 1) != LUA_TTABLE)
    arg_error(L, 1, "row %d must be a table of 3 numbers, got %s", row + 1, value_type_name(L, -1));
  if (lua_rawlen(L, -1) != 3)
    arg_error(L, 1, "row %d must have 3 numbers, got %d", row + 1, (int)lua_rawlen(L, -1));
  for (int j = 0; j < 3; ++j) {
    if (lua_rawgeti(L, -1, j + 1) != LUA_TNUMBER)
      arg_error(L, 1, "entry (%d, %d) must be a number, got %s", row + 1, j + 1,
                value_type_name(L, -1));
    const double x = lua_tonumber(L, -1);
    if (!std::isfinite(x))
      arg_error(L, 1, "entry (%d, %d) must be finite, got %s", row + 1, j + 1,
                format_number(x).c_str());
    m(row, j) = x;
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
}

// mat3(a11, a12, a13, a21, a22, a23, a31, a32, a33) or mat3{{a11, a12, a13}, {...}, {...}}.
int mat3_call(lua_State* L) {
  lua_remove(L, 1);  // the mat3 table itself
  Mat3 m;
  if (lua_type(L, 1) == LUA_TTABLE) {
    check_no_extra_args(L, 1);
    if (lua_rawlen(L, 1) != 3)
      arg_error(L, 1, "a table of 3 rows expected, got %d rows", (int)lua_rawlen(L, 1));
    for (int i = 0; i < 3; ++i) read_row(L, i, m);
  } else {
    if (lua_gettop(L) <= 1 && lua_type(L, 1) != LUA_TNUMBER)
      type_error(L, 1, "number or table of 3 rows");
    check_no_extra_args(L, 9);
    for (int k = 0; k < 9; ++k) {  // the first missing one is named: "got no value"
      const std::string name = "a" + std::to_string(k / 3 + 1) + std::to_string(k % 3 + 1);
      m(k / 3, k % 3) = check_finite(L, k + 1, name.c_str());
    }
  }
  push_mat3(L, m);
  return 1;
}

int mat3_identity(lua_State* L) {
  check_no_extra_args(L, 0);
  push_mat3(L, Mat3::Identity());
  return 1;
}

int mat3_zero(lua_State* L) {
  check_no_extra_args(L, 0);
  push_mat3(L, Mat3::Zero());
  return 1;
}

// mat3.diag(a, b, c) or mat3.diag(v)
int mat3_diag(lua_State* L) {
  Vec3 d;
  if (const Vec3* v = test_vec3(L, 1)) {
    check_no_extra_args(L, 1);
    d = *v;
  } else {
    check_no_extra_args(L, 3);
    static const char* const names[] = {"a", "b", "c"};
    for (int i = 0; i < 3; ++i) d[i] = check_finite(L, i + 1, names[i]);  // in order
  }
  push_mat3(L, d.asDiagonal());
  return 1;
}

int mat3_skew(lua_State* L) {
  const Vec3& v = check_vec3(L, 1);
  check_no_extra_args(L, 1);
  push_mat3(L, skew(v));
  return 1;
}

// A row or column number, 1 to 3 (2.0 counts as 2, as everywhere); 0-based.
int check_index(lua_State* L, int arg, const char* what) {
  return static_cast<int>(check_integer(L, arg, Where::argument(arg, what), 1, 3)) - 1;
}

int mat3_get(lua_State* L) {
  const Mat3& m = check_mat3(L, 1);
  const int i = check_index(L, 2, "row");
  const int j = check_index(L, 3, "column");
  check_no_extra_args(L, 3);
  lua_pushnumber(L, m(i, j));
  return 1;
}

int mat3_row(lua_State* L) {
  const Mat3& m = check_mat3(L, 1);
  const int i = check_index(L, 2, "row");
  check_no_extra_args(L, 2);
  push_vec3(L, m.row(i).transpose());
  return 1;
}

int mat3_col(lua_State* L) {
  const Mat3& m = check_mat3(L, 1);
  const int j = check_index(L, 2, "column");
  check_no_extra_args(L, 2);
  push_vec3(L, m.col(j));
  return 1;
}

int mat3_transpose(lua_State* L) {
  const Mat3& m = check_mat3(L, 1);
  check_no_extra_args(L, 1);
  push_mat3(L, m.transpose());
  return 1;
}

// The power of two that moves a row's or column's largest entry halfway towards [1, 2) in
// log scale, or 0 when it is there (or the row is zero).
int half_shift(double largest) {
  if (!(largest > 0.0)) return 0;
  int e = 0;
  std::frexp(largest, &e);
  const int d = e - 1;  // floor(log2(largest))
  return d == 0 ? 0 : -(d + (d > 0 ? 1 : -1)) / 2;
}

// Ruiz's equilibration: A = D_r M D_c with D_r = diag(2^row_exp), D_c = diag(2^col_exp),
// found by scaling each row, then each column, by about 1/sqrt of its largest entry until all
// lie in [1, 2). It balances rows and columns of any scales; powers of two scale exactly.
Mat3 equilibrate(const Mat3& m, int row_exp[3], int col_exp[3]) {
  Mat3 a = m;
  for (int sweep = 0; sweep < 64; ++sweep) {  // the imbalance halves every sweep
    bool moved = false;
    for (int i = 0; i < 3; ++i) {
      const int shift = half_shift(a.row(i).cwiseAbs().maxCoeff());
      for (int j = 0; j < 3; ++j) a(i, j) = std::ldexp(a(i, j), shift);
      row_exp[i] += shift;
      moved = moved || shift != 0;
    }
    for (int j = 0; j < 3; ++j) {
      const int shift = half_shift(a.col(j).cwiseAbs().maxCoeff());
      for (int i = 0; i < 3; ++i) a(i, j) = std::ldexp(a(i, j), shift);
      col_exp[j] += shift;
      moved = moved || shift != 0;
    }
    if (!moved) break;
  }
  return a;
}

int mat3_inverse(lua_State* L) {
  const Mat3& m = check_mat3(L, 1);
  check_no_extra_args(L, 1);
  // Invertibility is decided on the equilibrated matrix (see equilibrate), not on M: full-pivot
  // LU's rank threshold is relative to the largest pivot, which one huge entry would set, so
  // diag(1e308, 1, 1) would be "rank 1". M⁻¹ = D_c A⁻¹ D_r.
  int row_exp[3] = {0, 0, 0}, col_exp[3] = {0, 0, 0};
  const Mat3 scaled = equilibrate(m, row_exp, col_exp);
  const Eigen::FullPivLU<Mat3> lu(scaled);
  if (!lu.isInvertible())
    arg_error(L, 1, "matrix is singular (rank %d, det = %s)", (int)lu.rank(),
              format_number(m.determinant()).c_str());
  Mat3 inverse = lu.inverse();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      inverse(i, j) = std::ldexp(inverse(i, j), col_exp[i] + row_exp[j]);
  if (!is_finite(inverse)) overflow_error(L, 1, "the inverse", "an entry");
  push_mat3(L, inverse);
  return 1;
}

int mat3_det(lua_State* L) {
  const Mat3& m = check_mat3(L, 1);
  check_no_extra_args(L, 1);
  lua_pushnumber(L, m.determinant());
  return 1;
}

int mat3_trace(lua_State* L) {
  const Mat3& m = check_mat3(L, 1);
  check_no_extra_args(L, 1);
  lua_pushnumber(L, m.trace());
  return 1;
}

// values (ascending, vec3), axes (mat3, columns = unit eigenvectors, det +1). Only for
// symmetric matrices: a non-symmetric one is refused rather than silently symmetrised.
int mat3_eigen(lua_State* L) {
  const Mat3& m = check_mat3(L, 1);
  check_no_extra_args(L, 1);
  const double scale = m.cwiseAbs().maxCoeff();
  if (asymmetry(m) > 1e-12 * scale)
    arg_error(L, 1, "matrix must be symmetric (largest |a_ij - a_ji| = %s)",
              format_number(asymmetry(m)).c_str());
  const SymmetricEigen e = symmetric_eigen(symmetric_part(m));
  // The eigenvalues of a finite matrix can exceed the largest double (by up to a factor 3).
  if (!is_finite(e.values) || !is_finite(e.axes))
    arg_error(L, 1, "the eigenvalues are not finite (the largest overflows the largest double, "
                    "1.8e308)");
  push_vec3(L, e.values);
  push_mat3(L, e.axes);
  return 2;
}

int mat3_unpack(lua_State* L) {
  const Mat3& m = check_mat3(L, 1);
  check_no_extra_args(L, 1);
  for (int k = 0; k < 9; ++k) lua_pushnumber(L, m(k / 3, k % 3));
  return 9;
}

void check_two_mat3(lua_State* L, const Mat3*& a, const Mat3*& b) {
  a = test_mat3(L, 1);
  b = test_mat3(L, 2);
  if (a == nullptr) type_error(L, 1, "mat3");
  if (b == nullptr) type_error(L, 2, "mat3");
}

int mat3_add(lua_State* L) {
  const Mat3 *a, *b;
  check_two_mat3(L, a, b);
  push_finite(L, Mat3(*a + *b), 2);
  return 1;
}

int mat3_sub(lua_State* L) {
  const Mat3 *a, *b;
  check_two_mat3(L, a, b);
  push_finite(L, Mat3(*a - *b), 2);
  return 1;
}

int mat3_unm(lua_State* L) {
  push_mat3(L, -check_mat3(L, 1));
  return 1;
}

// M * v, M * N, M * s, s * M. A vec3 on the left is refused: vectors are columns.
int mat3_mul(lua_State* L) {
  const Mat3* a = test_mat3(L, 1);
  if (a == nullptr) {  // s * M, or v * M
    if (test_vec3(L, 1) != nullptr)
      arg_error(L, 1, "vec3 * mat3 is not defined (vectors are columns): use M * v or "
                      "M:transpose() * v");
    if (lua_type(L, 1) != LUA_TNUMBER) type_error(L, 1, "number");
    push_finite(L, Mat3(lua_tonumber(L, 1) * check_mat3(L, 2)), 1);
  } else if (const Vec3* v = test_vec3(L, 2)) {
    push_finite(L, Vec3(*a * *v), 2);
  } else if (const Mat3* b = test_mat3(L, 2)) {
    push_finite(L, Mat3(*a * *b), 2);
  } else if (lua_type(L, 2) == LUA_TNUMBER) {
    push_finite(L, Mat3(*a * lua_tonumber(L, 2)), 2);
  } else {
    type_error(L, 2, "vec3, mat3 or number");
  }
  return 1;
}

int mat3_div(lua_State* L) {
  const Mat3& m = check_mat3(L, 1);
  const double s = check_finite(L, 2, "divisor");
  if (s == 0.0) arg_error(L, 2, "division of a mat3 by zero");
  push_finite(L, Mat3(m / s), 2);
  return 1;
}

int mat3_eq(lua_State* L) {
  const Mat3* a = test_mat3(L, 1);
  const Mat3* b = test_mat3(L, 2);
  lua_pushboolean(L, a != nullptr && b != nullptr && *a == *b);
  return 1;
}

// Rows in the vec3 style: ((1, 0, 0), (0, 1, 0), (0, 0, 1)).
int mat3_tostring(lua_State* L) {
  const Mat3& m = check_mat3(L, 1);
  std::string text = "(";
  for (int i = 0; i < 3; ++i) {
    text += i == 0 ? "(" : ", (";
    for (int j = 0; j < 3; ++j) text += (j == 0 ? "" : ", ") + format_number(m(i, j));
    text += ")";
  }
  text += ")";
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

int mat3_concat(lua_State* L) {
  luaL_tolstring(L, 1, nullptr);
  luaL_tolstring(L, 2, nullptr);
  lua_concat(L, 2);
  return 1;
}

int mat3_index(lua_State* L) {
  check_mat3(L, 1);
  lua_pushvalue(L, 2);
  if (lua_type(L, 2) == LUA_TSTRING && lua_rawget(L, lua_upvalueindex(1)) != LUA_TNIL) return 1;
  field_error(L, "mat3", push_key_name(L, 2),
              "no such field: use M:get(i, j), M:row(i), M:col(j); see help(\"mat3\")");
}

int mat3_newindex(lua_State* L) {
  check_mat3(L, 1);
  immutable_error(L, "mat3", 2, "M = mat3(a11, a12, ..., a33) or mat3{{...}, {...}, {...}}");
}

const Entry methods[] = {
    {"get", mat3_get, "mat3:get", "M:get(i, j) -> number", "Entry in row i, column j (1-based)."},
    {"row", mat3_row, "mat3:row", "M:row(i) -> vec3", "Row i as a vec3."},
    {"col", mat3_col, "mat3:col", "M:col(j) -> vec3", "Column j as a vec3."},
    {"transpose", mat3_transpose, "mat3:transpose", "M:transpose() -> mat3", "Mᵀ."},
    {"inverse", mat3_inverse, "mat3:inverse", "M:inverse() -> mat3",
     "M⁻¹. Error if M is singular: decided by full-pivot LU on M with its rows and columns\n"
     "balanced by powers of two, so a matrix is not singular for its scale alone."},
    {"det", mat3_det, "mat3:det", "M:det() -> number", "Determinant."},
    {"trace", mat3_trace, "mat3:trace", "M:trace() -> number", "Sum of the diagonal."},
    {"eigen", mat3_eigen, "mat3:eigen", "M:eigen() -> values, axes",
     "For a symmetric M: eigenvalues ascending (vec3) and a mat3 whose columns are the matching\n"
     "unit eigenvectors, right-handed (det = +1): M * axes == axes * mat3.diag(values).\n"
     "Each axis has its largest component positive (the third may flip to keep det = +1)."},
    {"unpack", mat3_unpack, "mat3:unpack", "M:unpack() -> a11, a12, ..., a33",
     "The nine entries in row-major order."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry functions[] = {
    {"identity", mat3_identity, "mat3.identity", "mat3.identity() -> mat3", "The identity E."},
    {"zero", mat3_zero, "mat3.zero", "mat3.zero() -> mat3", "The zero matrix."},
    {"diag", mat3_diag, "mat3.diag", "mat3.diag(a, b, c) or mat3.diag(v) -> mat3",
     "Diagonal matrix with a, b, c (or v.x, v.y, v.z) on the diagonal."},
    {"skew", mat3_skew, "mat3.skew", "mat3.skew(v) -> mat3",
     "The hat operator v̂: mat3.skew(v) * w == v:cross(w)."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry metamethods[] = {
    {"__add", mat3_add, "mat3.__add", "M + N", "Sum."},
    {"__sub", mat3_sub, "mat3.__sub", "M - N", "Difference."},
    {"__unm", mat3_unm, "mat3.__unm", "-M", "Negation."},
    {"__mul", mat3_mul, "mat3.__mul", "M * v, M * N, M * s, s * M", "Products."},
    {"__div", mat3_div, "mat3.__div", "M / s", "Division by a non-zero number."},
    {"__eq", mat3_eq, "mat3.__eq", "M == N", "Exact equality of all entries."},
    {"__tostring", mat3_tostring, "mat3.__tostring", "tostring(M)", "Rows: ((a11, a12, a13), ...)."},
    {"__concat", mat3_concat, "mat3.__concat", "s .. M", "Concatenation as tostring."},
    {"__newindex", mat3_newindex, "mat3.__newindex", "", "Matrices are immutable."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry index_entry[] = {
    {"__index", mat3_index, "mat3.__index", "M:method()", "Methods."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry constructor[] = {
    {"__call", mat3_call, "mat3",
     "mat3(a11, a12, a13, a21, a22, a23, a31, a32, a33) or mat3{{a11, a12, a13}, {...}, {...}}",
     "A 3x3 matrix, row-major. Immutable: operations return new matrices.\n"
     "Functions: mat3.identity(), mat3.zero(), mat3.diag(a, b, c), mat3.skew(v).\n"
     "Operators: M * v, M * N, M * s, s * M, M / s, M + N, M - N, -M, M == N (exact).\n"
     "Methods: get, row, col, transpose, inverse, det, trace, eigen, unpack."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void open_mat3(lua_State* L, int lib) {
  new_metatable(L, "mat3", &mat3_metatable_key);
  register_entries(L, -1, metamethods);
  lua_newtable(L);  // methods, the upvalue of __index
  register_entries(L, -1, methods);
  register_entries(L, -2, index_entry, 1);
  lua_pop(L, 1);

  lua_newtable(L);  // the callable `mat3` table
  register_entries(L, -1, functions);
  register_entries(L, -1, methods);  // mat3.transpose(M) works as M:transpose()
  lua_newtable(L);
  register_entries(L, -1, constructor);
  lua_pushliteral(L, "mat3");
  lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, -2);
  register_topic(L, -1, "mat3", constructor[0].doc);
  lua_setfield(L, lib, "mat3");
}

}  // namespace rigidlab::lua
