// Small helpers shared by the contact constraints' files (engine/contact_constraints.cpp,
// contact_finder.cpp, contact_restitution.cpp, contact_positions.cpp): not part of the
// engine's interface.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <tuple>

#include "engine/contact_constraints.hpp"

namespace rigidlab::contact_detail {

// Two unit tangents completing the unit normal n to a right-handed basis, continuous in n
// except across n.z = 0 (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017).
inline void tangent_basis(const Vec3& n, Vec3& t1, Vec3& t2) {
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  t1 = Vec3(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  t2 = Vec3(b, sign + n.y() * n.y() * a, -n.y());
}

// The friction directions of a point: the first along its slip (its tangential relative
// velocity), so that when it slides the Coulomb impulse μ λn opposes the slip, as Coulomb's
// law has it (with two independent tangents of unequal effective masses the clamped impulse
// would lean off it: a box sliding down a slope then got 94 % of its friction); any basis when
// it does not slip.
inline void friction_directions(const Vec3& n, const Vec3& slip, Vec3& t1, Vec3& t2) {
  const double speed = slip.norm();
  if (!(speed > 1e-9)) return tangent_basis(n, t1, t2);
  t1 = slip / speed;
  t2 = n.cross(t1);
}

// The order of contacts: by the first body (a, or the body of a plane contact), then other
// bodies before planes, then the other body or plane, then the feature.
inline auto sort_key(BodyId a, BodyId b, std::size_t plane, std::uint32_t feature) {
  const bool is_plane = !a.valid();
  return std::make_tuple(is_plane ? b : a, is_plane, is_plane ? BodyId{} : b,
                         is_plane ? plane : 0, feature);
}
inline auto sort_key(const ContactInfo& c) { return sort_key(c.a, c.b, c.plane, c.feature); }

// The part of v in the contact plane of unit normal n.
inline Vec3 in_plane(const Vec3& v, const Vec3& n) { return v - n.dot(v) * n; }

// Velocity of the material point at offset r from the COM of a solver body (m/s).
inline Vec3 point_velocity_of(const SolverBody& s, const Vec3& r) {
  return s.velocity + s.angular_velocity.cross(r);
}


// m, the farthest a shape is looked ahead in one step.
constexpr double max_sweep = 1e6;

}  // namespace rigidlab::contact_detail
