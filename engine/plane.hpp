// Static planes of a world and the surface material of contacts.
//
// A plane is the half-space {x : n·x ≥ offset} (the solid side is n·x < offset): bodies live
// where n·x ≥ offset and are pushed back there. It never moves (infinite mass).
//
// Material: restitution e in [0, 1] (001_* Appendix C: e = 0 perfectly inelastic, e = 1
// elastic) and a Coulomb friction coefficient μ ≥ 0. A contact between two surfaces uses the
// rule of Box2D (b2MixFriction / b2MixRestitution in Box2D v2.4's b2_contact.h):
//   μ = √(μa μb),   e = max(ea, eb),
// so a frictionless surface makes every contact on it frictionless, and a bouncy surface
// makes every contact on it bounce. Defaults are Box2D v3's b2DefaultShapeDef: μ = 0.6, e = 0.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/math.hpp"

namespace rigidlab {

inline constexpr double default_restitution = 0.0;
inline constexpr double default_friction = 0.6;

struct Plane {
  Vec3 normal = Vec3::UnitY();  // unit, pointing out of the solid into the free half-space
  double offset = 0.0;          // m: the surface is n·x = offset
  double restitution = default_restitution;
  double friction = default_friction;
};

// "" when e is in [0, 1] and μ is finite and ≥ 0; otherwise the rule broken, naming the field:
// "restitution must be in [0, 1], got 2", "friction must be >= 0, got -1".
std::string material_problem(double restitution, double friction);

// The plane n·x ≥ offset for any finite non-zero n: stored with the unit normal n/|n| and the
// offset divided by |n| (the same half-space). Throws std::invalid_argument for a zero or
// non-finite normal, a non-finite offset or a bad material (material_problem's message).
Plane make_plane(const Vec3& normal, double offset, double restitution = default_restitution,
                 double friction = default_friction);

// n·x − offset (m): > 0 in the free half-space, < 0 inside the solid.
inline double signed_distance(const Plane& plane, const Vec3& x) {
  return plane.normal.dot(x) - plane.offset;
}

// The contact material of two surfaces (Box2D's mixing rules, see above).
inline double mix_friction(double friction_a, double friction_b) {
  return std::sqrt(friction_a * friction_b);
}
inline double mix_restitution(double restitution_a, double restitution_b) {
  return std::max(restitution_a, restitution_b);
}

}  // namespace rigidlab
