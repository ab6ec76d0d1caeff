// inertia: the inertia-tensor calculator. Closed forms of the primitive shapes, particles,
// the parallel axis theorem, rotation, principal axes, composite bodies and closed triangle
// meshes (engine/inertia.hpp, engine/mesh_inertia.hpp), plus inertia.check, the validator.
// Every argument is checked here so that errors name the argument; tensors given by the user
// must be physically possible (symmetric, principal moments >= 0, A + B >= C).
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "engine/inertia.hpp"
#include "engine/mesh_inertia.hpp"
#include "lua/binding.hpp"
#include "lua/modules.hpp"

namespace rigidlab::lua {
namespace {

// Results are pushed only when finite: huge inputs can overflow. The overflow is blamed on
// argument `arg`, the one that made the result too large (a shape's size: see largest_arg).
void push_result(lua_State* L, const Mat3& m, int arg) { push_finite(L, m, arg); }
void push_result(lua_State* L, const Vec3& v, int arg) { push_finite(L, v, arg); }
void push_result(lua_State* L, double x, int arg) {
  if (!std::isfinite(x)) overflow_error(L, arg, "the result", "it");
  lua_pushnumber(L, x);
}

// Of the numbers at first..last (already checked), the argument of the largest: the size that
// makes a tensor m (a² + b²)/k overflow.
int largest_arg(lua_State* L, int first, int last) {
  int largest = first;
  for (int arg = first + 1; arg <= last; ++arg)
    if (lua_tonumber(L, arg) > lua_tonumber(L, largest)) largest = arg;
  return largest;
}

// The results of inertia.points and inertia.composite; an overflow blames the list.
void push_mass_properties(lua_State* L, const MassProperties& p) {
  push_result(L, p.mass, 1);
  push_result(L, p.com, 1);
  push_result(L, p.inertia, 1);
}

// A user-supplied inertia tensor: a mat3 that a real body (or an idealised particle or rod)
// could have.
const Mat3& check_tensor(lua_State* L, int arg) {
  const Mat3& I = check_mat3(L, arg);
  const std::string problem = inertia_tensor_problem(I, InertiaRules::idealized);
  if (!problem.empty()) arg_error(L, arg, "not a physical inertia tensor: %s", problem.c_str());
  return I;
}

// ---- shapes --------------------------------------------------------------------------------

template <Mat3 (*shape)(double, double)>
int mass_radius(lua_State* L) {
  check_no_extra_args(L, 2);
  const double m = check_positive(L, 1, "mass");
  const double r = check_positive(L, 2, "radius");
  push_result(L, protect(L, [&] { return shape(m, r); }), 2);
  return 1;
}

// Cylinder-like shapes: (m, r, h). The capsule's h (between the cap centres) may be 0.
template <Mat3 (*shape)(double, double, double), bool zero_height_allowed>
int mass_radius_height(lua_State* L) {
  check_no_extra_args(L, 3);
  const double m = check_positive(L, 1, "mass");
  const double r = check_positive(L, 2, "radius");
  const double h = zero_height_allowed ? check_nonnegative(L, 3, "height")
                                       : check_positive(L, 3, "height");
  push_result(L, protect(L, [&] { return shape(m, r, h); }), largest_arg(L, 2, 3));
  return 1;
}

// solid_box(m, w, h, d) or solid_box(m, vec3(w, h, d)).
int solid_box(lua_State* L) {
  const double m = check_positive(L, 1, "mass");
  Vec3 size;
  int size_arg = 2;  // blamed for an overflow
  if (const Vec3* v = test_vec3(L, 2)) {
    check_no_extra_args(L, 2);
    size = *v;
    static const char* const names[] = {"width (size.x)", "height (size.y)", "depth (size.z)"};
    for (int i = 0; i < 3; ++i)
      if (!(size[i] > 0.0))
        arg_error(L, 2, "%s must be > 0, got %s", names[i], format_number(size[i]).c_str());
  } else {
    check_no_extra_args(L, 4);
    size = Vec3(check_positive(L, 2, "width"), check_positive(L, 3, "height"),
                check_positive(L, 4, "depth"));
    size_arg = largest_arg(L, 2, 4);
  }
  push_result(L, protect(L, [&] { return inertia_solid_box(m, size); }), size_arg);
  return 1;
}

int solid_ellipsoid(lua_State* L) {
  check_no_extra_args(L, 4);
  const double m = check_positive(L, 1, "mass");
  const double a = check_positive(L, 2, "semi-axis a");
  const double b = check_positive(L, 3, "semi-axis b");
  const double c = check_positive(L, 4, "semi-axis c");
  push_result(L, protect(L, [&] { return inertia_solid_ellipsoid(m, a, b, c); }),
              largest_arg(L, 2, 4));
  return 1;
}

// ---- list arguments ------------------------------------------------------------------------

// The length n >= 1 of the list at `arg`; refuses non-tables, empty lists and keys other than
// 1..n (a list with holes or named fields is a mistake).
int check_list(lua_State* L, int arg, const char* expected) {
  const lua_Integer n = check_sequence(L, arg, expected, expected);
  if (n == 0) arg_error(L, arg, "%s: the list is empty", expected);
  if (n > 100000000) arg_error(L, arg, "the list is too long (%I entries)", n);
  return static_cast<int>(n);
}

// Entry `entry` of the list at `arg`, a table with only the `allowed` fields, pushed.
void push_entry_table(lua_State* L, int arg, int entry, const char* const* allowed,
                      const char* shape) {
  if (lua_rawgeti(L, arg, entry) != LUA_TTABLE)
    arg_error(L, arg, "entry %d must be a table %s, got %s", entry, shape, value_type_name(L, -1));
  const int table = lua_gettop(L);
  check_fields(L, table, allowed, Where::argument(arg, lua_pushfstring(L, "entry %d:", entry)));
  lua_pop(L, 1);
}

// Field 'mass' of the entry table on top of the stack: a finite number > 0.
double entry_mass(lua_State* L, int arg, int entry) {
  const int type = lua_getfield(L, -1, "mass");
  if (type == LUA_TNIL) arg_error(L, arg, "entry %d: field 'mass' is required", entry);
  if (type != LUA_TNUMBER)
    arg_error(L, arg, "entry %d: field 'mass' must be a number, got %s", entry,
              value_type_name(L, -1));
  const double m = lua_tonumber(L, -1);
  lua_pop(L, 1);
  if (!std::isfinite(m) || !(m > 0.0))
    arg_error(L, arg, "entry %d: field 'mass' must be %s, got %s", entry,
              std::isfinite(m) ? "> 0" : "finite", format_number(m).c_str());
  return m;
}

// Field `name` of the entry table on top of the stack: a value of a math type (vec3, mat3).
template <class T, T* (*test)(lua_State*, int)>
T entry_value(lua_State* L, int arg, int entry, const char* name, const char* type_name) {
  lua_getfield(L, -1, name);
  const T* value = test(L, -1);
  if (value == nullptr) {
    if (lua_isnil(L, -1)) arg_error(L, arg, "entry %d: field '%s' is required", entry, name);
    const char* got = value_type_name(L, -1);
    arg_error(L, arg, "entry %d: field '%s' must be a %s, got %s", entry, name, type_name, got);
  }
  const T result = *value;
  if (!is_finite(result))  // the engine would refuse it without naming the entry
    arg_error(L, arg, "entry %d: field '%s' must be finite, got %s", entry, name,
              push_shown_value(L, -1));
  lua_pop(L, 1);
  return result;
}

// inertia.points{{mass = m, pos = vec3}, ...}
int points(lua_State* L) {
  check_no_extra_args(L, 1);
  const int n = check_list(L, 1, "list of {mass =, pos =}");
  static const char* const fields[] = {"mass", "pos", nullptr};
  std::vector<PointMass> list;
  list.reserve(n);
  for (int i = 1; i <= n; ++i) {
    push_entry_table(L, 1, i, fields, "{mass =, pos =}");
    const double m = entry_mass(L, 1, i);
    list.push_back({m, entry_value<Vec3, test_vec3>(L, 1, i, "pos", "vec3")});
    lua_pop(L, 1);
  }
  push_mass_properties(L, protect(L, [&] { return inertia_points(list); }));
  return 3;
}

// inertia.composite{{mass = m, com = vec3, inertia = mat3}, ...}
int composite(lua_State* L) {
  check_no_extra_args(L, 1);
  const int n = check_list(L, 1, "list of {mass =, com =, inertia =}");
  static const char* const fields[] = {"mass", "com", "inertia", nullptr};
  std::vector<MassProperties> parts;
  parts.reserve(n);
  for (int i = 1; i <= n; ++i) {
    push_entry_table(L, 1, i, fields, "{mass =, com =, inertia =}");
    MassProperties part;
    part.mass = entry_mass(L, 1, i);
    part.com = entry_value<Vec3, test_vec3>(L, 1, i, "com", "vec3");
    part.inertia = entry_value<Mat3, test_mat3>(L, 1, i, "inertia", "mat3");
    const std::string problem = inertia_tensor_problem(part.inertia, InertiaRules::idealized);
    if (!problem.empty())
      arg_error(L, 1, "entry %d: field 'inertia' is not a physical inertia tensor: %s", i,
                problem.c_str());
    parts.push_back(part);
    lua_pop(L, 1);
  }
  push_mass_properties(L, protect(L, [&] { return composite_inertia(parts); }));
  return 3;
}

// ---- tensor algebra ------------------------------------------------------------------------

int point(lua_State* L) {
  check_no_extra_args(L, 2);
  const double m = check_positive(L, 1, "mass");
  const Vec3& r = check_vec3(L, 2);
  push_result(L, protect(L, [&] { return inertia_point(m, r); }), 2);
  return 1;
}

int parallel_axis(lua_State* L) {
  check_no_extra_args(L, 3);
  const Mat3& I = check_tensor(L, 1);
  const double m = check_positive(L, 2, "mass");
  const Vec3& d = check_vec3(L, 3);
  push_result(L, rigidlab::parallel_axis(I, m, d), 3);
  return 1;
}

int rotate(lua_State* L) {
  check_no_extra_args(L, 2);
  const Mat3& I = check_tensor(L, 1);
  if (const Quat* q = test_quat(L, 2)) {
    if (is_zero(*q)) arg_error(L, 2, "the rotation quaternion must be non-zero");
    push_result(L, protect(L, [&] { return rotate_inertia(I, *q); }), 1);
    return 1;
  }
  const Mat3* R = test_mat3(L, 2);
  if (R == nullptr) type_error(L, 2, "mat3 or quat");
  const std::string problem = rotation_problem(*R);
  if (!problem.empty()) arg_error(L, 2, "R must be a rotation: %s", problem.c_str());
  push_result(L, rotate_inertia(I, *R), 1);
  return 1;
}

int about_axis(lua_State* L) {
  check_no_extra_args(L, 2);
  const Mat3& I = check_tensor(L, 1);
  const Vec3& n = check_vec3(L, 2);
  if (!is_finite(n))
    arg_error(L, 2, "the axis must be finite, got %s", luaL_tolstring(L, 2, nullptr));
  if (is_zero(n)) arg_error(L, 2, "the axis must be a non-zero vector");
  push_result(L, protect(L, [&] { return rigidlab::about_axis(I, n); }), 1);
  return 1;
}

int principal(lua_State* L) {
  check_no_extra_args(L, 1);
  const SymmetricEigen e = principal_inertia(check_tensor(L, 1));
  push_result(L, e.values, 1);
  push_result(L, e.axes, 1);
  return 2;
}

int check(lua_State* L) {
  check_no_extra_args(L, 1);
  const std::string problem = inertia_tensor_problem(check_mat3(L, 1), InertiaRules::body);
  lua_pushboolean(L, problem.empty());
  if (problem.empty()) return 1;
  lua_pushstring(L, problem.c_str());
  return 2;
}

// ---- meshes --------------------------------------------------------------------------------

std::vector<Vec3> check_vertices(lua_State* L, int arg) {
  const int n = check_list(L, arg, "list of vec3");
  std::vector<Vec3> vertices(n);
  for (int i = 1; i <= n; ++i) {
    lua_rawgeti(L, arg, i);
    const Vec3* v = test_vec3(L, -1);
    if (v == nullptr) {
      const char* got = value_type_name(L, -1);
      arg_error(L, arg, "entry %d must be a vec3, got %s", i, got);
    }
    vertices[i - 1] = *v;
    lua_pop(L, 1);
  }
  if (n < 4) arg_error(L, arg, "a closed mesh needs at least 4 vertices, got %d", n);
  return vertices;
}

// Triangles {i, j, k} with 1-based vertex indices, converted to 0-based.
std::vector<MeshTriangle> check_triangles(lua_State* L, int arg, int vertex_count) {
  const int n = check_list(L, arg, "list of {i, j, k}");
  std::vector<MeshTriangle> triangles(n);
  for (int t = 1; t <= n; ++t) {
    const bool is_table = lua_rawgeti(L, arg, t) == LUA_TTABLE;
    int keys = 0;
    if (is_table)
      for (lua_pushnil(L); lua_next(L, -2) != 0; lua_pop(L, 1)) ++keys;
    if (!is_table || keys != 3 || lua_rawlen(L, -1) != 3)
      arg_error(L, arg, "entry %d must be a table of 3 vertex indices {i, j, k}, got %s", t,
                is_table ? "a table of another shape" : value_type_name(L, -1));
    for (int k = 0; k < 3; ++k) {
      lua_Integer index = 0;
      lua_rawgeti(L, -1, k + 1);
      if (!to_integer(L, -1, index))  // 2.0 counts as 2, as everywhere
        arg_error(L, arg, "entry %d: vertex index %d must be an integer, got %s", t, k + 1,
                  lua_type(L, -1) == LUA_TNUMBER ? push_shown_value(L, -1)
                                                 : value_type_name(L, -1));
      if (index < 1 || index > vertex_count)
        arg_error(L, arg, "entry %d: vertex index %I is out of range (the vertices are 1 to %d)",
                  t, index, vertex_count);
      triangles[t - 1][k] = static_cast<int>(index - 1);
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  return triangles;
}

int mesh(lua_State* L) {
  check_no_extra_args(L, 3);
  const std::vector<Vec3> vertices = check_vertices(L, 1);
  const std::vector<MeshTriangle> triangles =
      check_triangles(L, 2, static_cast<int>(vertices.size()));
  const double density = lua_isnoneornil(L, 3) ? 1.0 : check_positive(L, 3, "density");
  const std::string problem = mesh_problem(vertices, triangles);
  if (!problem.empty()) arg_error(L, 2, "%s", problem.c_str());
  const MeshMassProperties p =
      protect(L, [&] { return inertia_mesh(vertices, triangles, density); });
  push_result(L, p.mass, 1);
  push_result(L, p.com, 1);
  push_result(L, p.inertia, 1);
  push_result(L, p.volume, 1);
  return 4;
}

// ---- registration --------------------------------------------------------------------------

const char* const module_doc =
    "Inertia tensors (kg·m², SI units). Unless stated, a result is the 3x3 tensor (mat3) about\n"
    "the centre of mass, in the body's own frame, with the principal axes along x, y, z:\n"
    "I = ∫((r·r)E − r⊗r) dm, so Ixx = ∫(y² + z²) dm and Ixy = −∫xy dm.\n"
    "Masses and lengths must be finite and > 0. Tensors you pass in must be physically\n"
    "possible: symmetric, principal moments >= 0, and A + B >= C for any ordering of them.\n"
    "inertia.check(I) tells whether a tensor can belong to a body, and why not.";

const Entry functions[] = {
    {"solid_sphere", mass_radius<inertia_solid_sphere>, "inertia.solid_sphere",
     "inertia.solid_sphere(m, r) -> mat3", "Solid ball of radius r: (2/5) m r² on the diagonal."},
    {"hollow_sphere", mass_radius<inertia_hollow_sphere>, "inertia.hollow_sphere",
     "inertia.hollow_sphere(m, r) -> mat3",
     "Thin spherical shell of radius r (all mass on the surface): (2/3) m r² on the diagonal."},
    {"solid_box", solid_box, "inertia.solid_box",
     "inertia.solid_box(m, w, h, d) -> mat3   or   inertia.solid_box(m, vec3(w, h, d))",
     "Solid box with edges w along x, h along y, d along z, centred on its COM:\n"
     "Ixx = m(h² + d²)/12, Iyy = m(w² + d²)/12, Izz = m(w² + h²)/12."},
    {"solid_cylinder", mass_radius_height<inertia_solid_cylinder, false>,
     "inertia.solid_cylinder", "inertia.solid_cylinder(m, r, h) -> mat3",
     "Solid cylinder of radius r and length h, axis z, about its centre:\n"
     "Ixx = Iyy = m(3r² + h²)/12, Izz = m r²/2."},
    {"hollow_cylinder", mass_radius_height<inertia_hollow_cylinder, false>,
     "inertia.hollow_cylinder", "inertia.hollow_cylinder(m, r, h) -> mat3",
     "Thin-walled tube of radius r and length h, axis z, open ends (the wall only, no end\n"
     "caps): Ixx = Iyy = m(6r² + h²)/12, Izz = m r²."},
    {"solid_ellipsoid", solid_ellipsoid, "inertia.solid_ellipsoid",
     "inertia.solid_ellipsoid(m, a, b, c) -> mat3",
     "Solid ellipsoid with semi-axes a, b, c along x, y, z:\n"
     "Ixx = m(b² + c²)/5, Iyy = m(a² + c²)/5, Izz = m(a² + b²)/5."},
    {"capsule", mass_radius_height<inertia_capsule, true>, "inertia.capsule",
     "inertia.capsule(m, r, h) -> mat3",
     "Capsule along z: a solid cylinder of radius r and length h (h excludes the caps; the\n"
     "total length is h + 2r; h = 0 gives a sphere) closed by two solid hemispheres of radius\n"
     "r. Uniform density, so the mass splits between cylinder and caps by volume; each cap's\n"
     "COM is 3r/8 from its flat face. About the capsule's centre."},
    {"solid_cone", mass_radius_height<inertia_solid_cone, false>, "inertia.solid_cone",
     "inertia.solid_cone(m, r, h) -> mat3",
     "Solid cone, base radius r, height h, axis z, apex toward +z, about its COM, which is on\n"
     "the axis h/4 above the base (base at z = −h/4, apex at z = 3h/4):\n"
     "Ixx = Iyy = (3/80) m (4r² + h²), Izz = (3/10) m r²."},
    {"point", point, "inertia.point", "inertia.point(m, r) -> mat3",
     "Tensor of one particle of mass m at offset r (vec3) from the reference point:\n"
     "m((r·r)E − r⊗r)."},
    {"points", points, "inertia.points",
     "inertia.points{{mass = m, pos = vec3}, ...} -> mass, com, I_com",
     "Total mass, centre of mass and tensor about the centre of mass of rigidly connected\n"
     "particles. A single particle or particles on a line give a singular tensor."},
    {"parallel_axis", parallel_axis, "inertia.parallel_axis",
     "inertia.parallel_axis(I_com, m, d) -> mat3",
     "The tensor about a point P given the tensor about the COM, the mass and d = COM − P:\n"
     "I_com + m((d·d)E − d⊗d)."},
    {"rotate", rotate, "inertia.rotate", "inertia.rotate(I, R) -> mat3",
     "The tensor in a rotated frame: R I Rᵀ. R is a mat3 that must be a rotation (RᵀR = E and\n"
     "det R = +1 within 1e-9) or a quat (normalised first)."},
    {"about_axis", about_axis, "inertia.about_axis", "inertia.about_axis(I, n) -> number",
     "The scalar moment of inertia about the axis along n through the tensor's reference\n"
     "point: n·I·n with n normalised (n may have any non-zero length)."},
    {"principal", principal, "inertia.principal", "inertia.principal(I) -> values, axes",
     "Principal moments ascending (vec3) and principal axes as the columns of a rotation\n"
     "(mat3, det = +1): I = axes * mat3.diag(values) * axes:transpose(). As mat3:eigen."},
    {"composite", composite, "inertia.composite",
     "inertia.composite{{mass = m, com = vec3, inertia = mat3}, ...} -> mass, com, I_com",
     "A body made of parts: each part's mass, COM and tensor about its own COM in the axes of\n"
     "the composite frame. Returns the total mass, the composite COM and the tensor about it\n"
     "(each part moved there by the parallel axis theorem, then summed)."},
    {"mesh", mesh, "inertia.mesh",
     "inertia.mesh(vertices, triangles [, density]) -> mass, com, I_com, volume",
     "Solid of uniform density (default 1 kg/m³) bounded by a closed triangle mesh: vertices\n"
     "a list of vec3, triangles a list of {i, j, k} (1-based), counter-clockwise seen from\n"
     "outside. Exact polyhedral integrals (Mirtich 1996, Eberly 2002). Open or non-manifold\n"
     "meshes, inconsistent or inverted winding, degenerate triangles and zero volume are\n"
     "refused with the edge or triangle at fault; the mesh must span 1e-60 to 1e60 m.\n"
     "Several separate closed surfaces are allowed: a surface wound inside-out (counter-\n"
     "clockwise seen from inside) is a cavity and must lie inside another surface; solids\n"
     "that overlap are summed (the overlap counts twice)."},
    {"check", check, "inertia.check", "inertia.check(I) -> true | false, message",
     "Whether I can be the inertia tensor of a rigid body: finite, symmetric, all principal\n"
     "moments > 0, and A + B >= C (planar bodies reach equality). The message names the rule\n"
     "broken and by how much. Particles and infinitely thin rods (a zero moment) are refused:\n"
     "a body needs an invertible tensor."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void open_inertia(lua_State* L, int lib) {
  lua_newtable(L);
  register_entries(L, -1, functions);
  register_topic(L, -1, "inertia", module_doc);
  lua_setfield(L, lib, "inertia");
}

}  // namespace rigidlab::lua
