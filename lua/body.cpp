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
#include <type_traits>
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

// ---- properties ------------------------------------------------------------------------------

// Getters copy the value before pushing: the push allocates, which may run a finaliser that
// moves the body's store (w:add of another body).
template <class T, T Body::*member>
void get_member(lua_State* L, int object, const Property&) {
  const T value = check_body(L, object).*member;
  if constexpr (std::is_same_v<T, double>) lua_pushnumber(L, value);
  else if constexpr (std::is_same_v<T, Vec3>) push_vec3(L, value);
  else if constexpr (std::is_same_v<T, Quat>) push_quat(L, value);
  else push_mat3(L, value);
}

void get_static(lua_State* L, int object, const Property&) {
  lua_pushboolean(L, is_static(check_body(L, object)));
}

void get_shape(lua_State* L, int object, const Property&) {
  lua_pushstring(L, shape_name(check_body(L, object).shape.kind));
}

void get_radius(lua_State* L, int object, const Property&) {
  const Shape shape = check_body(L, object).shape;
  if (shape.kind == ShapeKind::sphere) lua_pushnumber(L, shape.radius);
  else lua_pushnil(L);
}

void get_size(lua_State* L, int object, const Property&) {
  const Shape shape = check_body(L, object).shape;
  if (shape.kind == ShapeKind::box) push_vec3(L, 2.0 * shape.half_extents);
  else lua_pushnil(L);
}

// What the user changes on a sleeping body wakes its island (engine/islands.hpp), as Box2D's
// setters do. During a step (a force callback) no body sleeps: the world has a callback.
void wake(const BodyHandle& handle) {
  World* w = handle.store->world();
  if (w != nullptr && !handle.store->stepping() && handle.body().sleeping) w->wake(handle.id);
}

void set_position(lua_State* L, int object, int value, const Where& where, const Property&) {
  const Vec3 p = check_vec3(L, value, where);
  check_body(L, object).position = p;
  wake(check_body_handle(L, object));
}

void get_sleeping(lua_State* L, int object, const Property&) {
  lua_pushboolean(L, check_body(L, object).sleeping);
}


// velocity and angular_velocity: a static body's stay zero.
template <Vec3 Body::*member>
void set_motion(lua_State* L, int object, int value, const Where& where, const Property&) {
  const Vec3 v = check_vec3(L, value, where);
  Body& b = check_body(L, object);
  if (is_static(b) && v != Vec3::Zero())
    where.error(L, "must be zero for a static body (it never moves), got %s",
                push_shown_value(L, value));
  b.*member = v;
  wake(check_body_handle(L, object));
}

void set_orientation(lua_State* L, int object, int value, const Where& where, const Property&) {
  const Quat* q = test_quat(L, value);
  if (q == nullptr) where.type_error(L, value, "quat");
  if (!is_finite(*q)) where.error(L, "must be finite, got %s", push_shown_value(L, value));
  if (is_zero(*q)) where.error(L, "must be a rotation, got the zero quaternion");
  const Quat rotation = unit(*q);
  check_body(L, object).orientation = rotation;
  wake(check_body_handle(L, object));
}

// restitution e in [0, 1] and friction μ >= 0: engine/plane.hpp's material rules, for bodies
// and planes alike.
double check_restitution(lua_State* L, int value, const Where& where) {
  return check_number(L, value, where, 0.0, 1.0, "in [0, 1]");
}

double check_friction(lua_State* L, int value, const Where& where) {
  return check_number(L, value, where, 0.0, HUGE_VAL, "finite and >= 0");
}

void set_restitution(lua_State* L, int object, int value, const Where& where, const Property&) {
  const double e = check_restitution(L, value, where);
  check_body(L, object).restitution = e;
  wake(check_body_handle(L, object));
}

void set_friction(lua_State* L, int object, int value, const Where& where, const Property&) {
  const double mu = check_friction(L, value, where);
  check_body(L, object).friction = mu;
  wake(check_body_handle(L, object));
}

constexpr const char* made_fixed = "mass properties and shape are fixed when the body is made";

