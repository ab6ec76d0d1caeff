// collide: the collision impulses of engine/impulses.hpp on their own, to compute by hand
// what a world does at every contact: collide.impulse_1d, collide.resolve,
// collide.inverse_mass_matrix, collide.effective_mass.
// Sources: 001_* "System Of Particles", "Collisions", Appendices C and D; 002_* "Inverse Mass
// Matrix"; 003_* "Collision Response".
#include <cmath>
#include <cstring>
#include <limits>

#include "engine/impulses.hpp"
#include "lua/binding.hpp"
#include "lua/body.hpp"
#include "lua/modules.hpp"

namespace rigidlab::lua {
namespace {

// A mass for impulse_1d: finite and > 0, or math.huge for an immovable body. Returns 1/m.
double check_inverse_mass(lua_State* L, int arg) {
  if (lua_type(L, arg) != LUA_TNUMBER) type_error(L, arg, "number");
  const double mass = lua_tonumber(L, arg);
  if (!(mass > 0.0))
    arg_error(L, arg, "mass must be > 0 (math.huge for immovable), got %s",
              format_number(mass).c_str());
  const double inverse = std::isinf(mass) ? 0.0 : 1.0 / mass;
  if (std::isinf(inverse))
    arg_error(L, arg, "mass must be at least %s (1/mass overflows), got %s",
              format_number(1.0 / std::numeric_limits<double>::max()).c_str(),
              format_number(mass).c_str());
  return inverse;
}

bool starts_with(const char* text, const char* prefix) {
  return std::strncmp(text, prefix, std::strlen(prefix)) == 0;
}

double check_restitution(lua_State* L, int arg) {
  const double e = check_finite(L, arg, "restitution");
  if (!(e >= 0.0 && e <= 1.0))
    arg_error(L, arg, "restitution must be in [0, 1], got %s", format_number(e).c_str());
  return e;
}

int collide_impulse_1d(lua_State* L) {
  check_no_extra_args(L, 5);
  const double inverse_mass_a = check_inverse_mass(L, 1);
  const double velocity_a = check_finite(L, 2, "va");
  const double inverse_mass_b = check_inverse_mass(L, 3);
  const double velocity_b = check_finite(L, 4, "vb");
  const double restitution = check_restitution(L, 5);
  if (inverse_mass_a == 0.0 && inverse_mass_b == 0.0)
    arg_error(L, 3, "both masses are math.huge: two immovable bodies cannot collide");
  // Overflow of J or a velocity: blame the larger of the two speeds.
  const int fast = std::abs(velocity_a) >= std::abs(velocity_b) ? 2 : 4;
  const Impulse1D r = protect(L, fast, [&] {
    return impulse_1d(inverse_mass_a, velocity_a, inverse_mass_b, velocity_b, restitution);
  });
  lua_pushnumber(L, r.impulse);
  lua_pushnumber(L, r.velocity_a);
  lua_pushnumber(L, r.velocity_b);
  return 3;
}

// Two distinct bodies at arguments 1 and 2, not both immovable.
void check_body_pair(lua_State* L, Body*& a, Body*& b) {
  a = &check_body(L, 1);
  b = &check_body(L, 2);
  if (a == b) arg_error(L, 2, "b must be a different body from a");
  if (is_static(*a) && is_static(*b))
    arg_error(L, 2, "both bodies are immovable: a contact between them has no impulse");
}

Vec3 check_normal(lua_State* L, int arg, const Vec3& normal, const char* what) {
  if (!is_finite(normal)) arg_error(L, arg, "%s must be finite", what);
  if (!(normal.cwiseAbs().maxCoeff() > 0.0)) arg_error(L, arg, "%s must not be zero", what);
  return normal;
}

Vec3 check_point(lua_State* L, int arg, const Vec3& point, const char* what) {
  if (!is_finite(point)) arg_error(L, arg, "%s must be finite", what);
  return point;
}

// The option table is read first, then the bodies are taken: its metamethods may add bodies
// to their world (moving its storage) or remove one.
int collide_resolve(lua_State* L) {
  check_no_extra_args(L, 3);
  check_body_handle(L, 1);
  check_body_handle(L, 2);
  if (lua_type(L, 3) != LUA_TTABLE) type_error(L, 3, "table");
  static const char* const fields[] = {"point", "normal", "restitution", "friction", nullptr};
  check_fields(L, 3, fields);
  Contact contact;
  contact.point = field_vec3(L, 3, "point", Vec3::Zero(), true);
  contact.normal = check_normal(L, 3, field_vec3(L, 3, "normal", Vec3::Zero(), true),
                                "field 'normal'");
  contact.restitution = field_finite(L, 3, "restitution", 0.0, false);
  if (!(contact.restitution >= 0.0 && contact.restitution <= 1.0))
    arg_error(L, 3, "field 'restitution' must be in [0, 1], got %s",
              format_number(contact.restitution).c_str());
  contact.friction = field_nonnegative(L, 3, "friction", 0.0, false);
  // No Lua code runs from here until the impulses are applied.
  Body *a, *b;
  check_body_pair(L, a, b);
  // Changing velocities in the middle of an RK4 step would corrupt it.
  check_not_stepping(L, 1, check_body_handle(L, 1), "apply collision impulses");
  check_not_stepping(L, 2, check_body_handle(L, 2), "apply collision impulses");
  // Left to the engine: a point so far away that the impulse overflows (bodies unchanged).
  const ContactImpulse r = protect(L, 3, [&] { return resolve_contact(*a, *b, contact); });
  lua_pushnumber(L, r.normal_impulse);
  push_vec3(L, r.friction_impulse);
  return 2;
}

int collide_inverse_mass_matrix(lua_State* L) {
  check_no_extra_args(L, 3);
  const Body& b = check_body(L, 1);
  const Vec3 r1 = check_vec3(L, 2);
  const Vec3 r2 = check_vec3(L, 3);
  check_point(L, 2, r1, "r1");
  check_point(L, 3, r2, "r2");
  const Mat3 m = inverse_mass_matrix(b, r1, r2);
  if (!is_finite(m))
    arg_error(L, 3, "r1 and r2 are too long: r̂2 I⁻¹ r̂1 overflows, got r1 = (%s, %s, %s), "
              "r2 = (%s, %s, %s)", format_number(r1.x()).c_str(), format_number(r1.y()).c_str(),
              format_number(r1.z()).c_str(), format_number(r2.x()).c_str(),
              format_number(r2.y()).c_str(), format_number(r2.z()).c_str());
  push_mat3(L, m);
  return 1;
}

int collide_effective_mass(lua_State* L) {
  check_no_extra_args(L, 4);
  Body *a, *b;
  check_body_pair(L, a, b);
  const Vec3 point = check_point(L, 3, check_vec3(L, 3), "point");
  const Vec3 normal = check_normal(L, 4, check_vec3(L, 4), "normal");
  double m = 0.0;
  if (const Failure failure = try_call([&] { m = effective_mass(*a, *b, point, normal); })) {
    const char* what = failure.what();
    failure.raise(L, starts_with(what, "normal") ? 4 : starts_with(what, "point") ? 3 : 2);
  }
  lua_pushnumber(L, m);
  return 1;
}

const Entry functions[] = {
    {"impulse_1d", collide_impulse_1d, "collide.impulse_1d",
     "collide.impulse_1d(ma, va, mb, vb, e) -> J, va', vb'",
     "The impulse of a head-on collision of two particles on a line, b ahead of a\n"
     "(001 \"System Of Particles\", Appendix C):\n"
     "  J = −(1 + e)(vb − va)/(1/ma + 1/mb),  va' = va − J/ma,  vb' = vb + J/mb\n"
     "Masses in kg (> 0; math.huge = immovable), velocities in m/s, restitution e in [0, 1]\n"
     "(1 elastic, 0 the bodies stick). The formula is applied as written: when vb > va the\n"
     "bodies are separating and J comes out negative.\n"
     "Example: collide.impulse_1d(1, 2, 4, 0, 1)  --> 3.2, -1.2, 0.8"},
    {"resolve", collide_resolve, "collide.resolve",
     "collide.resolve(a, b, {point =, normal =, restitution =, friction =}) -> J, friction_impulse",
     "Applies the collision impulses of one contact to bodies a and b (changes their velocity\n"
     "and angular_velocity) and returns the normal impulse J (N s, >= 0) and the friction\n"
     "impulse on b (vec3; a receives the opposite). point: world contact point; normal: from a\n"
     "to b (any length, normalised); restitution e in [0, 1] (default 0); friction μ >= 0\n"
     "(default 0). With v_rel = b:point_velocity(p) - a:point_velocity(p):\n"
     "  if v_rel·n >= 0 they separate: nothing happens, J = 0;\n"
     "  J = −(1+e) v_rel·n / (1/ma + 1/mb + n·[(Ia⁻¹(ra×n))×ra + (Ib⁻¹(rb×n))×rb])\n"
     "  (001 Appendix C, inverse world inertias), +J n on b and −J n on a at p, when there is\n"
     "  no friction. With friction μ the impulse P (on b; a gets −P) is found with the contact's\n"
     "  inverse mass matrix K (v_rel' = v_rel + K P, sums of collide.inverse_mass_matrix):\n"
     "  first the impulse that stops the point, −K⁻¹ v_rel, if Coulomb's cone |P_t| <= μ P_n\n"
     "  allows it (sticking), else the point where the way there from the frictionless impulse\n"
     "  leaves the cone (sliding at μ·J; Brach 1989, Mirtich 1996); then the rebound to\n"
     "  v_n' = −e v_n, keeping the point stuck if the cone allows and no energy is created.\n"
     "  Always v_n' = −e v_n, |friction| <= μ J and the kinetic energy never grows; for a\n"
     "  body whose contact couples normal and sliding motion (a turned box) a rebound with\n"
     "  e > 0 can leave the point slipping even for large μ (Kane's paradox, Stronge 1990).\n"     "Momentum (linear and angular) is conserved; energy is kept for e = 1 without friction."},
    {"inverse_mass_matrix", collide_inverse_mass_matrix, "collide.inverse_mass_matrix",
     "collide.inverse_mass_matrix(b, r1, r2) -> mat3",
     "002 \"Inverse Mass Matrix\": M⁻¹ = (1/m)E − r̂2 I⁻¹ r̂1 (world axes, world inverse\n"
     "inertia; r1, r2 world offsets from the COM in m; r1 may equal r2). An impulse j at\n"
     "offset r1 changes the velocity of the point at offset r2 by M⁻¹ * j. Zero for an\n"
     "immovable body."},
    {"effective_mass", collide_effective_mass, "collide.effective_mass",
     "collide.effective_mass(a, b, point, normal) -> kg",
     "001 Appendix D: 1/(J W Jᵀ) for the contact Jacobian J = [−n, −ra×n, n, rb×n] (n the\n"
     "normalised normal, ra, rb the offsets of the world point from each COM):\n"
     "  J W Jᵀ = 1/ma + 1/mb + (ra×n)·Ia⁻¹(ra×n) + (rb×n)·Ib⁻¹(rb×n).\n"
     "The mass the contact feels along n: the normal impulse is −(1+e) m_eff v_rel·n."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const char* const module_doc =
    "collide: collision impulses by hand (001 Appendices C and D, 002 \"Inverse Mass Matrix\",\n"
    "003 \"Collision Response\"). Bodies with mass = math.huge or static = true are immovable.";

}  // namespace

void open_collide(lua_State* L, int lib) {
  lua_newtable(L);
  register_entries(L, -1, functions);
  register_topic(L, -1, "collide", module_doc);
  lua_setfield(L, lib, "collide");
}

}  // namespace rigidlab::lua
