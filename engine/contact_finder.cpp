// The contact solver, part 1: finding the contacts of a step (broad phase, narrow phase,
// speculative contacts and their time of impact) and turning each point into constraints.
// See engine/contact_solver.hpp.
#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/contact_helpers.hpp"
#include "engine/contact_solver.hpp"
#include "engine/time_of_impact.hpp"

namespace rigidlab {

using namespace contact_detail;

namespace {

// The normal velocity w (m/s, < 0) with which a point meets the surface in this step, on the
// parabola its positions follow (see the header): with u_n the velocity the positions move
// with, a_n its normal acceleration and s its gap at the start, w₀ = u_n − a_n Δt/2 and the gap
// s + w₀ t + ½ a_n t² first closes at w = −√(w₀² − 2 a_n s). A touching point (s ≤ 0) meets
// it now, at w₀. 0 when the point does not approach the surface in the step.
double impact_velocity(double approach, double acceleration, double separation, double dt) {
  const double w0 = approach - 0.5 * acceleration * dt;
  if (separation <= 0.0) return std::min(w0, 0.0);
  const double square = w0 * w0 - 2.0 * acceleration * separation;
  if (!(square >= 0.0)) return 0.0;  // turns back before reaching the surface
  const double w = -std::sqrt(square);
  // The time of that velocity, w = w₀ + a_n t, must lie within the step (and after w₀ < 0
  // when a_n = 0, the gap closing at the constant rate −w₀).
  const double t = acceleration != 0.0 ? (w - w0) / acceleration
                                       : (w0 < 0.0 ? separation / -w0 : -1.0);
  return t >= 0.0 && t <= dt * (1.0 + 1e-9) ? w : 0.0;
}

// The smallest extent of a shape (m): a sphere's diameter, a box's shortest side.
double smallest_dimension(const Shape& shape) {
  switch (shape.kind) {
    case ShapeKind::sphere:
      return 2.0 * shape.radius;
    case ShapeKind::box:
      return 2.0 * shape.half_extents.minCoeff();
    case ShapeKind::none:
      break;
  }
  return std::numeric_limits<double>::infinity();
}

constexpr double slop_fraction = 0.01;

}  // namespace

std::uint32_t ContactSolver::slot_for(const std::vector<Body>& bodies, std::size_t index,
                                      const Vec3& gravity, double dt,
                                      ContactVelocities velocities) {
  const Body& body = bodies[index];
  if (is_static(body)) return 0;
  if (slot_of_[index] != 0) return slot_of_[index];
  SolverBody s;
  s.index = index;
  s.inverse_mass = body.inverse_mass;
  s.inverse_inertia = inverse_world_inertia(body);
  s.velocity = body.velocity;
  s.angular_velocity = body.angular_velocity;
  s.acceleration = body.inverse_mass * body.force + gravity;
  s.angular_acceleration = s.inverse_inertia * body.torque;
  const double h = force_time(velocities, dt);
  s.velocity += h * s.acceleration;
  s.angular_velocity += h * s.angular_acceleration;
  s.start_velocity = s.velocity;
  s.start_angular_velocity = s.angular_velocity;
  slot_of_[index] = static_cast<std::uint32_t>(solver_bodies_.size());
  solver_bodies_.push_back(s);
  return slot_of_[index];
}

// Broad phase: bounding spheres grown by how far the body can move in the step (its speed
// bound |v| + |ω| R after this step's forces), sorted along x (sweep and prune).
void ContactSolver::build_proxies(const std::vector<Body>& bodies, const Vec3& gravity, double dt,
                                  ContactVelocities velocities) {
  const double half_margin = 0.5 * settings.speculative_distance;
  const double h = force_time(velocities, dt);
  proxies_.clear();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    if (b.shape.kind == ShapeKind::none) continue;
    const double radius = bounding_radius(b.shape);
    double speed = 0.0;
    if (!is_static(b)) {
      const Vec3 v = b.velocity + h * (b.inverse_mass * b.force + gravity);
      // trace(I⁻¹) ≥ the largest eigenvalue of I⁻¹ (it is SPD), so this bounds |ω + h I⁻¹τ|.
      const double spin =
          b.angular_velocity.norm() + h * b.inverse_inertia.trace() * b.torque.norm();
      speed = v.norm() + spin * radius;
    }
    // Capped so that absurd speeds (1e300 m/s) cannot make the margins overflow to infinity.
    const double sweep = std::min(speed * dt, max_sweep);
    const double reach = radius + sweep + half_margin;
    proxies_.push_back({b.position.x() - reach, b.position.x() + reach, i, radius, sweep});
  }
  std::sort(proxies_.begin(), proxies_.end(), [](const Proxy& p, const Proxy& q) {
    return p.min_x < q.min_x || (p.min_x == q.min_x && p.index < q.index);
  });
}

