// The contact solver, part 3: position correction after the integrator moved the bodies.
// See engine/contact_solver.hpp.
#include <algorithm>

#include "engine/contact_helpers.hpp"
#include "engine/contact_solver.hpp"
#include "engine/integrators.hpp"

namespace rigidlab {

using namespace contact_detail;

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
// its witnesses at the present poses, C = clamp(β (s + slop), −max_correction, 0) with the
// point's own slop (see add_manifold), and the
// position impulse −C/K along n; per manifold, first at the centroid with the mean
// separation, then per point Jacobi-style (see the header).
std::size_t ContactSolver::correct_positions(std::vector<Body>& bodies) {
  auto correction = [this](double separation, double slop) {
    return std::clamp(settings.baumgarte * (separation + slop), -settings.max_correction, 0.0);
  };
  for (int sweep = 0; sweep < settings.position_iterations; ++sweep) {
    if (poll != nullptr) poll->tick(constraints_.size());
    bool deep = false;  // a point still sunk by more than three slops
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
        const double c = correction(mean / count, constraints_[begin].slop);
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
        deep = deep || separation < -3.0 * constraints_[k].slop;
        corrections[k - begin] = correction(separation, constraints_[k].slop);
        points[k - begin] = 0.5 * (pa + pb);
      }
      for (std::size_t k = begin; k < end; ++k)
        if (corrections[k - begin] < 0.0)
          move_apart(bodies, constraints_[k], points[k - begin], share * corrections[k - begin]);
    });
    if (!deep) break;
  }
  std::size_t first_bad = all_finite;
  for (std::size_t s = 1; s < solver_bodies_.size(); ++s)
    if (!state_is_finite(bodies[solver_bodies_[s].index]))
      first_bad = std::min(first_bad, solver_bodies_[s].index);
  return first_bad;
}

}  // namespace rigidlab
