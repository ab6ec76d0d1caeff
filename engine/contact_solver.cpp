#include "engine/contact_solver.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "engine/format.hpp"
#include "engine/integrators.hpp"

namespace rigidlab {
namespace {

// Two unit tangents completing the unit normal n to a right-handed basis, continuous in n
// except across n.z = 0 (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017).
void tangent_basis(const Vec3& n, Vec3& t1, Vec3& t2) {
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
void friction_directions(const Vec3& n, const Vec3& slip, Vec3& t1, Vec3& t2) {
  const double speed = slip.norm();
  if (!(speed > 1e-9)) return tangent_basis(n, t1, t2);
  t1 = slip / speed;
  t2 = n.cross(t1);
}

// The order of contacts: by the first body (a, or the body of a plane contact), then other
// bodies before planes, then the other body or plane, then the feature.
auto sort_key(std::size_t a, std::size_t b, std::size_t plane, std::uint32_t feature) {
  const bool is_plane = a == no_body;
  return std::make_tuple(is_plane ? b : a, is_plane, is_plane ? plane : b, feature);
}
auto sort_key(const ContactInfo& c) { return sort_key(c.a, c.b, c.plane, c.feature); }

// Velocity of the material point at offset r from the COM of a solver body (m/s).
template <class SolverBody>
Vec3 point_velocity_of(const SolverBody& s, const Vec3& r) {
  return s.velocity + s.angular_velocity.cross(r);
}

// 001_* Appendix D: J W Jᵀ of one constraint direction d (unit), the inverse of the mass
// the contact feels along d (1/kg).
template <class SolverBody>
double inverse_effective_mass(const SolverBody& a, const Vec3& r_a, const SolverBody& b,
                              const Vec3& r_b, const Vec3& d) {
  const Vec3 ra_d = r_a.cross(d), rb_d = r_b.cross(d);
  return a.inverse_mass + b.inverse_mass + ra_d.dot(a.inverse_inertia * ra_d) +
         rb_d.dot(b.inverse_inertia * rb_d);
}

double inverse_or_zero(double k) { return k > 0.0 ? 1.0 / k : 0.0; }

constexpr double max_sweep = 1e6;

// How long the forces act on the velocities the impulses are computed against (s).
double force_time(ContactVelocities velocities, double dt) {
  switch (velocities) {
    case ContactVelocities::after_forces:
      return dt;
    case ContactVelocities::mid_step:
      return 0.5 * dt;
    case ContactVelocities::current:
      break;
  }
  return 0.0;
}  // m, the farthest a shape is looked ahead in one step

}  // namespace

std::string contact_settings_problem(const ContactSettings& s) {
  if (s.iterations < 1 || s.iterations > ContactSettings::max_iterations)
    return "iterations must be an integer from 1 to " +
           std::to_string(ContactSettings::max_iterations) + ", got " +
           std::to_string(s.iterations);
  if (s.position_iterations < 0 || s.position_iterations > ContactSettings::max_iterations)
    return "position_iterations must be an integer from 0 to " +
           std::to_string(ContactSettings::max_iterations) + ", got " +
           std::to_string(s.position_iterations);
  const struct {
    const char* name;
    double value;
  } lengths[] = {{"restitution_threshold", s.restitution_threshold},
                 {"linear_slop", s.linear_slop},
                 {"max_correction", s.max_correction},
                 {"speculative_distance", s.speculative_distance},
                 {"match_distance", s.match_distance},
                 {"impact_speed", s.impact_speed}};
  for (const auto& field : lengths)
    if (!std::isfinite(field.value) || !(field.value >= 0.0))
      return std::string(field.name) + " must be finite and >= 0, got " +
             format_number(field.value);
  if (!(s.baumgarte >= 0.0 && s.baumgarte <= 1.0))
    return "baumgarte must be in [0, 1], got " + format_number(s.baumgarte);
  return "";
}

// ---- finding the contacts --------------------------------------------------------------------

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
  const double h = force_time(velocities, dt);
  s.velocity += h * (body.inverse_mass * body.force + gravity);
  s.angular_velocity += h * (s.inverse_inertia * body.torque);
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
                                 Mat3::Zero(), 0.0,          no_body};
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
        add_manifold(bodies, m, no_body, p.index, k, &planes[k], dt, 0, slot(p.index));
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
      if (m.count > 0) add_manifold(bodies, m, a, b, no_plane, nullptr, dt, slot(a), slot(b));
    }
  }
}

