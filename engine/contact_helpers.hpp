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


// soft_step pushes an overlap out to this fraction of the point's slop (0.2 mm between bodies
// of 0.5 m and more, 0.04 % of the smaller body's size below), not to 0, as Box2D v2.4's
// position solver leaves b2_linearSlop. Why: a face's corners held at a separation of exactly
// 0 flip, step after step, between touching (v_n ≥ 0, pushed) and a gap (v_n ≥ −s/Δt, not
// pushed), and each flip changes the targets of the whole face. Measured at 60 Hz with the
// defaults, the boxes of a stack tilted by up to 2 × amplitude (tests/engine/
// perturbed_stack_test.cpp; largest sideways excursion of the top in 40 s): pushed to 0, a
// column of 10 at amplitude 1e-4 rocked with a growing swing, ±119 mm, and a twisted stack
// of 8 at 1e-3 ±99 mm; at 0.02 of the slop both stood up to 3e-3, but the twisted stack
// (θ = 0.1) at 1e-2 swung 147 mm; at 0.03 all stood up to 1e-2, and at 0.04 (θ = 0.4 at
// 2e-2: 9 mm where 0.03 gave 311 mm) up to 2e-2. What it costs: a body that sank comes back
// to this overlap rather than to touching (a stack settled by the euler integrator sits
// 0.2 mm per layer low); a body placed touching stays there.
constexpr double push_slop_fraction = 0.04;

// m, the farthest a shape is looked ahead in one step.
constexpr double max_sweep = 1e6;

}  // namespace rigidlab::contact_detail
