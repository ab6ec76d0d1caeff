// body: a rigid body. Constructors body{...}, body.sphere{...}, body.box{...}; fields (mass
// properties read-only, state read/write with checks); methods that apply forces and impulses
// and compute the derived quantities of engine/body.hpp. See lua/body.hpp for ownership.
#include "lua/body.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>

#include "engine/inertia.hpp"
#include "lua/binding.hpp"
#include "lua/modules.hpp"

namespace rigidlab::lua {
namespace {

const char body_metatable_key = 0;

using BodyBox = Tagged<BodyHandle>;

const char* shape_name(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::sphere: return "sphere";
    case ShapeKind::box: return "box";
    case ShapeKind::none: break;
  }
  return "none";
}

// ---- constructors ----------------------------------------------------------------------------

// mass and static of a constructor table. Returns true for a static body; `mass` is set for a
// dynamic one. `mass = math.huge` and `static = true` both make a static body.
bool read_mass(lua_State* L, double& mass) {
  bool is_static = false, static_given = false;
  if (get_field(L, 1, "static") != LUA_TNIL) {
    if (!lua_isboolean(L, -1))
      arg_error(L, 1, "field 'static' must be a boolean, got %s", value_type_name(L, -1));
    is_static = lua_toboolean(L, -1);
    static_given = true;
  }
  lua_pop(L, 1);
  const int type = get_field(L, 1, "mass");
  if (type == LUA_TNIL) {
    lua_pop(L, 1);
    if (!is_static) arg_error(L, 1, "field 'mass' is required (or static = true)");
    return true;
  }
  if (type != LUA_TNUMBER)
    arg_error(L, 1, "field 'mass' must be a number, got %s", value_type_name(L, -1));
  mass = lua_tonumber(L, -1);
  lua_pop(L, 1);
  if (mass == std::numeric_limits<double>::infinity()) {
    if (static_given && !is_static)
      arg_error(L, 1, "mass = math.huge makes a static body, but field 'static' is false");
    return true;
  }
  if (std::isnan(mass) || std::isinf(mass))
    arg_error(L, 1, "field 'mass' must be finite or math.huge, got %s", format_number(mass).c_str());
  if (is_static)
    arg_error(L, 1, "field 'mass' must be math.huge or absent for a static body, got %s",
              format_number(mass).c_str());
  const std::string problem = mass_problem(mass);
  if (!problem.empty()) arg_error(L, 1, "field 'mass' %s", problem.c_str());
  return false;
}

Quat field_orientation(lua_State* L) {
  if (get_field(L, 1, "orientation") == LUA_TNIL) {
    lua_pop(L, 1);
    return Quat::Identity();
  }
  const Quat* q = test_quat(L, -1);
  if (q == nullptr) arg_error(L, 1, "field 'orientation' must be a quat, got %s", value_type_name(L, -1));
  if (!is_finite(*q)) arg_error(L, 1, "field 'orientation' must be finite");
  if (is_zero(*q))
    arg_error(L, 1, "field 'orientation' is the zero quaternion, which is not a rotation");
  const Quat rotation = unit(*q);
  lua_pop(L, 1);
  return rotation;
}

// position, orientation, velocity, angular_velocity of a constructor table into b.
void read_state(lua_State* L, Body& b) {
  b.position = field_vec3(L, 1, "position", Vec3::Zero(), false);
  b.orientation = field_orientation(L);
  b.velocity = field_vec3(L, 1, "velocity", Vec3::Zero(), false);
  b.angular_velocity = field_vec3(L, 1, "angular_velocity", Vec3::Zero(), false);
  if (is_static(b) && (b.velocity != Vec3::Zero() || b.angular_velocity != Vec3::Zero()))
    arg_error(L, 1, "a static body cannot move: velocity and angular_velocity must be zero");
}

// Runs an engine constructor, turning its std::invalid_argument into an argument error (the
// fields were checked before, so this is a second line of defence).
template <class Make>
Body make_or_raise(lua_State* L, Make&& make) {
  std::string message;
  try {
    return make();
  } catch (const std::invalid_argument& e) {
    message = e.what();
  }
  arg_error(L, 1, "%s", message.c_str());
}

int body_call(lua_State* L) {
  lua_remove(L, 1);  // the body table itself
  if (!lua_istable(L, 1)) type_error(L, 1, "table");
  check_no_extra_args(L, 1);
  static const char* const fields[] = {"mass", "inertia", "position", "orientation", "velocity",
                                       "angular_velocity", "static", "restitution", "friction",
                                       nullptr};
  check_fields(L, 1, fields);
  double mass = 0.0;
  const bool is_static = read_mass(L, mass);
  Body b;
  if (is_static) {
    if (get_field(L, 1, "inertia") != LUA_TNIL)
      arg_error(L, 1, "field 'inertia' must be absent for a static body (its inertia is infinite)");
    lua_pop(L, 1);
    b = make_static_body();
  } else {
    if (get_field(L, 1, "inertia") == LUA_TNIL) arg_error(L, 1, "field 'inertia' is required");
    const Mat3* inertia = test_mat3(L, -1);
    if (inertia == nullptr)
      arg_error(L, 1, "field 'inertia' must be a mat3, got %s", value_type_name(L, -1));
    const Mat3 tensor = *inertia;
    lua_pop(L, 1);
    const std::string problem = inertia_tensor_problem(tensor);
    if (!problem.empty())
      arg_error(L, 1,
                "field 'inertia' is not a valid inertia tensor (symmetric, positive definite, "
                "A + B >= C): %s",
                problem.c_str());
    b = make_or_raise(L, [&] { return make_body(mass, tensor); });
  }
  read_state(L, b);
  read_material_fields(L, 1, b.restitution, b.friction);
  push_new_body(L, b);
  return 1;
}

// Refuses the tensor of a dynamic body.sphere / body.box, naming the fields, when it overflows
// (a radius of 1e200 m) or is no body's tensor (too small to invert).
void check_shape_inertia(lua_State* L, ShapeKind kind, double mass, double radius,
                         const Vec3& size) {
  const bool sphere = kind == ShapeKind::sphere;
  const Mat3 tensor = sphere ? inertia_solid_sphere(mass, radius) : inertia_solid_box(mass, size);
  const std::string problem = inertia_tensor_problem(tensor);
  if (problem.empty()) return;
  const std::string fields =
      "fields 'mass' (" + format_number(mass) + ") and " +
      (sphere ? "'radius' (" + format_number(radius) + ")"
              : "'size' (" + format_number(size.x()) + ", " + format_number(size.y()) + ", " +
                    format_number(size.z()) + ")");
  const char* formula = sphere ? "(2/5) m r²" : "m (h² + d²)/12, ...";
  if (!is_finite(tensor))
    arg_error(L, 1, "%s are too large: the inertia %s overflows", fields.c_str(), formula);
  arg_error(L, 1, "%s give an inertia %s that no body can have: %s", fields.c_str(), formula,
            problem.c_str());
}

// body.sphere{...} and body.box{...}: the shape's own field, then mass and state.
int shaped_body(lua_State* L, ShapeKind kind) {
  if (!lua_istable(L, 1)) type_error(L, 1, "table");
  check_no_extra_args(L, 1);
  static const char* const sphere_fields[] = {"mass", "radius", "position", "orientation",
                                              "velocity", "angular_velocity", "static",
                                              "restitution", "friction", nullptr};
  static const char* const box_fields[] = {"mass", "size", "position", "orientation",
                                           "velocity", "angular_velocity", "static",
                                           "restitution", "friction", nullptr};
  check_fields(L, 1, kind == ShapeKind::sphere ? sphere_fields : box_fields);
  double radius = 0.0;
  Vec3 size = Vec3::Zero();
  if (kind == ShapeKind::sphere) {
    radius = field_positive(L, 1, "radius", 0.0, true);
  } else {
    size = field_vec3(L, 1, "size", Vec3::Zero(), true);
    if (!(size.minCoeff() > 0.0))
      arg_error(L, 1, "field 'size' must have every component > 0, got (%s, %s, %s)",
                format_number(size.x()).c_str(), format_number(size.y()).c_str(),
                format_number(size.z()).c_str());
  }
  double mass = 0.0;
  Body b;
  if (read_mass(L, mass)) {
    b = make_static_body();
    b.shape.kind = kind;
    b.shape.radius = radius;
    b.shape.half_extents = 0.5 * size;
  } else {
    check_shape_inertia(L, kind, mass, radius, size);
    b = make_or_raise(L, [&] {
      return kind == ShapeKind::sphere ? make_sphere_body(mass, radius) : make_box_body(mass, size);
    });
  }
  read_state(L, b);
  read_material_fields(L, 1, b.restitution, b.friction);
  push_new_body(L, b);
  return 1;
}

int body_sphere(lua_State* L) { return shaped_body(L, ShapeKind::sphere); }
int body_box(lua_State* L) { return shaped_body(L, ShapeKind::box); }

// ---- fields ----------------------------------------------------------------------------------

// Pushes the field `key` of b; false when there is no such field.
bool push_field(lua_State* L, const Body& b, const char* key) {
  const auto is = [key](const char* name) { return std::strcmp(key, name) == 0; };
  if (is("position")) push_vec3(L, b.position);
  else if (is("velocity")) push_vec3(L, b.velocity);
  else if (is("angular_velocity")) push_vec3(L, b.angular_velocity);
  else if (is("orientation")) push_quat(L, b.orientation);
  else if (is("mass")) lua_pushnumber(L, b.mass);
  else if (is("inv_mass")) lua_pushnumber(L, b.inverse_mass);
  else if (is("inertia")) push_mat3(L, b.inertia);
  else if (is("inv_inertia")) push_mat3(L, b.inverse_inertia);
  else if (is("static")) lua_pushboolean(L, is_static(b));
  else if (is("shape")) lua_pushstring(L, shape_name(b.shape.kind));
  else if (is("restitution")) lua_pushnumber(L, b.restitution);
  else if (is("friction")) lua_pushnumber(L, b.friction);
  else if (is("radius")) {
    if (b.shape.kind == ShapeKind::sphere) lua_pushnumber(L, b.shape.radius);
    else lua_pushnil(L);
  } else if (is("size")) {
    if (b.shape.kind == ShapeKind::box) push_vec3(L, 2.0 * b.shape.half_extents);
    else lua_pushnil(L);
  } else {
    return false;
  }
  return true;
}

constexpr const char* field_list =
    "position, orientation, velocity, angular_velocity, restitution, friction (read/write); "
    "mass, inv_mass, inertia, inv_inertia, static, shape, radius, size (read-only)";

int body_index(lua_State* L) {
  const BodyHandle& handle = check_body_handle(L, 1);
  if (lua_type(L, 2) == LUA_TSTRING) {
    if (push_field(L, handle.body(), lua_tostring(L, 2))) return 1;
    lua_pushvalue(L, 2);
    if (lua_rawget(L, lua_upvalueindex(1)) != LUA_TNIL) return 1;
  }
  field_error(L, "body", push_key_name(L, 2), "no such field; the fields are %s, the methods are "
              "in help(\"body\")", field_list);
}

// The quat being assigned to b.orientation, normalised.
Quat new_orientation(lua_State* L) {
  const Quat* q = test_quat(L, 3);
  if (q == nullptr) field_type_error(L, "body", "orientation", "quat", 3);
  if (!is_finite(*q))
    field_error(L, "body", "orientation", "must be finite, got %s", luaL_tolstring(L, 3, nullptr));
  if (is_zero(*q)) field_error(L, "body", "orientation", "the zero quaternion is not a rotation");
  return unit(*q);
}

// b.restitution = e or b.friction = μ, the value at index 3 (engine/plane.hpp's rules).
void set_material(lua_State* L, Body& b, bool restitution) {
  const char* key = restitution ? "restitution" : "friction";
  if (lua_type(L, 3) != LUA_TNUMBER) field_type_error(L, "body", key, "number", 3);
  const double x = lua_tonumber(L, 3);
  const std::string problem = restitution ? material_problem(x, b.friction)
                                          : material_problem(b.restitution, x);
  if (!problem.empty()) {
    // "friction must be finite and >= 0, got -1": the field's name is in the form already.
    const std::size_t length = std::strlen(key);
    const std::size_t skip = problem.compare(0, length, key) == 0 ? length + 1 : 0;
    field_error(L, "body", key, "%s", problem.c_str() + skip);
  }
  (restitution ? b.restitution : b.friction) = x;
}

int body_newindex(lua_State* L) {
  const BodyHandle& handle = check_body_handle(L, 1);
  const char* key = lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : "";
  const auto is = [key](const char* name) { return std::strcmp(key, name) == 0; };
  const bool material = is("restitution") || is("friction");
  const bool state = is("position") || is("orientation") || is("velocity") ||
                     is("angular_velocity") || material;
  if (!state) {
    if (push_field(L, handle.body(), key))
      field_error(L, "body", key, "read-only: mass properties and shape are fixed when the body "
                  "is made");
    field_error(L, "body", push_key_name(L, 2), "no such field; the settable fields are position, "
                "orientation, velocity, angular_velocity, restitution, friction");
  }
  if (handle.store->stepping())
    field_error(L, "body", key, "the world is stepping: it cannot be set until world:step returns; "
                "force callbacks may only apply forces");
  if (is("orientation")) {
    const Quat q = new_orientation(L);
    handle.body().orientation = q;
    return 0;
  }
  if (material) {
    set_material(L, handle.body(), is("restitution"));
    return 0;
  }
  const Vec3 v = check_field_vec3(L, "body", key, 3);
  Body& b = handle.body();
  if (is("position")) {
    b.position = v;
    return 0;
  }
  if (is_static(b) && v != Vec3::Zero())
    field_error(L, "body", key, "a static body's %s must stay zero: it never moves", key);
  (is("velocity") ? b.velocity : b.angular_velocity) = v;
  return 0;
}

int body_tostring(lua_State* L) {
  const Body& b = check_body(L, 1);
  std::string text = "body(";
  if (b.shape.kind != ShapeKind::none) text += std::string(shape_name(b.shape.kind)) + ", ";
  text += is_static(b) ? std::string("static") : "m=" + format_number(b.mass);
  text += ", pos=(" + format_number(b.position.x()) + ", " + format_number(b.position.y()) +
          ", " + format_number(b.position.z()) + "))";
  lua_pushstring(L, text.c_str());
  return 1;
}

int body_gc(lua_State* L) {
  auto* box = static_cast<BodyBox*>(lua_touserdata(L, 1));
  if (box != nullptr && box->tag == body_tag) {
    box->value.~BodyHandle();
    box->tag = 0;  // a resurrected (finalised) body is no longer a body
  }
  return 0;
}

// ---- methods ---------------------------------------------------------------------------------

int body_world_inertia(lua_State* L) {
  const Body& b = check_body(L, 1);
  check_no_extra_args(L, 1);
  push_mat3(L, world_inertia(b));
  return 1;
}

int body_inv_world_inertia(lua_State* L) {
  const Body& b = check_body(L, 1);
  check_no_extra_args(L, 1);
  push_mat3(L, inverse_world_inertia(b));
  return 1;
}

// The optional world point of apply_force/apply_impulse, default the COM.
Vec3 opt_point(lua_State* L, int arg, const Body& b) {
  return lua_isnoneornil(L, arg) ? b.position : check_vec3(L, arg);
}

int body_apply_force(lua_State* L) {
  Body& b = check_body(L, 1);
  const Vec3 f = check_vec3(L, 2);
  const Vec3 point = opt_point(L, 3, b);
  check_no_extra_args(L, 3);
  Body candidate = b;
  apply_force(candidate, f, point);
  if (!is_finite(candidate.force) || !is_finite(candidate.torque))
    arg_error(L, 2, "the accumulated force or torque would overflow");
  b.force = candidate.force;
  b.torque = candidate.torque;
  return 0;
}

int body_apply_torque(lua_State* L) {
  Body& b = check_body(L, 1);
  const Vec3 t = check_vec3(L, 2);
  check_no_extra_args(L, 2);
  if (!is_finite(Vec3(b.torque + t))) arg_error(L, 2, "the accumulated torque would overflow");
  apply_torque(b, t);
  return 0;
}

// Impulses change velocities now; the new velocities must be finite, else the impulse (the
// first argument after self) is blamed.
void commit_velocities(lua_State* L, Body& b, const Body& candidate) {
  if (!is_finite(candidate.velocity) || !is_finite(candidate.angular_velocity))
    arg_error(L, 2, "the impulse would make the velocity non-finite");
  b.velocity = candidate.velocity;
  b.angular_velocity = candidate.angular_velocity;
}

int body_apply_impulse(lua_State* L) {
  BodyHandle& handle = check_body_handle(L, 1);
  const Vec3 j = check_vec3(L, 2);
  const Vec3 point = opt_point(L, 3, handle.body());
  check_no_extra_args(L, 3);
  check_not_stepping(L, 1, handle, "apply an impulse");
  Body candidate = handle.body();
  apply_impulse(candidate, j, point);
  commit_velocities(L, handle.body(), candidate);
  return 0;
}

int body_apply_angular_impulse(lua_State* L) {
  BodyHandle& handle = check_body_handle(L, 1);
  const Vec3 h = check_vec3(L, 2);
  check_no_extra_args(L, 2);
  check_not_stepping(L, 1, handle, "apply an impulse");
  Body candidate = handle.body();
  apply_angular_impulse(candidate, h);
  commit_velocities(L, handle.body(), candidate);
  return 0;
}

// Methods b:f(p) -> vec3 of one vec3 argument.
template <Vec3 (*compute)(const Body&, const Vec3&)>
int point_method(lua_State* L) {
  const Body& b = check_body(L, 1);
  const Vec3& p = check_vec3(L, 2);
  check_no_extra_args(L, 2);
  push_finite(L, compute(b, p), 2);
  return 1;
}

template <Vec3 (*compute)(const Body&)>
int vec3_method(lua_State* L) {
  const Body& b = check_body(L, 1);
  check_no_extra_args(L, 1);
  push_finite(L, compute(b), 1);
  return 1;
}

int body_kinetic_energy(lua_State* L) {
  const Body& b = check_body(L, 1);
  check_no_extra_args(L, 1);
  lua_pushnumber(L, kinetic_energy(b));
  return 1;
}

const Entry methods[] = {
    {"world_inertia", body_world_inertia, "body:world_inertia", "b:world_inertia() -> mat3",
     "The inertia tensor in world axes about the COM, R I Rᵀ (kg m²). Infinite for a static "
     "body."},
    {"inv_world_inertia", body_inv_world_inertia, "body:inv_world_inertia",
     "b:inv_world_inertia() -> mat3",
     "Its inverse, R I⁻¹ Rᵀ (1/(kg m²)); zero for a static body."},
    {"apply_force", body_apply_force, "body:apply_force", "b:apply_force(f [, point])",
     "Adds force f (N, world) at the world point `point` (default the COM), so also the torque\n"
     "(point − position) × f. Accumulated until the next world step, which applies it over\n"
     "the whole step and then clears it. Nothing happens to a static body. Allowed inside\n"
     "force callbacks (w:add_force)."},
    {"apply_torque", body_apply_torque, "body:apply_torque", "b:apply_torque(t)",
     "Adds torque t (N m, world), accumulated like apply_force."},
    {"apply_impulse", body_apply_impulse, "body:apply_impulse", "b:apply_impulse(j [, point])",
     "Changes the velocities now by the impulse j (N s, world) at the world point `point`\n"
     "(default the COM): Δv = j/m, Δω = I_world⁻¹ ((point − position) × j). Does nothing to a\n"
     "static body (infinite mass). Not allowed during world:step."},
    {"apply_angular_impulse", body_apply_angular_impulse, "body:apply_angular_impulse",
     "b:apply_angular_impulse(h)",
     "Changes the angular velocity now by Δω = I_world⁻¹ h (h in N m s, world). Does nothing\n"
     "to a static body."},
    {"point_velocity", point_method<point_velocity>, "body:point_velocity",
     "b:point_velocity(p) -> vec3",
     "Velocity of the material point at world position p: v + ω × (p − position) (m/s)."},
    {"to_world", point_method<to_world>, "body:to_world", "b:to_world(p_local) -> vec3",
     "World coordinates of a point given in body coordinates: position + q p_local."},
    {"to_local", point_method<to_local>, "body:to_local", "b:to_local(p_world) -> vec3",
     "Body coordinates of a world point: q⁻¹ (p_world − position)."},
    {"linear_momentum", vec3_method<linear_momentum>, "body:linear_momentum",
     "b:linear_momentum() -> vec3", "m v (kg m/s); zero for a static body."},
    {"angular_momentum", vec3_method<angular_momentum>, "body:angular_momentum",
     "b:angular_momentum() -> vec3",
     "Angular momentum about the COM in world axes, I_world ω (kg m²/s)."},
    {"kinetic_energy", body_kinetic_energy, "body:kinetic_energy", "b:kinetic_energy() -> number",
     "½ m v·v + ½ ω·I_world ω (J); zero for a static body."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry metamethods[] = {
    {"__newindex", body_newindex, "body.__newindex", "b.position = v",
     "Sets position, orientation (normalised), velocity, angular_velocity, restitution or\n"
     "friction."},
    {"__tostring", body_tostring, "body.__tostring", "tostring(b)",
     "Short form: body(sphere, m=1, pos=(0, 1, 0))."},
    {"__gc", body_gc, "body.__gc", "", "Releases the body's storage."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry index_entry[] = {
    {"__index", body_index, "body.__index", "b.position, b:method()", "Fields and methods."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry constructors[] = {
    {"sphere", body_sphere, "body.sphere",
     "body.sphere{mass =, radius =, position =, orientation =, velocity =, angular_velocity =, "
     "static =, restitution =, friction =} -> body",
     "A solid sphere of uniform density: inertia (2/5) m r² on every axis, collision shape a\n"
     "sphere of that radius. static = true (or mass = math.huge) makes it immovable; mass is\n"
     "then not needed. restitution (default 0) and friction (default 0.6) as for body{}."},
    {"box", body_box, "body.box",
     "body.box{mass =, size = vec3(w, h, d), position =, orientation =, velocity =, "
     "angular_velocity =, static =, restitution =, friction =} -> body",
     "A solid box of uniform density, edges w, h, d along the body's x, y, z: Ixx = m(h²+d²)/12\n"
     "etc.; collision shape the box. static = true makes it immovable. restitution and\n"
     "friction as for body{}."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry call_entry[] = {
    {"__call", body_call, "body",
     "body{mass =, inertia =, position =, orientation =, velocity =, angular_velocity =, "
     "static =, restitution =, friction =} -> body",
     "A rigid body. mass (kg) and inertia (mat3, kg m², body frame about the COM: symmetric,\n"
     "positive definite, principal moments with A + B >= C) are required; position (m, of the\n"
     "COM), orientation (quat, normalised), velocity (m/s) and angular_velocity (rad/s, world)\n"
     "default to zero / identity. mass = math.huge or static = true makes an immovable body\n"
     "(inverse mass and inverse inertia 0; impulses and forces do nothing to it).\n"
     "restitution e in [0, 1] (default 0) and friction μ >= 0 (default 0.6) are the surface\n"
     "material for contacts; a contact uses e = max(ea, eb) and μ = √(μa μb) (Box2D's rule).\n"
     "Shapes: body.sphere{...}, body.box{...}.\n"
     "Fields: position, orientation, velocity, angular_velocity, restitution, friction\n"
     "(read/write); mass, inv_mass, inertia, inv_inertia, static, shape (\"none\", \"sphere\",\n"
     "\"box\"), radius (spheres), size (boxes) (read-only).\n"
     "Methods: world_inertia, inv_world_inertia, apply_force, apply_torque, apply_impulse,\n"
     "apply_angular_impulse, point_velocity, to_world, to_local, linear_momentum,\n"
     "angular_momentum, kinetic_energy."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void read_material_fields(lua_State* L, int arg, double& restitution, double& friction) {
  restitution = field_finite(L, arg, "restitution", default_restitution, false);
  if (!(restitution >= 0.0 && restitution <= 1.0))
    arg_error(L, arg, "field 'restitution' must be in [0, 1], got %s",
              format_number(restitution).c_str());
  friction = field_finite(L, arg, "friction", default_friction, false);
  if (!(friction >= 0.0))
    arg_error(L, arg, "field 'friction' must be >= 0, got %s", format_number(friction).c_str());
}

BodyHandle* test_body(lua_State* L, int index) { return test_tagged<BodyHandle>(L, index, body_tag); }

BodyHandle& check_body_handle(lua_State* L, int arg) {
  BodyHandle* handle = test_body(L, arg);
  if (handle == nullptr) {
    // A body whose __gc has run (used from a finaliser) has its tag cleared but its size and
    // metatable; anything else in a body's metatable (debug.setmetatable) is named by type.
    const auto* box = static_cast<const BodyBox*>(lua_touserdata(L, arg));
    if (box != nullptr && lua_rawlen(L, arg) == sizeof(BodyBox) && box->tag == 0 &&
        has_metatable(L, arg, &body_metatable_key))
      arg_error(L, arg, "the body was garbage-collected (it is used from a finaliser)");
    type_error(L, arg, "body");
  }
  return *handle;
}

BodyHandle& push_new_body(lua_State* L, const Body& b) {
  BodyHandle handle{std::make_shared<BodyStore>(), 0};
  handle.id = handle.store->insert(b);
  void* memory = lua_newuserdatauv(L, sizeof(BodyBox), 0);
  auto* box = new (memory) BodyBox{body_tag, std::move(handle)};
  lua_rawgetp(L, LUA_REGISTRYINDEX, &body_metatable_key);
  lua_setmetatable(L, -2);
  return box->value;
}

void check_not_stepping(lua_State* L, int arg, const BodyHandle& handle, const char* what) {
  if (handle.store->stepping()) stepping_error(L, arg, what);
}

void open_body(lua_State* L, int lib) {
  new_metatable(L, "body", &body_metatable_key);
  register_entries(L, -1, metamethods);
  lua_newtable(L);  // methods, the upvalue of __index
  register_entries(L, -1, methods);
  register_entries(L, -2, index_entry, 1);
  lua_pop(L, 1);

  lua_newtable(L);  // the callable `body` table
  register_entries(L, -1, constructors);
  register_entries(L, -1, methods);  // body.kinetic_energy(b) works as b:kinetic_energy()
  lua_newtable(L);
  register_entries(L, -1, call_entry);
  lua_pushliteral(L, "body");
  lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, -2);
  register_topic(L, -1, "body", call_entry[0].doc);
  lua_setfield(L, lib, "body");
}

}  // namespace rigidlab::lua