// One constraint per manifold point: offsets, effective masses (001_* Appendix D), the
// approach velocity before the solve, and the warm-start impulses of the previous step.
void ContactSolver::add_manifold(const std::vector<Body>& bodies, const Manifold& m, std::size_t a,
                                 std::size_t b, std::size_t plane, const Plane* plane_material,
                                 double dt, std::uint32_t slot_a, std::uint32_t slot_b) {
  const Body* body_a = a == no_body ? nullptr : &bodies[a];
  const Body& body_b = bodies[b];
  const double restitution_a = body_a ? body_a->restitution : plane_material->restitution;
  const double friction_a = body_a ? body_a->friction : plane_material->friction;
  const SolverBody& sa = solver_bodies_[slot_a];
  const SolverBody& sb = solver_bodies_[slot_b];
  manifold_begin_.push_back(constraints_.size());
  for (int k = 0; k < m.count; ++k) {
    const ContactPoint& p = m.points[k];
    Constraint c{};
    c.a = a, c.b = b, c.plane = plane;
    c.slot_a = slot_a, c.slot_b = slot_b, c.feature = p.feature;
    c.normal = m.normal;
    c.point = p.point;
    c.separation = -p.depth;
    // Witness points (engine/contacts.hpp): on a at point − n s/2, on b at point + n s/2.
    const Vec3 witness_a = p.point - 0.5 * c.separation * c.normal;
    const Vec3 witness_b = p.point + 0.5 * c.separation * c.normal;
    c.anchor_a = body_a ? to_local(*body_a, witness_a) : witness_a;
    c.anchor_b = to_local(body_b, witness_b);
    c.radius_a = body_a && body_a->shape.kind == ShapeKind::sphere ? body_a->shape.radius : 0.0;
    c.radius_b = body_b.shape.kind == ShapeKind::sphere ? body_b.shape.radius : 0.0;
    c.r_a = body_a ? Vec3(p.point - body_a->position) : Vec3::Zero();
    c.r_b = p.point - body_b.position;
    const Vec3 relative = point_velocity_of(sb, c.r_b) - point_velocity_of(sa, c.r_a);
    c.approach = c.normal.dot(relative);
    friction_directions(c.normal, relative - c.approach * c.normal, c.tangent1, c.tangent2);
    c.normal_mass = inverse_or_zero(inverse_effective_mass(sa, c.r_a, sb, c.r_b, c.normal));
    c.tangent_mass1 = inverse_or_zero(inverse_effective_mass(sa, c.r_a, sb, c.r_b, c.tangent1));
    c.tangent_mass2 = inverse_or_zero(inverse_effective_mass(sa, c.r_a, sb, c.r_b, c.tangent2));
    c.bias = c.separation > 0.0 ? c.separation / dt : 0.0;
    c.restitution = mix_restitution(restitution_a, body_b.restitution);
    c.friction = mix_friction(friction_a, body_b.friction);
    constraints_.push_back(c);
  }
}

// ---- solving ---------------------------------------------------------------------------------

