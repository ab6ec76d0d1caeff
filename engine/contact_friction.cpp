// The contact constraints, part 5: patch friction. See engine/contact_constraints.hpp.
//
// A flat manifold (two to four points of a face or an edge, no sphere) gets its friction as one
// patch, as PhysX's patch friction: two tangent rows at the centre of its points and one twist
// row about the normal, solved together in each sweep as a 3 x 3 block (λ' = λ − K⁻¹ J v, K =
// J W Jᵀ), within
//   |λ_tangent| ≤ μ Σ λn,ᵢ  (the Coulomb disk of the patch's whole load) and
//   |λ_twist| ≤ μ Σ λn,ᵢ dᵢ  (the torque the points' disks give at their distances dᵢ from the
//                            centre, all slipping around it),
// instead of two rows per point, each within μ of its own point's load. Why, measured on the
// pyramid of 210 unit boxes (60 Hz, one substep, 10 sweeps): with a row pair per point, 2-9 %
// of its points sat on their friction cone at rest (a lightly loaded corner of a box that the
// block normal solve unloaded cannot hold the shear the others leave to it), the eight rows
// of a face hold its three tangential degrees of freedom redundantly and Gauss-Seidel
// converged slowly on the twist about the vertical, and the pyramid's top crept 4.5 mm in 10 s
// and 9.7 mm in 20 s (soft_step; sequential_impulses 4.7 and 79 mm, the pyramid swaying
// ever wider), in directions that changed with the solve order (7.4 and 87 mm with the boxes
// added in reverse). The block reaches the patch's three targets at once, and the patch holds
// while its whole load can hold it.
// The points keep their own friction impulses for the reports and the warm start: the patch's
// impulse (F, τ) is spread over them as fᵢ = wᵢ F + τ' (n × dᵢ)/Σ dⱼ², wᵢ = λn,ᵢ/Σ λn (the
// share of the load: a patch sliding at μ gives each point μ λn,ᵢ) and τ' = τ − Σ wᵢ n·(dᵢ ×
// F) (the same force and torque about the centre), and gathered back from the points it
// continues in the next step.
#include <algorithm>
#include <cmath>

#include "engine/contact_constraints.hpp"
#include "engine/contact_helpers.hpp"

namespace rigidlab {

using namespace contact_detail;

// The patch's rows at the arms the points have now (warm_start, which then sets its impulses
// from the points, or positions_moved after the bodies moved, which keeps them).
void ContactConstraints::prepare_patch(std::size_t manifold, const SolverBody& a,
                                       const SolverBody& b) {
  Manifold& m = manifolds_[manifold];
  Patch& patch = patches_[manifold];
  m.patch = false;
  if (!may_be_patch(m)) return;
  Vec3 r_a = Vec3::Zero(), r_b = Vec3::Zero();
  for (std::uint32_t k = m.first; k < m.first + m.count; ++k)
    r_a += points_[k].r_a, r_b += points_[k].r_b;
  r_a /= m.count, r_b /= m.count;
  patch.spread = 0.0;
  for (std::uint32_t i = 0; i < m.count; ++i) {
    patch.distance[i] = in_plane(points_[m.first + i].r_b - r_b, m.normal).norm();
    patch.spread += patch.distance[i] * patch.distance[i];
  }
  if (!(patch.spread > 1e-12) || !std::isfinite(patch.spread)) return;
  Vec3 t1, t2;
  tangent_basis(m.normal, t1, t2);
  patch.rows[0].jacobian = point_jacobian(t1, r_a, r_b);
  patch.rows[1].jacobian = point_jacobian(t2, r_a, r_b);
  patch.rows[2].jacobian = angular_jacobian(m.normal);
  Eigen::Matrix3d k;
  for (int j = 0; j < 3; ++j) {
    prepare_row(patch.rows[j], a, b);
    for (int i = 0; i < 3; ++i)
      k(i, j) = coupling_weighted(patch.rows[i].jacobian, patch.rows[j].jacobian, a.inverse_mass,
                                  patch.rows[j].weighted_a, b.inverse_mass,
                                  patch.rows[j].weighted_b);
  }
  Eigen::Matrix3d inverse;
  bool invertible = false;
  const double trace = k.trace();  // the threshold's scale: a product, not std::pow's call
  k.computeInverseWithCheck(inverse, invertible, 1e-12 * (trace * trace) * trace);
  if (!invertible || !inverse.allFinite()) return;
  patch.inverse = inverse;
  patch.r_a = r_a, patch.r_b = r_b;
  m.patch = true;
}

void ContactConstraints::prepare_friction(const Manifold& m, const SolverBody& a,
                                          const SolverBody& b) {
  for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
    const Point& p = points_[k];
    for (ConstraintRow* row : {&frictions_[k].tangent1, &frictions_[k].tangent2}) {
      row->jacobian = point_jacobian(row->jacobian.linear, p.r_a, p.r_b);
      prepare_row(*row, a, b);
    }
  }
}

