// The contact solver, part 2: warm starting, the sequential-impulse sweeps, restitution and
// the bookkeeping between steps. See engine/contact_solver.hpp.
#include "engine/contact_solver.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

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
                 {"match_distance", s.match_distance}};
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

// Gauss-Seidel updates of a point (Catto 2005; Box2D v2.4 SolveVelocityConstraints): its
// friction within the Coulomb disk of the current normal impulse, and its normal impulse
// toward the target (−bias, or the bounce in the restitution pass), accumulated and ≥ 0.
void ContactSolver::solve_friction(Constraint& c) {
  if (!(c.friction > 0.0)) return;
  SolverBody& a = solver_bodies_[c.slot_a];
  SolverBody& b = solver_bodies_[c.slot_b];
  const Vec3 dv = point_velocity_of(b, c.r_b) - point_velocity_of(a, c.r_a);
  double t1 = c.tangent_impulse1 - c.tangent_mass1 * dv.dot(c.tangent1);
  double t2 = c.tangent_impulse2 - c.tangent_mass2 * dv.dot(c.tangent2);
  const double limit = c.friction * c.normal_impulse;
  const double length = std::hypot(t1, t2);
  if (length > limit) {  // slipping: on the edge of the cone, against the slip
    const double scale = length > 0.0 ? limit / length : 0.0;
    t1 *= scale, t2 *= scale;
  }
  apply_impulse(c, (t1 - c.tangent_impulse1) * c.tangent1 + (t2 - c.tangent_impulse2) * c.tangent2);
  c.tangent_impulse1 = t1, c.tangent_impulse2 = t2;
}

double ContactSolver::solve_normal(Constraint& c, bool restitution) {
  SolverBody& a = solver_bodies_[c.slot_a];
  SolverBody& b = solver_bodies_[c.slot_b];
  const double vn = c.normal.dot(point_velocity_of(b, c.r_b) - point_velocity_of(a, c.r_a));
  const double total =
      std::max(c.normal_impulse - c.normal_mass * (vn - target_of(c, restitution)), 0.0);
  const double change = total - c.normal_impulse;
  apply_impulse(c, change * c.normal);
  c.normal_impulse = total;
  return std::abs(change);
}

// The block solve of one manifold's normal impulses (see the header): the accumulated impulses
// λ' = P λ − K⁺ (v_n − target), K the manifold's J W Jᵀ, K⁺ its pseudo-inverse and P = K⁺K,
// which reaches every point's target at once when it can (the least-squares impulses when the
// points are redundant, as the four corners of a face: a symmetric load gets equal impulses).
// When some λ' would be negative the points are solved one by one instead. Returns the largest
// change of an impulse.
double ContactSolver::solve_normals(std::size_t manifold, bool restitution) {
  const std::size_t begin = manifold_begin_[manifold];
  const std::size_t end = manifold + 1 < manifold_begin_.size() ? manifold_begin_[manifold + 1]
                                                                : constraints_.size();
  const int count = static_cast<int>(end - begin);
  double largest = 0.0;
  if (count > 1 && blocks_[manifold].usable) {
    const Block& block = blocks_[manifold];
    Vec4 old = Vec4::Zero(), residual = Vec4::Zero();
    for (int i = 0; i < count; ++i) {
      const Constraint& c = constraints_[begin + i];
      const SolverBody& a = solver_bodies_[c.slot_a];
      const SolverBody& b = solver_bodies_[c.slot_b];
      old[i] = c.normal_impulse;
      residual[i] = c.normal.dot(point_velocity_of(b, c.r_b) - point_velocity_of(a, c.r_a)) -
                    target_of(c, restitution);
    }
    const Vec4 next = block.projector * old - block.inverse * residual;
    if ((next.head(count).array() >= 0.0).all()) {
      for (int i = 0; i < count; ++i) {
        Constraint& c = constraints_[begin + i];
        apply_impulse(c, (next[i] - old[i]) * c.normal);
        c.normal_impulse = next[i];
        largest = std::max(largest, std::abs(next[i] - old[i]));
      }
      return largest;
    }
  }
  for (std::size_t k = begin; k < end; ++k)
    largest = std::max(largest, solve_normal(constraints_[k], restitution));
  return largest;
}