// The previous step's point that c continues: the same bodies (or plane) and feature, or else
// the nearest point of the same pair within match_distance (features of clipped faces change
// when a corner of one box lies exactly on a side of the other). nullptr when c is new.
const ContactInfo* ContactSolver::previous_point(const Constraint& c) const {
  auto less = [](const ContactInfo& info, const auto& k) { return sort_key(info) < k; };
  const auto key = sort_key(c.a, c.b, c.plane, c.feature);
  const auto found = std::lower_bound(contacts_.begin(), contacts_.end(), key, less);
  if (found != contacts_.end() && sort_key(*found) == key) return &*found;
  const ContactInfo* nearest = nullptr;
  double best = settings.match_distance * settings.match_distance;
  for (auto it = std::lower_bound(contacts_.begin(), contacts_.end(),
                                  sort_key(c.a, c.b, c.plane, 0), less);
       it != contacts_.end() && it->a == c.a && it->b == c.b && it->plane == c.plane; ++it) {
    const double d2 = (it->point - c.point).squaredNorm();
    if (d2 <= best) best = d2, nearest = &*it;
  }
  return nearest;
}

// Starts c from the impulses its point ended the previous step with.
void ContactSolver::warm_start(Constraint& c, double dt) {
  const ContactInfo* found = previous_point(c);
  if (found == nullptr) return;
  // Impulses scale with the step: a resting contact carries m g Δt.
  const double scale = last_dt_ > 0.0 ? dt / last_dt_ : 1.0;
  c.normal_impulse = scale * found->normal_impulse;
  c.tangent_impulse1 = scale * found->friction_impulse.dot(c.tangent1);
  c.tangent_impulse2 = scale * found->friction_impulse.dot(c.tangent2);
  const Vec3 impulse = c.normal_impulse * c.normal + c.tangent_impulse1 * c.tangent1 +
                       c.tangent_impulse2 * c.tangent2;
  SolverBody& a = solver_bodies_[c.slot_a];
  SolverBody& b = solver_bodies_[c.slot_b];
  a.velocity -= a.inverse_mass * impulse;
  a.angular_velocity -= a.inverse_inertia * c.r_a.cross(impulse);
  b.velocity += b.inverse_mass * impulse;
  b.angular_velocity += b.inverse_inertia * c.r_b.cross(impulse);
}

// The coarse correction of a manifold (see the header): the normal impulse that brings its
// centroid to the mean target velocity, −bias or −e v_n⁻, shared equally by its points.
void ContactSolver::seed_manifold(std::size_t begin, std::size_t end, bool restitution) {
  const Constraint& first = constraints_[begin];
  SolverBody& a = solver_bodies_[first.slot_a];
  SolverBody& b = solver_bodies_[first.slot_b];
  const double count = static_cast<double>(end - begin);
  Vec3 r_a = Vec3::Zero(), r_b = Vec3::Zero();
  double target = 0.0;  // mean of the velocity each point must gain along n, m/s
  for (std::size_t k = begin; k < end; ++k) {
    const Constraint& c = constraints_[k];
    r_a += c.r_a / count, r_b += c.r_b / count;
    target -= (restitution ? c.restitution * c.approach : c.bias) / count;
  }
  const Vec3& n = first.normal;
  const double vn = n.dot(point_velocity_of(b, r_b) - point_velocity_of(a, r_a));
  const double k = inverse_effective_mass(a, r_a, b, r_b, n);
  if (!(k > 0.0)) return;
  // A negative share (the warm start pushed too hard) may take back at most what the
  // least-loaded point holds, so every accumulated impulse stays ≥ 0.
  double least = constraints_[begin].normal_impulse;
  for (std::size_t j = begin; j < end; ++j) least = std::min(least, constraints_[j].normal_impulse);
  // Only impacts: at rest the warm start already holds a better split than an equal one.
  if (!(std::abs(target - vn) > settings.impact_speed)) return;
  const double share = std::max((target - vn) / k / count, -least);
  if (share == 0.0) return;
  for (std::size_t j = begin; j < end; ++j) constraints_[j].normal_impulse += share;
  const Vec3 impulse = share * count * n;
  a.velocity -= a.inverse_mass * impulse;
  a.angular_velocity -= a.inverse_inertia * r_a.cross(impulse);
  b.velocity += b.inverse_mass * impulse;
  b.angular_velocity += b.inverse_inertia * r_b.cross(impulse);
}