// The warm start: the points' impulses (warm_start set them from the points they continue)
// gathered into the patch's force and torque about its centre, then applied.
void ContactConstraints::warm_start_patch(std::size_t manifold) {
  const Manifold& m = manifolds_[manifold];
  Patch& patch = patches_[manifold];
  Vec3 force = Vec3::Zero();
  double torque = 0.0;
  for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
    FrictionRows& p = frictions_[k];
    const Vec3 f = p.tangent1.impulse * p.tangent1.jacobian.linear +
                   p.tangent2.impulse * p.tangent2.jacobian.linear;
    force += f;
    torque += m.normal.dot(in_plane(points_[k].r_b - patch.r_b, m.normal).cross(f));
    p.tangent1.impulse = p.tangent2.impulse = 0.0;
  }
  SolverBody& a = solver_[m.a];
  SolverBody& b = solver_[m.b];
  const double impulses[3] = {force.dot(patch.rows[0].jacobian.linear),
                              force.dot(patch.rows[1].jacobian.linear), torque};
  for (int i = 0; i < 3; ++i) {
    patch.rows[i].impulse = impulses[i];
    apply_row(patch.rows[i], a, b, impulses[i]);
  }
}

// One block update of the patch within its limits (see the top), from the points' present
// normal impulses.
void ContactConstraints::solve_patch(std::size_t manifold) {
  const Manifold& m = manifolds_[manifold];
  Patch& patch = patches_[manifold];
  double load = 0.0, lever = 0.0;
  for (std::uint32_t i = 0; i < m.count; ++i) {
    const double normal = normals_[m.first + i].impulse;
    load += normal;
    lever += normal * patch.distance[i];
  }
  ConstraintRow* rows = patch.rows;
  const Eigen::Vector3d old(rows[0].impulse, rows[1].impulse, rows[2].impulse);
  // No load and no friction impulse: nothing changes (side by side boxes of a pyramid).
  if (load == 0.0 && old.isZero()) return;
  SolverBody& a = solver_[m.a];
  SolverBody& b = solver_[m.b];
  // The velocities in locals (as solve_friction): row_velocity and apply_row term for term,
  // without reading back what the previous row's update stored.
  Vec3 va = a.velocity, wa = a.angular_velocity, vb = b.velocity, wb = b.angular_velocity;
  // The twist row has no linear part (angular_jacobian): J v and the update of its row have
  // no linear terms (they were sums of products with zeros, which change no velocity).
  const Vec3 dv = vb - va;
  const Jacobian& twist = rows[2].jacobian;
  const Eigen::Vector3d velocity(jacobian_velocity(rows[0].jacobian, dv, wa, wb),
                                 jacobian_velocity(rows[1].jacobian, dv, wa, wb),
                                 angular_velocity_along(twist.angular_a, twist.angular_b, wa, wb));
  Eigen::Vector3d next = old - patch.inverse * velocity;
  const double limit = m.friction * load, twist_limit = m.friction * lever;
  const double length_squared = next[0] * next[0] + next[1] * next[1];
  if (!(length_squared <= limit * limit)) {  // sliding: on the disk's edge
    const double length = std::sqrt(length_squared);
    const double scale = length > 0.0 && std::isfinite(length) ? limit / length : 0.0;
    next[0] *= scale, next[1] *= scale;
  }
  next[2] = std::clamp(next[2], -twist_limit, twist_limit);
  const double ma = a.inverse_mass, mb = b.inverse_mass;
  for (int i = 0; i < 3; ++i) {
    const double lambda = next[i] - old[i];
    if (i < 2) {
      va -= (ma * lambda) * rows[i].jacobian.linear;
      vb += (mb * lambda) * rows[i].jacobian.linear;
    }
    wa -= lambda * rows[i].weighted_a;
    wb += lambda * rows[i].weighted_b;
    rows[i].impulse = next[i];
  }
  a.velocity = va, a.angular_velocity = wa;
  b.velocity = vb, b.angular_velocity = wb;
}

// The patch's impulse back on its points (see the top), for the reports and the next step.
void ContactConstraints::spread_patch(std::size_t manifold) {
  const Manifold& m = manifolds_[manifold];
  const Patch& patch = patches_[manifold];
  if (!m.patch) return;
  const Vec3 force = patch.rows[0].impulse * patch.rows[0].jacobian.linear +
                     patch.rows[1].impulse * patch.rows[1].jacobian.linear;
  double load = 0.0;
  for (std::uint32_t k = m.first; k < m.first + m.count; ++k) load += normals_[k].impulse;
  double share[max_manifold_points];
  double torque = patch.rows[2].impulse;  // less what the force's shares turn about the centre
  for (std::uint32_t i = 0; i < m.count; ++i) {
    const Point& p = points_[m.first + i];
    share[i] = load > 0.0 ? normals_[m.first + i].impulse / load : 1.0 / m.count;
    torque -= share[i] * m.normal.dot(in_plane(p.r_b - patch.r_b, m.normal).cross(force));
  }
  for (std::uint32_t i = 0; i < m.count; ++i) {
    const Point& p = points_[m.first + i];
    FrictionRows& rows = frictions_[m.first + i];
    const Vec3 f = share[i] * force + (torque / patch.spread) *
                                          m.normal.cross(in_plane(p.r_b - patch.r_b, m.normal));
    rows.tangent1.impulse = f.dot(rows.tangent1.jacobian.linear);
    rows.tangent2.impulse = f.dot(rows.tangent2.jacobian.linear);
  }
}

}  // namespace rigidlab
