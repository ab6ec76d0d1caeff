// The contact constraints, part 1: finding the contacts of a step (the candidate pairs of the
// broad phase, engine/contact_pairs.hpp; the narrow phase, engine/narrow_phase.hpp;
// speculative contacts and their time of impact) and turning each point into rows.
// See engine/contact_constraints.hpp.
#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/contact_helpers.hpp"
#include "engine/integrators.hpp"
#include "engine/time_of_impact.hpp"

namespace rigidlab {

using namespace contact_detail;

namespace {

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

void ContactConstraints::find(const std::vector<Body>& bodies, const std::vector<BodyId>& ids,
                              const std::vector<Plane>& planes, const SolverBody* solver,
                              const Acceleration* acceleration, const ContactSettings& settings,
                              double h) {
  settings_ = &settings;
  h_ = h;
  // The largest gap at which a point counts as touching (m): a point that landed at the end of
  // the last step sits at gap 0 up to rounding, and conservative advancement stops this close.
  touch_tolerance_ = std::max(0.1 * settings.linear_slop, 1e-6);
  ground_ = bodies.size();
  found_with_ = solver;
  acceleration_ = acceleration;
  ids_ = &ids;
  manifolds_.clear();
  points_.clear();
  normals_.clear();
  frictions_.clear();
  velocity_rows_.ready = push_rows_.ready = relax_rows_.ready = false;
  pairs_.update(bodies, ids, solver, h, settings.speculative_distance);
  // The planes first, body by body, then the pairs in the order of their ids
  // (engine/contact_pairs.hpp): the order depends on the ids only.
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    if (b.shape.kind == ShapeKind::none || is_static(b)) continue;
    const double margin = settings.speculative_distance + pairs_.sweep(i);
    for (std::size_t k = 0; k < planes.size(); ++k) {
      if (signed_distance(planes[k], b.position) - pairs_.radius(i) > margin) continue;
      const rigidlab::Manifold m = collide_shape_plane(b.shape, pose_of(b), planes[k], margin);
      if (m.count > 0) add_pair(bodies, m, no_body, i, k, &planes[k]);
    }
  }
  for (const BodyPair& pair : pairs_.pairs()) {
    const Body& body_a = bodies[pair.a];
    const Body& body_b = bodies[pair.b];
    const double margin =
        settings.speculative_distance + pairs_.sweep(pair.a) + pairs_.sweep(pair.b);
    // The bounding spheres first: cheaper than the narrow phase, and most pairs of fat boxes
    // are farther apart than that.
    const double reach = pairs_.radius(pair.a) + pairs_.radius(pair.b) + margin;
    if ((body_b.position - body_a.position).squaredNorm() > reach * reach) continue;
    const rigidlab::Manifold m =
        collide_shapes(body_a.shape, pose_of(body_a), body_b.shape, pose_of(body_b), margin);
    if (m.count > 0) add_pair(bodies, m, pair.a, pair.b, no_plane, nullptr);
  }
  blocks_.resize(manifolds_.size());  // made when first needed (block_usable)
}

// Which contact a pair gets (see the header, "Speculative contacts"): the manifold at the start
// of the step when a point touches; when all its points have gaps, the points within
// speculative_distance if the bodies cannot meet in the step anyway (bounded by how fast they
// close along the normal, spin included), else the manifold at the time of impact, or nothing
// when they miss each other.
void ContactConstraints::add_pair(const std::vector<Body>& bodies, const rigidlab::Manifold& m,
                                  std::size_t a, std::size_t b, std::size_t plane,
                                  const Plane* plane_material) {
  const double dt = h_;
  const Body* body_a = a == no_body ? nullptr : &bodies[a];
  const Body& body_b = bodies[b];
  const Pose pose_a = body_a ? pose_of(*body_a) : Pose{}, pose_b = pose_of(body_b);
  auto add = [&](const rigidlab::Manifold& manifold, double toi, const Pose& at_a,
                 const Pose& at_b) {
    add_manifold(bodies, manifold, a, b, plane, plane_material, toi, at_a, at_b);
  };
  double gap = std::numeric_limits<double>::infinity();
  for (int k = 0; k < m.count; ++k) gap = std::min(gap, -m.points[k].depth);
  if (gap <= touch_tolerance()) return add(m, 0.0, pose_a, pose_b);
  const SolverBody& sa = found_with_[a == no_body ? ground_ : a];
  const SolverBody& sb = found_with_[b];
  const Motion motion_a{sa.velocity, sa.angular_velocity}, motion_b{sb.velocity, sb.angular_velocity};
  const double radius_a = body_a ? bounding_radius(body_a->shape) : 0.0;
  const double closing = -m.normal.dot(sb.velocity - sa.velocity) +
                         sa.angular_velocity.norm() * radius_a +
                         sb.angular_velocity.norm() * bounding_radius(body_b.shape);
  if (gap - closing * dt > 0.0) {  // they stay apart along the normal: keep the near points
    rigidlab::Manifold near = m;
    near.count = 0;
    for (int k = 0; k < m.count; ++k)
      if (-m.points[k].depth <= settings_->speculative_distance)
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
      settings_->speculative_distance + tolerance + std::min(speed * (dt - toi), max_sweep);
  const rigidlab::Manifold hit = body_a ? collide_shapes(body_a->shape, at_a, body_b.shape, at_b, margin)
                              : collide_shape_plane(body_b.shape, at_b, *plane_material, margin);
  if (hit.count > 0) add(hit, toi, at_a, at_b);
}

// Two spheres: the contact along the line of their centres at the start of the step, the arms
// along it through the centres, at one point midway between the surfaces, the gap the exact
// distance of the surfaces. Central impulses at one point: a frictionless contact never spins
// them and their angular momentum is kept. (The time of impact only says whether they meet;
// its point would give the arms a sideways part, and a frictionless bounce a spin.)
void ContactConstraints::central_sphere_point(Manifold& m, Point& p, const Vec3& centre_a,
                                              const Vec3& centre_b) const {
  const Vec3 centres = centre_b - centre_a;
  const double length = centres.norm();
  if (!(length > 0.0)) return;  // concentric: keep what the narrow phase chose
  m.normal = m.start_normal = centres / length;
  const double from_a = m.radius_a + 0.5 * (length - m.radius_a - m.radius_b);
  p.r_a = from_a * m.normal;
  p.r_b = (from_a - length) * m.normal;
  p.separation = length - m.radius_a - m.radius_b;
}

// One manifold of points: offsets (lever arms at the poses where the manifold was found),
// rows and effective masses (001_* Appendix D), the approach velocity before the solve and the
// gap along the normal at the start of the step.
void ContactConstraints::add_manifold(const std::vector<Body>& bodies, const rigidlab::Manifold& m,
                                      std::size_t a, std::size_t b, std::size_t plane,
                                      const Plane* plane_material, double toi,
                                      const Pose& pose_a, const Pose& pose_b) {
  const Body* body_a = a == no_body ? nullptr : &bodies[a];
  const Body& body_b = bodies[b];
  Manifold c{};
  c.a = static_cast<std::uint32_t>(a == no_body ? ground_ : a);
  c.b = static_cast<std::uint32_t>(b);
  c.first = static_cast<std::uint32_t>(points_.size());
  c.count = static_cast<std::uint32_t>(m.count);
  c.id_a = body_a ? (*ids_)[a] : no_body_id;
  c.id_b = (*ids_)[b];
  c.plane = plane;
  c.normal = c.start_normal = m.normal;
  c.radius_a = body_a && body_a->shape.kind == ShapeKind::sphere ? body_a->shape.radius : 0.0;
  c.radius_b = body_b.shape.kind == ShapeKind::sphere ? body_b.shape.radius : 0.0;
  c.restitution = mix_restitution(body_a ? body_a->restitution : plane_material->restitution,
                                  body_b.restitution);
  c.friction =
      mix_friction(body_a ? body_a->friction : plane_material->friction, body_b.friction);
  const SolverBody& sa = found_with_[c.a];
  const SolverBody& sb = found_with_[c.b];
  // Box2D v3 makes contacts with static bodies twice as stiff (b2PrepareContactsTask): the
  // ground then gives way less than a pile on it.
  const bool on_static = sa.inverse_mass == 0.0 || sb.inverse_mass == 0.0;
  c.softness = make_soft((on_static ? 2.0 : 1.0) * settings_->contact_hertz,
                         settings_->contact_damping_ratio, h_);
  const double size_a = body_a ? smallest_dimension(body_a->shape)
                               : std::numeric_limits<double>::infinity();
  const double size_b = smallest_dimension(body_b.shape);
  // The lever arms: one world point for both bodies at their present poses, so the pair's
  // linear and angular momentum are kept exactly. At an impact found at τ > 0 the bodies touch
  // at p when they have moved by u τ; the point taken is p − τ (m_a⁻¹u_a + m_b⁻¹u_b)
  // /(m_a⁻¹ + m_b⁻¹), which is p as the lighter body sees it (exactly, against a plane or a
  // static body: a fast ball meeting a floor gets the lever R), the difference of their
  // displacements going to the heavier one.
  const double weight_a = sa.inverse_mass / (sa.inverse_mass + sb.inverse_mass);
  const Vec3 shift = toi * (weight_a * sa.velocity + (1.0 - weight_a) * sb.velocity);
  // A manifold that may hold its friction as a patch (prepare_patch) leaves its points'
  // friction rows unprepared until they are needed (prepare_friction): their directions only.
  const bool patch = may_be_patch(c);
  for (int k = 0; k < m.count; ++k) {
    const ContactPoint& found = m.points[k];
    // Made in place and not zeroed first (see Point): every field is set below.
    const auto index = static_cast<std::uint32_t>(points_.size());
    Point& p = points_.emplace_back();
    FrictionRows& f = frictions_.emplace_back();
    NormalRow& normal = normals_.emplace_back();
    normal.impulse = normal.push_impulse = normal.relax_cap = 0.0;
    p.end_separation = p.restitution_impulse = p.round_impulse = p.target = 0.0;
    p.separation = 0.0;  // central_sphere_point keeps it for concentric spheres
    p.flags = 0;
    p.turned = false;
    p.feature = found.feature;
    p.point = found.point;
    // Witness points (engine/narrow_phase.hpp): on a at point − n g/2, on b at point + n g/2,
    // stored in body coordinates of the poses they were found at.
    const double gap = -found.depth;
    const Vec3 witness_a = found.point - 0.5 * gap * c.normal;
    const Vec3 witness_b = found.point + 0.5 * gap * c.normal;
    p.anchor_a = body_a ? Vec3(pose_a.rotation.transpose() * (witness_a - pose_a.position))
                        : witness_a;
    p.anchor_b = pose_b.rotation.transpose() * (witness_b - pose_b.position);
    const Vec3 point = found.point - shift;
    p.r_a = body_a ? Vec3(point - body_a->position) : Vec3::Zero();
    p.r_b = point - body_b.position;
    // A sphere that gets its exact lever arm gets it along the normal, without rounding: a
    // frictionless contact then never spins it.
    if (weight_a == 0.0 && c.radius_b > 0.0) p.r_b = -c.radius_b * c.normal;
    if (weight_a == 1.0 && c.radius_a > 0.0) p.r_a = c.radius_a * c.normal;
    const bool spheres = c.radius_a > 0.0 && c.radius_b > 0.0;
    if (spheres) central_sphere_point(c, p, body_a->position, body_b.position);
    p.start_r_a = p.r_a, p.start_r_b = p.r_b;
    const Vec3 relative = point_velocity_of(sb, p.r_b) - point_velocity_of(sa, p.r_a);
    // The gap at the start of the step: found at τ, it closed at the rate −v_n since.
    if (!spheres) p.separation = gap - toi * c.normal.dot(relative);
    p.approach = c.normal.dot(relative);
    Vec3 t1, t2;
    friction_directions(c.normal, relative - p.approach * c.normal, t1, t2);
    prepare_normal(index, c.normal, p.r_a, p.r_b, sa, sb);
    if (patch) {  // only the directions are read (warm start, store) until prepare_friction
      f.tangent1.jacobian.linear = t1;
      f.tangent2.jacobian.linear = t2;
    } else {
      f.tangent1.jacobian = point_jacobian(t1, p.r_a, p.r_b);
      f.tangent2.jacobian = point_jacobian(t2, p.r_a, p.r_b);
      prepare_row(f.tangent1, sa, sb);
      prepare_row(f.tangent2, sa, sb);
    }
    // The overlap position correction leaves alone: linear_slop, but at most 1 % of the
    // smaller body (a 0.1 m cube would otherwise rest 5 mm, 5 % of its height, deep).
    p.slop = std::min(settings_->linear_slop, slop_fraction * std::min(size_a, size_b));
  }
  manifolds_.push_back(c);
}

}  // namespace rigidlab