// One Gauss-Seidel update of a point: friction within the Coulomb disk of the current normal
// impulse, then the normal impulse (Catto 2005; Box2D v2.4 SolveVelocityConstraints).
void ContactSolver::solve_point(Constraint& c) {
  SolverBody& a = solver_bodies_[c.slot_a];
  SolverBody& b = solver_bodies_[c.slot_b];
  auto apply = [&](const Vec3& impulse) {
    a.velocity -= a.inverse_mass * impulse;
    a.angular_velocity -= a.inverse_inertia * c.r_a.cross(impulse);
    b.velocity += b.inverse_mass * impulse;
    b.angular_velocity += b.inverse_inertia * c.r_b.cross(impulse);
  };
  if (c.friction > 0.0) {
    const Vec3 dv = point_velocity_of(b, c.r_b) - point_velocity_of(a, c.r_a);
    double t1 = c.tangent_impulse1 - c.tangent_mass1 * dv.dot(c.tangent1);
    double t2 = c.tangent_impulse2 - c.tangent_mass2 * dv.dot(c.tangent2);
    const double limit = c.friction * c.normal_impulse;
    const double length = std::hypot(t1, t2);
    if (length > limit) {  // slipping: on the edge of the cone, against the slip
      const double scale = length > 0.0 ? limit / length : 0.0;
      t1 *= scale, t2 *= scale;
    }
    apply((t1 - c.tangent_impulse1) * c.tangent1 + (t2 - c.tangent_impulse2) * c.tangent2);
    c.tangent_impulse1 = t1, c.tangent_impulse2 = t2;
  }
  const Vec3 dv = point_velocity_of(b, c.r_b) - point_velocity_of(a, c.r_a);
  const double vn = dv.dot(c.normal);
  const double total = std::max(c.normal_impulse - c.normal_mass * (vn + c.bias), 0.0);
  apply((total - c.normal_impulse) * c.normal);
  c.normal_impulse = total;
  c.max_normal_impulse = std::max(c.max_normal_impulse, total);
}

// Box2D v3 b2ApplyRestitution: v_n → −e v_n⁻ at points that pushed and were approaching
// faster than the threshold. Repeated so simultaneous impacts (a box landing flat) share it.
void ContactSolver::apply_restitution() {
  auto bounces = [this](const Constraint& c) {
    return c.restitution > 0.0 && c.approach < -settings.restitution_threshold &&
           c.max_normal_impulse > 0.0;
  };
  for_each_manifold([&](std::size_t begin, std::size_t end) {
    if (end - begin > 1 &&
        std::all_of(constraints_.begin() + begin, constraints_.begin() + end, bounces))
      seed_manifold(begin, end, true);
  });
  for (int sweep = 0; sweep < settings.iterations; ++sweep) {
    double largest_change = 0.0;
    for (Constraint& c : constraints_) {
      if (!bounces(c)) continue;
      SolverBody& a = solver_bodies_[c.slot_a];
      SolverBody& b = solver_bodies_[c.slot_b];
      const double vn = c.normal.dot(point_velocity_of(b, c.r_b) - point_velocity_of(a, c.r_a));
      const double total =
          std::max(c.normal_impulse - c.normal_mass * (vn + c.restitution * c.approach), 0.0);
      const Vec3 impulse = (total - c.normal_impulse) * c.normal;
      largest_change = std::max(largest_change, std::abs(total - c.normal_impulse));
      a.velocity -= a.inverse_mass * impulse;
      a.angular_velocity -= a.inverse_inertia * c.r_a.cross(impulse);
      b.velocity += b.inverse_mass * impulse;
      b.angular_velocity += b.inverse_inertia * c.r_b.cross(impulse);
      c.normal_impulse = total;
    }
    if (largest_change == 0.0) break;
  }
}