const Property properties[] = {
    {"position", get_member<Vec3, &Body::position>, set_position, "vec3, m: the COM, world",
     nullptr, nullptr},
    {"orientation", get_member<Quat, &Body::orientation>, set_orientation,
     "quat, body to world (normalised when set)", nullptr, nullptr},
    {"velocity", get_member<Vec3, &Body::velocity>, set_motion<&Body::velocity>,
     "vec3, m/s: of the COM, world", nullptr, nullptr},
    {"angular_velocity", get_member<Vec3, &Body::angular_velocity>,
     set_motion<&Body::angular_velocity>, "vec3, rad/s, world", nullptr, nullptr},
    {"restitution", get_member<double, &Body::restitution>, set_restitution,
     "e in [0, 1] (default 0): contacts use max(ea, eb)", nullptr, nullptr},
    {"friction", get_member<double, &Body::friction>, set_friction,
     "Coulomb μ >= 0 (default 0.6): contacts use √(μa μb)", nullptr, nullptr},
    {"sleeping", get_sleeping, nullptr,
     "true while the body's island sleeps (world.sleeping; b:wake() wakes it)",
     "bodies fall asleep by themselves, a whole island at rest at a time, when world.sleeping "
     "is on; b:wake() wakes the body's island",
     nullptr},
    {"mass", get_member<double, &Body::mass>, nullptr, "kg (math.huge: static)", made_fixed,
     nullptr},
    {"inv_mass", get_member<double, &Body::inverse_mass>, nullptr, "1/kg (0: static)",
     made_fixed, nullptr},
    {"inertia", get_member<Mat3, &Body::inertia>, nullptr,
     "mat3, kg m², body frame, about the COM", made_fixed, nullptr},
    {"inv_inertia", get_member<Mat3, &Body::inverse_inertia>, nullptr,
     "mat3, 1/(kg m²), body frame (0: static)", made_fixed, nullptr},
    {"static", get_static, nullptr, "true for an immovable body", made_fixed, nullptr},
    {"shape", get_shape, nullptr, "\"none\", \"sphere\" or \"box\"", made_fixed, nullptr},
    {"radius", get_radius, nullptr, "m, of a sphere (nil otherwise)", made_fixed, nullptr},
    {"size", get_size, nullptr, "vec3, m, full edges of a box (nil otherwise)", made_fixed,
     nullptr},
    {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr}};

void check_body_settable(lua_State* L, int object, const Where& where) {
  if (check_body_handle(L, object).store->stepping())
    where.error(L, "the world is stepping: it cannot be set until world:step returns; force "
                   "callbacks may only apply forces");
}

// ---- constructors ----------------------------------------------------------------------------

// mass and static of a constructor table. Returns true for a static body; `mass` is set for a
// dynamic one. `mass = math.huge` and `static = true` both make a static body.
bool read_mass(lua_State* L, double& mass) {
  bool is_static = false, static_given = false;
  if (get_field(L, 1, "static") != LUA_TNIL) {
    is_static = check_boolean(L, -1, Where::field(1, "static"));
    static_given = true;
  }
  lua_pop(L, 1);
  const int type = get_field(L, 1, "mass");
  if (type == LUA_TNIL) {
    lua_pop(L, 1);
    if (!is_static) arg_error(L, 1, "field 'mass' is required (or static = true)");
    return true;
  }
  if (type != LUA_TNUMBER) Where::field(1, "mass").type_error(L, -1, "number");
  mass = lua_tonumber(L, -1);
  lua_pop(L, 1);
  if (mass == std::numeric_limits<double>::infinity()) {
    if (static_given && !is_static)
      arg_error(L, 1, "mass = math.huge makes a static body, but field 'static' is false");
    return true;
  }
  if (std::isnan(mass) || std::isinf(mass))
    arg_error(L, 1, "field 'mass' must be finite or math.huge, got %s",
              format_number(mass).c_str());
  if (is_static)
    arg_error(L, 1, "field 'mass' must be math.huge or absent for a static body, got %s",
              format_number(mass).c_str());
  const std::string problem = mass_problem(mass);
  if (!problem.empty()) arg_error(L, 1, "field 'mass' %s", problem.c_str());
  return false;
}

// API.md "Bodies": an immovable body takes no inertia (its inverse inertia is 0).
void refuse_static_inertia(lua_State* L) {
  if (get_field(L, 1, "inertia") != LUA_TNIL)
    arg_error(L, 1, "field 'inertia' must be absent: a static body (static = true or mass = "
                    "math.huge) takes no inertia (its inverse inertia is 0)");
  lua_pop(L, 1);
}