void ContactSolver::find_contacts(std::vector<Body>& bodies, const std::vector<Plane>& planes,
                                  const Vec3& gravity, double dt, ContactVelocities velocities) {
  for (std::size_t s = 1; s < solver_bodies_.size(); ++s)
    if (solver_bodies_[s].index < slot_of_.size()) slot_of_[solver_bodies_[s].index] = 0;
  slot_of_.resize(bodies.size(), 0);
  solver_bodies_.resize(1);
  solver_bodies_[0] = SolverBody{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero(),
                                 Vec3::Zero(), Vec3::Zero(), Mat3::Zero(),  0.0,
                                 no_body};
  constraints_.clear();
  manifold_begin_.clear();
  build_proxies(bodies, gravity, dt, velocities);
  auto slot = [&](std::size_t index) { return slot_for(bodies, index, gravity, dt, velocities); };
  for (const Proxy& p : proxies_) {
    const Body& b = bodies[p.index];
    if (is_static(b)) continue;
    const double margin = settings.speculative_distance + p.sweep;
    for (std::size_t k = 0; k < planes.size(); ++k) {
      if (signed_distance(planes[k], b.position) - p.radius > margin) continue;
      const Manifold m = collide_shape_plane(b.shape, pose_of(b), planes[k], margin);
      if (m.count > 0)
        add_pair(bodies, m, no_body, p.index, k, &planes[k], dt, 0, slot(p.index));
    }
  }
  for (std::size_t i = 0; i < proxies_.size(); ++i) {
    for (std::size_t j = i + 1; j < proxies_.size() && proxies_[j].min_x <= proxies_[i].max_x;
         ++j) {
      const std::size_t a = std::min(proxies_[i].index, proxies_[j].index);
      const std::size_t b = std::max(proxies_[i].index, proxies_[j].index);
      const Body& body_a = bodies[a];
      const Body& body_b = bodies[b];
      if (is_static(body_a) && is_static(body_b)) continue;
      const double margin = settings.speculative_distance + proxies_[i].sweep + proxies_[j].sweep;
      const double reach = proxies_[i].radius + proxies_[j].radius + margin;
      if ((body_b.position - body_a.position).squaredNorm() > reach * reach) continue;
      const Manifold m =
          collide_shapes(body_a.shape, pose_of(body_a), body_b.shape, pose_of(body_b), margin);
      if (m.count > 0) add_pair(bodies, m, a, b, no_plane, nullptr, dt, slot(a), slot(b));
    }
  }
}

// The largest gap at which a point counts as touching (m): a point that landed at the end of
// the last step sits at gap 0 up to rounding, and conservative advancement stops this close.
double ContactSolver::touch_tolerance() const {
  return std::max(0.1 * settings.linear_slop, 1e-6);
}