void ContactSolver::store_results(double dt) {
  next_contacts_.clear();
  for (const Constraint& c : constraints_) {
    ContactInfo info;
    info.a = c.a, info.b = c.b, info.plane = c.plane, info.feature = c.feature;
    info.point = c.point;
    info.normal = c.normal;
    info.depth = -c.separation;
    info.normal_impulse = c.normal_impulse;
    info.friction_impulse = c.tangent_impulse1 * c.tangent1 + c.tangent_impulse2 * c.tangent2;
    info.restitution = c.restitution;
    info.friction = c.friction;
    next_contacts_.push_back(info);
  }
  std::sort(next_contacts_.begin(), next_contacts_.end(),
            [](const ContactInfo& x, const ContactInfo& y) { return sort_key(x) < sort_key(y); });
  contacts_.swap(next_contacts_);
  last_dt_ = dt;
}

std::size_t ContactSolver::write_back(std::vector<Body>& bodies) {
  std::size_t first_bad = all_finite;
  for (std::size_t s = 1; s < solver_bodies_.size(); ++s) {
    const SolverBody& sb = solver_bodies_[s];
    Body& body = bodies[sb.index];
    const Vec3 dv = sb.velocity - sb.start_velocity;
    const Vec3 dw = sb.angular_velocity - sb.start_angular_velocity;
    body.velocity += dv;
    body.angular_velocity += dw;
    if (!state_is_finite(body)) first_bad = std::min(first_bad, sb.index);
  }
  return first_bad;
}

std::size_t ContactSolver::solve_velocities(std::vector<Body>& bodies,
                                            const std::vector<Plane>& planes, const Vec3& gravity,
                                            double dt, ContactVelocities velocities) {
  find_contacts(bodies, planes, gravity, dt, velocities);
  for_each_manifold([&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) warm_start(constraints_[k], dt);
    if (end - begin > 1) seed_manifold(begin, end, false);
  });
  // Sweeps alternate direction (symmetric Gauss-Seidel), so no point of a symmetric contact,
  // like the four corners of a box landing flat, is always solved first.
  for (int sweep = 0; sweep < settings.iterations; ++sweep) {
    if (sweep % 2 == 0)
      for (Constraint& c : constraints_) solve_point(c);
    else
      for (auto c = constraints_.rbegin(); c != constraints_.rend(); ++c) solve_point(*c);
  }
  apply_restitution();
  store_results(dt);
  return write_back(bodies);
}

// ---- position correction ---------------------------------------------------------------------

// The two witness points of c at the bodies' present poses. A sphere's is its point along the
// normal, wherever it has rolled to (Box2D's b2PositionSolverManifold uses circles' centres).
void ContactSolver::witnesses(const std::vector<Body>& bodies, const Constraint& c, Vec3& pa,
                              Vec3& pb) const {
  const Body* a = c.a == no_body ? nullptr : &bodies[c.a];
  const Body& b = bodies[c.b];
  pa = c.radius_a > 0.0 ? Vec3(a->position + c.radius_a * c.normal)
       : a              ? to_world(*a, c.anchor_a)
                        : c.anchor_a;
  pb = c.radius_b > 0.0 ? Vec3(b.position - c.radius_b * c.normal) : to_world(b, c.anchor_b);
}

// Moves the bodies of c apart along its normal, at `point`, by the position impulse −C/K that
// changes their separation there by −C (C ≤ 0): positions and orientations only.
void ContactSolver::move_apart(std::vector<Body>& bodies, const Constraint& c, const Vec3& point,
                               double correction) {
  Body* a = c.a == no_body ? nullptr : &bodies[c.a];
  Body& b = bodies[c.b];
  const SolverBody& sa = solver_bodies_[c.slot_a];
  const SolverBody& sb = solver_bodies_[c.slot_b];
  const Vec3 r_a = a ? Vec3(point - a->position) : Vec3::Zero();
  const Vec3 r_b = point - b.position;
  const double k = inverse_effective_mass(sa, r_a, sb, r_b, c.normal);
  if (!(k > 0.0)) return;
  const Vec3 impulse = (-correction / k) * c.normal;
  if (a && !is_static(*a)) {
    a->position -= sa.inverse_mass * impulse;
    a->orientation = rotate_by(a->orientation, -(sa.inverse_inertia * r_a.cross(impulse)), 1.0);
  }
  if (!is_static(b)) {
    b.position += sb.inverse_mass * impulse;
    b.orientation = rotate_by(b.orientation, sb.inverse_inertia * r_b.cross(impulse), 1.0);
  }
}