// The new body b, pushed, then the settable fields of the table at 1 set on it.
int push_constructed(lua_State* L, const Body& b) {
  push_new_body(L, b);
  set_from_table(L, body_type, lua_gettop(L), 1);
  return 1;
}

int body_call(lua_State* L) {
  lua_remove(L, 1);  // the body table itself
  if (!lua_istable(L, 1)) type_error(L, 1, "table");
  check_no_extra_args(L, 1);
  static const char* const own[] = {"mass", "inertia", "static", nullptr};
  check_fields(L, 1, constructor_fields(L, body_type, own));
  double mass = 0.0;
  if (read_mass(L, mass)) {
    refuse_static_inertia(L);
    return push_constructed(L, make_static_body());
  }
  if (get_field(L, 1, "inertia") == LUA_TNIL) arg_error(L, 1, "field 'inertia' is required");
  const Mat3* inertia = test_mat3(L, -1);
  if (inertia == nullptr) Where::field(1, "inertia").type_error(L, -1, "mat3");
  const Mat3 tensor = *inertia;
  lua_pop(L, 1);
  const std::string problem = inertia_tensor_problem(tensor);
  if (!problem.empty())
    arg_error(L, 1,
              "field 'inertia' is not a valid inertia tensor (symmetric, positive definite, "
              "A + B >= C): %s",
              problem.c_str());
  return push_constructed(L, protect(L, 1, [&] { return make_body(mass, tensor); }));
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
  static const char* const sphere_fields[] = {"mass", "static", "radius", nullptr};
  static const char* const box_fields[] = {"mass", "static", "size", nullptr};
  const bool sphere = kind == ShapeKind::sphere;
  check_fields(L, 1, constructor_fields(L, body_type, sphere ? sphere_fields : box_fields));
  double radius = 0.0;
  Vec3 size = Vec3::Zero();
  if (sphere) {
    radius = field_positive(L, 1, "radius", 0.0, true);
  } else {
    size = field_vec3(L, 1, "size", Vec3::Zero(), true);
    if (!(size.minCoeff() > 0.0))
      arg_error(L, 1, "field 'size' must have every component > 0, got (%s, %s, %s)",
                format_number(size.x()).c_str(), format_number(size.y()).c_str(),
                format_number(size.z()).c_str());
  }
  double mass = 0.0;
  if (read_mass(L, mass)) {
    Body b = make_static_body();
    b.shape.kind = kind;
    b.shape.radius = radius;
    b.shape.half_extents = 0.5 * size;
    return push_constructed(L, b);
  }
  check_shape_inertia(L, kind, mass, radius, size);
  return push_constructed(L, protect(L, 1, [&] {
    return sphere ? make_sphere_body(mass, radius) : make_box_body(mass, size);
  }));
}

int body_sphere(lua_State* L) { return shaped_body(L, ShapeKind::sphere); }
int body_box(lua_State* L) { return shaped_body(L, ShapeKind::box); }

// ---- metamethods -----------------------------------------------------------------------------

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

// A body's __gc, run by the collector or by hand: refused while its world steps (the
// collector never finalises such a body: its world's list holds it); afterwards the value is
// no body ("the body was finalised"), so a second call does nothing.
int body_gc(lua_State* L) {
  BodyHandle* handle = test_body(L, 1);
  if (handle == nullptr) return 0;
  if (handle->store->stepping())
    arg_error(L, 1, "the body's world is stepping: it cannot be finalised until world:step "
                    "returns");
  handle->~BodyHandle();
  static_cast<BodyBox*>(lua_touserdata(L, 1))->tag = 0;
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
  wake(check_body_handle(L, 1));
  return 0;
}

