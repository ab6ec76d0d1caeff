// The contact solver, part 2: warm starting, the sequential-impulse sweeps, restitution and
// the bookkeeping between steps. See engine/contact_solver.hpp.
#include "engine/contact_solver.hpp"

#include <algorithm>
#include <cmath>

#include "engine/contact_helpers.hpp"
#include "engine/format.hpp"
#include "engine/integrators.hpp"

namespace rigidlab {

using namespace contact_detail;

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
  prepare_restitution(c, found, dt);
  if (found == nullptr) return;
  // Impulses scale with the step: a resting contact carries m g Δt.
  const double scale = last_dt_ > 0.0 ? dt / last_dt_ : 1.0;
  c.normal_impulse = scale * found->normal_impulse;
  c.tangent_impulse1 = scale * found->friction_impulse.dot(c.tangent1);
  c.tangent_impulse2 = scale * found->friction_impulse.dot(c.tangent2);
  apply_impulse(c, c.normal_impulse * c.normal + c.tangent_impulse1 * c.tangent1 +
                       c.tangent_impulse2 * c.tangent2);
}

// Whether c bounces in this step and to what normal velocity (see the header): a point that
// landed in the previous step (and so touches, up to rounding) bounces on the impact velocity
// it landed with; a point that touches or overlaps (s ≤ 0) on its own; a point with a gap
// lands first, even a tiny one, so that every bounce starts from the surface. Only when
// e > 0 and the impact is faster than the threshold. The target reflects the parabola of the
// positions at the surface: v_n = −e w + a_n Δt/2, never below the contact's own bound −s/Δt
// (a bounce too small to lift off leaves the point resting).
void ContactSolver::prepare_restitution(Constraint& c, const ContactInfo* previous,
                                        double dt) const {
  c.bounces = false;
  const bool landed = previous != nullptr && previous->impact < 0.0 &&
                      c.separation <= touch_tolerance();
  if (landed) c.impact = previous->impact;
  else if (c.separation > 0.0) return;
  if (!(c.restitution > 0.0 && -c.impact > settings.restitution_threshold)) return;
  c.target = std::max(-c.restitution * c.impact + 0.5 * c.acceleration * dt, -c.bias);
  c.bounces = true;
}

void ContactSolver::apply_impulse(Constraint& c, const Vec3& impulse) {
  SolverBody& a = solver_bodies_[c.slot_a];
  SolverBody& b = solver_bodies_[c.slot_b];
  a.velocity -= a.inverse_mass * impulse;
  a.angular_velocity -= a.inverse_inertia * c.r_a.cross(impulse);
  b.velocity += b.inverse_mass * impulse;
  b.angular_velocity += b.inverse_inertia * c.r_b.cross(impulse);
}

// The coarse correction of a manifold (see the header): the normal impulse that brings its
// centroid to the mean target velocity (−bias, or the restitution targets), shared equally by
// its points.
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
    target += target_of(c, restitution) / count;
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
  auto apply = [&](const Vec3& impulse) { apply_impulse(c, impulse); };
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
}

// The restitution pass (see the header): every point again along its normal, to its bounce
// target where it bounces and to its own bound −s/Δt elsewhere, Gauss-Seidel with the
// accumulated normal impulses (≥ 0) of the sweeps. Whole manifolds that bounce first get
// their share (a box landing flat leaves without a spin). Nothing to do when no point bounces.
void ContactSolver::apply_restitution() {
  if (std::none_of(constraints_.begin(), constraints_.end(),
                   [](const Constraint& c) { return c.bounces; }))
    return;
  for_each_manifold([&](std::size_t begin, std::size_t end) {
    if (end - begin > 1 && std::all_of(constraints_.begin() + begin, constraints_.begin() + end,
                                       [](const Constraint& c) { return c.bounces; }))
      seed_manifold(begin, end, true);
  });
  for (int sweep = 0; sweep < settings.iterations; ++sweep) {
    if (poll != nullptr) poll->tick(constraints_.size());
    double largest_change = 0.0;
    for (Constraint& c : constraints_) {
      SolverBody& a = solver_bodies_[c.slot_a];
      SolverBody& b = solver_bodies_[c.slot_b];
      const double vn = c.normal.dot(point_velocity_of(b, c.r_b) - point_velocity_of(a, c.r_a));
      const double total =
          std::max(c.normal_impulse - c.normal_mass * (vn - target_of(c, true)), 0.0);
      largest_change = std::max(largest_change, std::abs(total - c.normal_impulse));
      apply_impulse(c, (total - c.normal_impulse) * c.normal);
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
    // A speculative point that the sweeps brought to the surface: it landed, and bounces in
    // the next step with the velocity it met the surface with.
    if (c.landed) info.impact = c.impact;
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
    if (poll != nullptr) poll->tick(constraints_.size());
    if (sweep % 2 == 0)
      for (Constraint& c : constraints_) solve_point(c);
    else
      for (auto c = constraints_.rbegin(); c != constraints_.rend(); ++c) solve_point(*c);
  }
  for (Constraint& c : constraints_)
    c.landed = !c.bounces && c.separation > 0.0 && c.normal_impulse > 0.0 && c.impact < 0.0;
  apply_restitution();
  store_results(dt);
  return write_back(bodies);
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