// K = J W Jᵀ of each manifold's normal constraints (001_* Appendix D for each pair of points:
// K_ij = m_a⁻¹ + m_b⁻¹ + (r_ai×n)·I_a⁻¹(r_aj×n) + (r_bi×n)·I_b⁻¹(r_bj×n)), its
// pseudo-inverse from the eigen-decomposition (eigenvalues below 1e-9 of the largest count
// as 0: four coplanar points have only three independent normal motions) and P = K⁺K.
void ContactSolver::prepare_blocks() {
  blocks_.resize(manifold_begin_.size());
  for (std::size_t m = 0; m < manifold_begin_.size(); ++m) {
    const std::size_t begin = manifold_begin_[m];
    const std::size_t end = m + 1 < manifold_begin_.size() ? manifold_begin_[m + 1]
                                                           : constraints_.size();
    const int count = static_cast<int>(end - begin);
    Block& block = blocks_[m];
    block.usable = false;
    if (count < 2) continue;
    Mat4 k = Mat4::Identity();  // unused rows and columns: identity, decoupled
    for (int i = 0; i < count; ++i)
      for (int j = 0; j < count; ++j) {
        const Constraint& ci = constraints_[begin + i];
        const Constraint& cj = constraints_[begin + j];
        const SolverBody& a = solver_bodies_[ci.slot_a];
        const SolverBody& b = solver_bodies_[ci.slot_b];
        const Vec3& n = ci.normal;
        k(i, j) = a.inverse_mass + b.inverse_mass +
                  ci.r_a.cross(n).dot(a.inverse_inertia * cj.r_a.cross(n)) +
                  ci.r_b.cross(n).dot(b.inverse_inertia * cj.r_b.cross(n));
      }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(k);
    if (eigen.info() != Eigen::Success) continue;
    const double largest = eigen.eigenvalues().maxCoeff();
    if (!(largest > 0.0) || !std::isfinite(largest)) continue;
    Mat4 inverse = Mat4::Zero();
    for (int e = 0; e < 4; ++e) {
      const double value = eigen.eigenvalues()[e];
      if (value > 1e-9 * largest)
        inverse += (eigen.eigenvectors().col(e) / value) * eigen.eigenvectors().col(e).transpose();
    }
    for (int i = count; i < 4; ++i) inverse(i, i) = 0.0, k(i, i) = 0.0;
    block.inverse = inverse;
    block.projector = inverse * k;
    block.usable = true;
  }
}

// The restitution pass (see the header): every point again along its normal, to its bounce
// target where it bounces and to its own bound −s/Δt elsewhere, Gauss-Seidel with the
// accumulated normal impulses (≥ 0) of the sweeps. Whole manifolds that bounce first get
// their share (a box landing flat leaves without a spin). Nothing to do when no point bounces.
void ContactSolver::apply_restitution() {
  if (std::none_of(constraints_.begin(), constraints_.end(),
                   [](const Constraint& c) { return c.bounces; }))
    return;
  for (int sweep = 0; sweep < settings.iterations; ++sweep) {
    if (poll != nullptr) poll->tick(constraints_.size());
    double largest_change = 0.0;
    for (std::size_t m = 0; m < manifold_begin_.size(); ++m)
      largest_change = std::max(largest_change, solve_normals(m, true));
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
  for (Constraint& c : constraints_) warm_start(c, dt);
  prepare_blocks();
  // Sweeps alternate direction (symmetric Gauss-Seidel over the manifolds): per manifold the
  // friction of each point, then its normal impulses as a block.
  const std::size_t manifolds = manifold_begin_.size();
  for (int sweep = 0; sweep < settings.iterations; ++sweep) {
    if (poll != nullptr) poll->tick(constraints_.size());
    for (std::size_t k = 0; k < manifolds; ++k) {
      const std::size_t m = sweep % 2 == 0 ? k : manifolds - 1 - k;
      for_manifold(m, [&](Constraint& c) { solve_friction(c); });
      solve_normals(m, false);
    }
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