int body_apply_torque(lua_State* L) {
  Body& b = check_body(L, 1);
  const Vec3 t = check_vec3(L, 2);
  check_no_extra_args(L, 2);
  if (!is_finite(Vec3(b.torque + t))) arg_error(L, 2, "the accumulated torque would overflow");
  apply_torque(b, t);
  wake(check_body_handle(L, 1));
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
  wake(check_body_handle(L, 1));
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
  wake(check_body_handle(L, 1));
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

// b:wake(): wakes the body's island (engine/islands.hpp); nothing for an awake or lone body.
int body_wake(lua_State* L) {
  BodyHandle& handle = check_body_handle(L, 1);
  check_no_extra_args(L, 1);
  check_not_stepping(L, 1, handle, "wake a body");
  wake(handle);
  return 0;
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
    {"wake", body_wake, "body:wake", "b:wake()",
     "Wakes the body's sleeping island (world.sleeping): its bodies move again from rest.\n"
     "Nothing for an awake body. Changing a body's state or applying a force, torque or\n"
     "impulse wakes its island too."},
    {"kinetic_energy", body_kinetic_energy, "body:kinetic_energy", "b:kinetic_energy() -> number",
     "½ m v·v + ½ ω·I_world ω (J); zero for a static body."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry metamethods[] = {
    {"__tostring", body_tostring, "body.__tostring", "tostring(b)",
     "Short form: body(sphere, m=1, pos=(0, 1, 0))."},
    {"__gc", body_gc, "body.__gc", "",
     "Releases the body's storage (refused while its world steps)."},
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
     "A rigid body. A moving body needs mass (kg) and inertia (mat3, kg m², body frame about\n"
     "the COM: symmetric, positive definite, principal moments with A + B >= C); position,\n"
     "orientation, velocity and angular_velocity default to zero / identity. static = true or\n"
     "mass = math.huge makes an immovable body, which takes no inertia (its inverse mass and\n"
     "inverse inertia are 0; impulses and forces do nothing to it).\n"
     "restitution and friction are the surface material for contacts (Box2D's rule).\n"
     "Shapes: body.sphere{...}, body.box{...}. The option table sets the settable fields."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

const TypeSpec body_type = {"body", &body_metatable_key, check_body_settable};

void read_material_fields(lua_State* L, int arg, double& restitution, double& friction) {
  restitution = default_restitution;
  friction = default_friction;
  if (get_field(L, arg, "restitution") != LUA_TNIL)
    restitution = check_restitution(L, -1, Where::field(arg, "restitution"));
  if (get_field(L, arg, "friction") != LUA_TNIL)
    friction = check_friction(L, -1, Where::field(arg, "friction"));
  lua_pop(L, 2);
}

BodyHandle* test_body(lua_State* L, int index) {
  return test_tagged<BodyHandle>(L, index, body_tag);
}

BodyHandle& check_body_handle(lua_State* L, int index, const Where& where) {
  BodyHandle* handle = test_body(L, index);
  if (handle != nullptr) return *handle;
  // A body whose __gc has run (used from a finaliser) has its tag cleared but its size and
  // metatable; anything else in a body's metatable (debug.setmetatable) is named by type.
  const auto* box = static_cast<const BodyBox*>(lua_touserdata(L, index));
  if (box != nullptr && lua_rawlen(L, index) == sizeof(BodyBox) && box->tag == 0 &&
      has_metatable(L, index, &body_metatable_key))
    where.error(L, "must be a body, got a finalised one (its __gc has run; it is used from a "
                   "finaliser)");
  where.type_error(L, index, "body");
}

BodyHandle& check_body_handle(lua_State* L, int arg) {
  return check_body_handle(L, arg, Where::argument(arg));
}

BodyHandle& push_new_body(lua_State* L, const Body& b) {
  BodyHandle handle{std::make_shared<BodyStore>(), {}};
  handle.id = handle.store->insert(b);
  void* memory = lua_newuserdatauv(L, sizeof(BodyBox), 0);
  auto* box = new (memory) BodyBox{body_tag, std::move(handle)};  // moving cannot throw
  lua_rawgetp(L, LUA_REGISTRYINDEX, &body_metatable_key);
  lua_setmetatable(L, -2);
  return box->value;
}

void check_not_stepping(lua_State* L, int arg, const BodyHandle& handle, const char* what) {
  if (handle.store->stepping()) stepping_error(L, arg, what);
}

void open_body(lua_State* L, int lib) {
  lua_newtable(L);  // the callable `body` table
  const int table = lua_gettop(L);
  new_type(L, body_type, table, metamethods);
  add_properties(L, body_type, properties);
  add_methods(L, body_type, methods);  // body.kinetic_energy(b) works as b:kinetic_energy()
  register_entries(L, table, constructors);
  lua_newtable(L);
  register_entries(L, -1, call_entry);
  lua_pushliteral(L, "body");
  lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, table);
  register_topic(L, table, "body", call_entry[0].doc);
  lua_setfield(L, lib, "body");
}

}  // namespace rigidlab::lua