// Box2D v2.4 b2ContactSolver::SolvePositionConstraints, in 3-D: each point's separation s from
// its witnesses at the present poses, C = clamp(β (s + slop), −max_correction, 0), and the
// position impulse −C/K along n; per manifold, first at the centroid with the mean
// separation, then per point Jacobi-style (see the header).
std::size_t ContactSolver::correct_positions(std::vector<Body>& bodies) {
  const double slop = settings.linear_slop;
  auto correction = [this, slop](double separation) {
    return std::clamp(settings.baumgarte * (separation + slop), -settings.max_correction, 0.0);
  };
  for (int sweep = 0; sweep < settings.position_iterations; ++sweep) {
    double min_separation = 0.0;
    for_each_manifold([&](std::size_t begin, std::size_t end) {
      Vec3 pa, pb;
      if (end - begin > 1) {
        Vec3 centroid = Vec3::Zero();
        double mean = 0.0;
        for (std::size_t k = begin; k < end; ++k) {
          witnesses(bodies, constraints_[k], pa, pb);
          centroid += 0.5 * (pa + pb), mean += constraints_[k].normal.dot(pb - pa);
        }
        const double count = static_cast<double>(end - begin);
        const double c = correction(mean / count);
        if (c < 0.0) move_apart(bodies, constraints_[begin], centroid / count, c);
      }
      // Then the points, Jacobi-style within the manifold: all measured at the same poses,
      // each moved by its share, so a symmetric manifold stays symmetric.
      const double share = 1.0 / static_cast<double>(end - begin);
      double corrections[max_manifold_points];
      Vec3 points[max_manifold_points];
      for (std::size_t k = begin; k < end; ++k) {
        witnesses(bodies, constraints_[k], pa, pb);
        const double separation = constraints_[k].normal.dot(pb - pa);
        min_separation = std::min(min_separation, separation);
        corrections[k - begin] = correction(separation);
        points[k - begin] = 0.5 * (pa + pb);
      }
      for (std::size_t k = begin; k < end; ++k)
        if (corrections[k - begin] < 0.0)
          move_apart(bodies, constraints_[k], points[k - begin], share * corrections[k - begin]);
    });
    if (min_separation >= -3.0 * slop) break;
  }
  std::size_t first_bad = all_finite;
  for (std::size_t s = 1; s < solver_bodies_.size(); ++s)
    if (!state_is_finite(bodies[solver_bodies_[s].index]))
      first_bad = std::min(first_bad, solver_bodies_[s].index);
  return first_bad;
}

// ---- bookkeeping -----------------------------------------------------------------------------

void ContactSolver::body_removed(std::size_t index) {
  auto involves = [index](const ContactInfo& c) { return c.a == index || c.b == index; };
  contacts_.erase(std::remove_if(contacts_.begin(), contacts_.end(), involves), contacts_.end());
  for (ContactInfo& c : contacts_) {
    if (c.a != no_body && c.a > index) --c.a;
    if (c.b > index) --c.b;
  }
  constraints_.clear();
  solver_bodies_.resize(1);
  std::fill(slot_of_.begin(), slot_of_.end(), 0);
}

void ContactSolver::save() {
  saved_contacts_ = contacts_;
  saved_dt_ = last_dt_;
}

void ContactSolver::restore() {
  contacts_ = saved_contacts_;
  last_dt_ = saved_dt_;
}

}  // namespace rigidlab