// Which contact a pair gets (see the header, "Speculative contacts"): the manifold at the start
// of the step when a point touches; when all its points have gaps, the points within
// speculative_distance if the bodies cannot meet in the step anyway (bounded by how fast they
// close along the normal, spin included), else the manifold at the time of impact, or nothing
// when they miss each other.
void ContactSolver::add_pair(const std::vector<Body>& bodies, const Manifold& m, std::size_t a,
                             std::size_t b, std::size_t plane, const Plane* plane_material,
                             double dt, std::uint32_t slot_a, std::uint32_t slot_b) {
  const Body* body_a = a == no_body ? nullptr : &bodies[a];
  const Body& body_b = bodies[b];
  const Pose pose_a = body_a ? pose_of(*body_a) : Pose{}, pose_b = pose_of(body_b);
  auto add = [&](const Manifold& manifold, double toi, const Pose& at_a, const Pose& at_b) {
    add_manifold(bodies, manifold, a, b, plane, plane_material, dt, slot_a, slot_b, toi, at_a,
                 at_b);
  };
  double gap = std::numeric_limits<double>::infinity();
  for (int k = 0; k < m.count; ++k) gap = std::min(gap, -m.points[k].depth);
  if (gap <= touch_tolerance()) return add(m, 0.0, pose_a, pose_b);
  const SolverBody& sa = solver_bodies_[slot_a];
  const SolverBody& sb = solver_bodies_[slot_b];
  const Motion motion_a{sa.velocity, sa.angular_velocity}, motion_b{sb.velocity, sb.angular_velocity};
  const double radius_a = body_a ? bounding_radius(body_a->shape) : 0.0;
  const double closing = -m.normal.dot(sb.velocity - sa.velocity) +
                         sa.angular_velocity.norm() * radius_a +
                         sb.angular_velocity.norm() * bounding_radius(body_b.shape);
  if (gap - closing * dt > 0.0) {  // they stay apart along the normal: keep the near points
    Manifold near = m;
    near.count = 0;
    for (int k = 0; k < m.count; ++k)
      if (-m.points[k].depth <= settings.speculative_distance)
        near.points[near.count++] = m.points[k];
    if (near.count > 0) add(near, 0.0, pose_a, pose_b);
    return;
  }
  const double tolerance = touch_tolerance();
  const double toi =
      body_a ? time_of_impact(body_a->shape, pose_a, motion_a, body_b.shape, pose_b, motion_b, dt,
                              tolerance)
             : time_of_impact(body_b.shape, pose_b, motion_b, *plane_material, dt, tolerance);
  if (toi < 0.0) return;  // they miss each other in this step
  const Pose at_a = body_a ? advance(pose_a, motion_a, toi) : pose_a;
  const Pose at_b = advance(pose_b, motion_b, toi);
  // At τ the rest of the shapes may still close in by what they can travel until the end of
  // the step (a box swinging down onto its face): those points are contacts too.
  const double speed = (sb.velocity - sa.velocity).norm() +
                       sa.angular_velocity.norm() * radius_a +
                       sb.angular_velocity.norm() * bounding_radius(body_b.shape);
  const double margin =
      settings.speculative_distance + tolerance + std::min(speed * (dt - toi), max_sweep);
  const Manifold hit = body_a ? collide_shapes(body_a->shape, at_a, body_b.shape, at_b, margin)
                              : collide_shape_plane(body_b.shape, at_b, *plane_material, margin);
  if (hit.count > 0) add(hit, toi, at_a, at_b);
}

