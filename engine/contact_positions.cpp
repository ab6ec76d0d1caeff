// The contact constraints, part 4: sequential_impulses' position correction after the
// integrator moved the bodies. See engine/contact_constraints.hpp.
#include <algorithm>

#include "engine/contact_helpers.hpp"
#include "engine/integrators.hpp"

namespace rigidlab {

using namespace contact_detail;

// The two witness points of c at the bodies' present poses. A sphere's is its point along the
// normal, wherever it has rolled to (Box2D's b2PositionSolverManifold uses circles' centres).
void ContactConstraints::witnesses(const std::vector<Body>& bodies, const Manifold& m,
                                   const Point& p, Vec3& pa, Vec3& pb) const {
  const Body* a = m.a == ground_ ? nullptr : &bodies[m.a];
  const Body& b = bodies[m.b];
  pa = m.radius_a > 0.0 ? Vec3(a->position + m.radius_a * m.normal)
       : a              ? to_world(*a, p.anchor_a)
                        : p.anchor_a;
  pb = m.radius_b > 0.0 ? Vec3(b.position - m.radius_b * m.normal) : to_world(b, p.anchor_b);
}

// Moves the bodies of m apart along its normal, at `point`, by the position impulse −C/K that
// changes their separation there by −C (C ≤ 0): positions and orientations only.
void ContactConstraints::move_apart(std::vector<Body>& bodies, const Manifold& m, const Point&,
                                    const Vec3& point, double correction) {
  Body* a = m.a == ground_ ? nullptr : &bodies[m.a];
  Body& b = bodies[m.b];
  const SolverBody& sa = solver_[m.a];
  const SolverBody& sb = solver_[m.b];
  const Vec3 r_a = a ? Vec3(point - a->position) : Vec3::Zero();
  const Vec3 r_b = point - b.position;
  const Jacobian j = point_jacobian(m.normal, r_a, r_b);
  const double k = coupling(j, j, sa, sb);
  if (!(k > 0.0)) return;
  const Vec3 impulse = (-correction / k) * m.normal;
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
std::size_t ContactConstraints::correct_positions(std::vector<Body>& bodies, StepPoll* poll) {
  const ContactSettings& settings = *settings_;
  auto correction = [&settings](double separation, double slop) {
    return std::clamp(settings.baumgarte * (separation + slop), -settings.max_correction, 0.0);
  };
  for (int sweep = 0; sweep < settings.position_iterations; ++sweep) {
    if (poll != nullptr) poll->tick(points_.size());
    bool deep = false;  // a point still sunk by more than three slops
    for (const Manifold& m : manifolds_) {
      const std::size_t begin = m.first, end = m.first + m.count;
      Vec3 pa, pb;
      if (end - begin > 1) {
        Vec3 centroid = Vec3::Zero();
        double mean = 0.0;
        for (std::size_t k = begin; k < end; ++k) {
          witnesses(bodies, m, points_[k], pa, pb);
          centroid += 0.5 * (pa + pb), mean += m.normal.dot(pb - pa);
        }
        const double count = static_cast<double>(end - begin);
        const double c = correction(mean / count, points_[begin].slop);
        if (c < 0.0) move_apart(bodies, m, points_[begin], centroid / count, c);
      }
      // Then the points, Jacobi-style within the manifold: all measured at the same poses,
      // each moved by its share, so a symmetric manifold stays symmetric.
      const double share = 1.0 / static_cast<double>(end - begin);
      double corrections[max_manifold_points];
      Vec3 points[max_manifold_points];
      for (std::size_t k = begin; k < end; ++k) {
        witnesses(bodies, m, points_[k], pa, pb);
        const double separation = m.normal.dot(pb - pa);
        deep = deep || separation < -3.0 * points_[k].slop;
        corrections[k - begin] = correction(separation, points_[k].slop);
        points[k - begin] = 0.5 * (pa + pb);
      }
      for (std::size_t k = begin; k < end; ++k)
        if (corrections[k - begin] < 0.0)
          move_apart(bodies, m, points_[k], points[k - begin], share * corrections[k - begin]);
    }
    if (!deep) break;
  }
  std::size_t first_bad = all_finite;
  for (const Manifold& m : manifolds_) {
    if (m.a != ground_ && !state_is_finite(bodies[m.a])) first_bad = std::min<std::size_t>(first_bad, m.a);
    if (!state_is_finite(bodies[m.b])) first_bad = std::min<std::size_t>(first_bad, m.b);
  }
  return first_bad;
}

}  // namespace rigidlab