// One constraint per manifold point: offsets (lever arms at the poses where the manifold was
// found), effective masses (001_* Appendix D), the approach velocity before the solve, the
// gap along the normal at the start of the step and the point's impact velocity.
void ContactSolver::add_manifold(const std::vector<Body>& bodies, const Manifold& m, std::size_t a,
                                 std::size_t b, std::size_t plane, const Plane* plane_material,
                                 double dt, std::uint32_t slot_a, std::uint32_t slot_b, double toi,
                                 const Pose& pose_a, const Pose& pose_b) {
  const Body* body_a = a == no_body ? nullptr : &bodies[a];
  const Body& body_b = bodies[b];
  const double restitution_a = body_a ? body_a->restitution : plane_material->restitution;
  const double friction_a = body_a ? body_a->friction : plane_material->friction;
  const SolverBody& sa = solver_bodies_[slot_a];
  const SolverBody& sb = solver_bodies_[slot_b];
  const double size_a = body_a ? smallest_dimension(body_a->shape)
                               : std::numeric_limits<double>::infinity();
  const double size_b = smallest_dimension(body_b.shape);
  manifold_begin_.push_back(constraints_.size());
  for (int k = 0; k < m.count; ++k) {
    const ContactPoint& p = m.points[k];
    Constraint c{};
    c.a = a, c.b = b, c.plane = plane;
    c.slot_a = slot_a, c.slot_b = slot_b, c.feature = p.feature;
    c.normal = m.normal;
    c.point = p.point;
    // Witness points (engine/contacts.hpp): on a at point − n g/2, on b at point + n g/2,
    // stored in body coordinates of the poses they were found at.
    const double gap = -p.depth;
    const Vec3 witness_a = p.point - 0.5 * gap * c.normal;
    const Vec3 witness_b = p.point + 0.5 * gap * c.normal;
    c.anchor_a = body_a ? Vec3(pose_a.rotation.transpose() * (witness_a - pose_a.position))
                        : witness_a;
    c.anchor_b = pose_b.rotation.transpose() * (witness_b - pose_b.position);
    c.radius_a = body_a && body_a->shape.kind == ShapeKind::sphere ? body_a->shape.radius : 0.0;
    c.radius_b = body_b.shape.kind == ShapeKind::sphere ? body_b.shape.radius : 0.0;
    // The lever arms: one world point for both bodies at their present poses, so the pair's
    // linear and angular momentum are kept exactly. At an impact found at τ > 0 the bodies
    // touch at p when they have moved by u τ; the point taken is p − τ (m_a⁻¹u_a + m_b⁻¹u_b)
    // /(m_a⁻¹ + m_b⁻¹), which is p as the lighter body sees it (exactly, against a plane or a
    // static body: a fast ball meeting a floor gets the lever R), the difference of their
    // displacements going to the heavier one.
    const double weight_a = sa.inverse_mass / (sa.inverse_mass + sb.inverse_mass);
    const Vec3 shift = toi * (weight_a * sa.velocity + (1.0 - weight_a) * sb.velocity);
    const Vec3 point = p.point - shift;
    c.r_a = body_a ? Vec3(point - body_a->position) : Vec3::Zero();
    c.r_b = point - body_b.position;
    // A sphere that gets its exact lever arm gets it along the normal, without rounding: a
    // frictionless contact then never spins it.
    if (weight_a == 0.0 && c.radius_b > 0.0) c.r_b = -c.radius_b * c.normal;
    if (weight_a == 1.0 && c.radius_a > 0.0) c.r_a = c.radius_a * c.normal;
    const Vec3 relative = point_velocity_of(sb, c.r_b) - point_velocity_of(sa, c.r_a);
    c.approach = c.normal.dot(relative);
    // The gap at the start of the step: found at τ, it closed at the rate −v_n since.
    c.separation = gap - toi * c.approach;
    friction_directions(c.normal, relative - c.approach * c.normal, c.tangent1, c.tangent2);
    c.normal_mass = inverse_or_zero(inverse_effective_mass(sa, c.r_a, sb, c.r_b, c.normal));
    c.tangent_mass1 = inverse_or_zero(inverse_effective_mass(sa, c.r_a, sb, c.r_b, c.tangent1));
    c.tangent_mass2 = inverse_or_zero(inverse_effective_mass(sa, c.r_a, sb, c.r_b, c.tangent2));
    c.bias = c.separation > 0.0 ? c.separation / dt : 0.0;
    c.acceleration = c.normal.dot(sb.acceleration + sb.angular_acceleration.cross(c.r_b) -
                                  sa.acceleration - sa.angular_acceleration.cross(c.r_a));
    c.impact = impact_velocity(c.approach, c.acceleration, c.separation, dt);
    // The overlap position correction leaves alone: linear_slop, but at most 1 % of the
    // smaller body (a 0.1 m cube would otherwise rest 5 mm, 5 % of its height, deep).
    c.slop = std::min(settings.linear_slop, slop_fraction * std::min(size_a, size_b));
    c.restitution = mix_restitution(restitution_a, body_b.restitution);
    c.friction = mix_friction(friction_a, body_b.friction);
    constraints_.push_back(c);
  }
}

}  // namespace rigidlab
