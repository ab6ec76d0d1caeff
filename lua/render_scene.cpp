#include "lua/render_scene.hpp"

#include <algorithm>
#include <cmath>

#include "engine/body.hpp"
#include "present/chart.hpp"

namespace rigidlab::lua {
namespace {

using present::short_number;  // "%.4g": enough digits to read a legend
constexpr auto number = short_number;

present::SceneBody scene_body(const Body& b) {
  present::SceneBody out;
  out.position = b.position;
  out.rotation = rotation(b);
  const std::string prefix = is_static(b) ? "static " : "";
  switch (b.shape.kind) {
    case ShapeKind::box:
      out.shape = present::BodyShape::box;
      out.half_extents = b.shape.half_extents;
      out.name = prefix + "box " + number(2 * b.shape.half_extents.x()) + "x" +
                 number(2 * b.shape.half_extents.y()) + "x" + number(2 * b.shape.half_extents.z());
      break;
    case ShapeKind::sphere:
      out.shape = present::BodyShape::sphere;
      out.radius = b.shape.radius;
      out.name = prefix + "sphere r " + number(b.shape.radius);
      break;
    case ShapeKind::none:
      out.name = prefix + "point mass";
      break;
  }
  return out;
}

// How far a body reaches from its COM (m); a point mass gets a tenth of `fallback`.
double reach(const Body& b, double fallback) {
  switch (b.shape.kind) {
    case ShapeKind::box: return b.shape.half_extents.norm();
    case ShapeKind::sphere: return b.shape.radius;
    case ShapeKind::none: break;
  }
  return 0.1 * fallback;
}

// The size of the scene (for point masses) and the median reach of its bodies: one body far
// larger than the rest does not make every arrow long.
double typical_reach(const std::vector<Body>& bodies) {
  if (bodies.empty()) return 1.0;
  Vec3 lo = bodies[0].position, hi = lo;
  for (const Body& b : bodies) {
    lo = lo.cwiseMin(b.position);
    hi = hi.cwiseMax(b.position);
  }
  const double extent = std::max((hi - lo).norm(), 1.0);
  std::vector<double> reaches;
  for (const Body& b : bodies) reaches.push_back(reach(b, extent));
  std::nth_element(reaches.begin(), reaches.begin() + reaches.size() / 2, reaches.end());
  const double median = reaches[reaches.size() / 2];
  return median > 0.0 && std::isfinite(median) ? median : 0.1 * extent;
}

// The scale that makes the longest of `values` `length` long (0 when all are zero).
double scale_for(const std::vector<Vec3>& values, double length, double& largest) {
  largest = 0.0;
  for (const Vec3& v : values)
    if (is_finite(v)) largest = std::max(largest, stable_norm(v));
  return largest > 0.0 && std::isfinite(largest) ? length / largest : 0.0;
}

void add_arrows(present::Scene& scene, present::Overlay kind, const std::vector<Body>& bodies,
                const std::vector<Vec3>& values, double scale) {
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (!is_static(bodies[i]) && is_finite(values[i]))
      scene.arrows.push_back(present::SceneArrow{kind, bodies[i].position, scale * values[i]});
}

void add_frames(present::Scene& scene, const std::vector<Body>& bodies, double typical) {
  for (const Body& b : bodies) {
    const Mat3 R = rotation(b);
    const double length = 1.3 * std::max(reach(b, 0.0), 0.5 * typical);
    const present::Overlay axes[3] = {present::Overlay::axis_x, present::Overlay::axis_y,
                                      present::Overlay::axis_z};
    for (int k = 0; k < 3; ++k)
      scene.arrows.push_back(present::SceneArrow{axes[k], b.position, length * R.col(k)});
  }
}

void add_ellipsoids(present::Scene& scene, const std::vector<Body>& bodies, double omega_scale,
                    double typical) {
  for (const Body& b : bodies) {
    if (is_static(b)) continue;
    const SymmetricEigen principal = symmetric_eigen(b.inertia);  // ascending moments
    const Vec3& I = principal.values;
    const double two_t = b.angular_velocity.dot(world_inertia(b) * b.angular_velocity);
    present::SceneEllipsoid e;
    e.center = b.position;
    e.axes = rotation(b) * principal.axes;
    if (omega_scale > 0.0 && two_t > 0.0 && std::isfinite(two_t)) {
      for (int k = 0; k < 3; ++k) e.semi_axes[k] = omega_scale * std::sqrt(two_t / I[k]);
    } else {  // at rest: xᵀ I x = const, the longest semi-axis (smallest moment) at the reach
      const double longest = std::max(reach(b, 0.0), 0.5 * typical);
      for (int k = 0; k < 3; ++k) e.semi_axes[k] = longest * std::sqrt(I[0] / I[k]);
    }
    if (e.semi_axes.allFinite()) scene.ellipsoids.push_back(e);
  }
}

void add_contacts(present::Scene& scene, const World& world, double typical) {
  std::vector<Vec3> impulses;
  for (const ContactInfo& c : world.contacts()) {
    scene.markers.push_back(present::SceneMarker{present::Overlay::contact, c.point});
    impulses.push_back(c.normal_impulse * c.normal + c.friction_impulse);
  }
  double largest = 0.0;
  const double scale = scale_for(impulses, typical, largest);
  for (std::size_t i = 0; i < impulses.size(); ++i)
    if (scale > 0.0 && impulses[i].norm() > 0.0)
      scene.arrows.push_back(present::SceneArrow{present::Overlay::impulse,
                                                 world.contacts()[i].point, scale * impulses[i]});
  if (largest > 0.0)
    scene.notes.push_back({present::Overlay::impulse, "(largest " + number(largest) + " N s)", ""});
}

// Each joint as document 000 draws a kinematic pair: a marker where it attaches, and lines
// from each body's COM to its attachment point (and between the two points, a rod's length
// for a distance joint), so a chain reads as a chain.
void add_joints(present::Scene& scene, const World& world) {
  const BodyStore& store = world.store();
  for (std::size_t i = 0; i < world.constraint_count(); ++i) {
    const Constraint& joint = world.constraint(i);
    if (!store.contains(joint.body_a())) continue;
    const Body& a = store.get(joint.body_a());
    const Body* b = joint.body_b().valid() && store.contains(joint.body_b())
                        ? &store.get(joint.body_b()) : nullptr;
    Vec3 on_a, on_b;
    joint.attachment_points(a, b, on_a, on_b);
    if (!on_a.allFinite() || !on_b.allFinite()) continue;
    std::vector<Vec3> line{a.position, on_a};
    if ((on_b - on_a).norm() > 0.0) line.push_back(on_b);
    if (b != nullptr) line.push_back(b->position);
    scene.curves.push_back(present::SceneCurve{present::Overlay::joint, line});
    scene.markers.push_back(present::SceneMarker{present::Overlay::joint, on_a});
    if ((on_b - on_a).norm() > 0.0)
      scene.markers.push_back(present::SceneMarker{present::Overlay::joint, on_b});
  }
}

}  // namespace

present::Scene scene_from_world(const World& world, const SceneRequest& request) {
  present::Scene scene;
  const std::vector<Body>& bodies = world.bodies();
  for (const Body& b : bodies) scene.bodies.push_back(scene_body(b));
  for (const Plane& p : world.planes()) scene.planes.push_back(present::ScenePlane{p.normal, p.offset});
  const double typical = typical_reach(bodies);
  std::vector<Vec3> omegas, moments;
  for (const Body& b : bodies) {
    omegas.push_back(is_static(b) ? Vec3::Zero() : b.angular_velocity);
    moments.push_back(is_static(b) ? Vec3::Zero() : Vec3(world_inertia(b) * b.angular_velocity));
  }
  double omega_max = 0.0, momentum_max = 0.0;
  const double omega_scale = scale_for(omegas, 1.5 * typical, omega_max);
  const double momentum_scale = scale_for(moments, 1.5 * typical, momentum_max);
  const std::string which = bodies.size() > 1 ? "largest " : "";
  if (request.frames) add_frames(scene, bodies, typical);
  if (request.ellipsoid) add_ellipsoids(scene, bodies, omega_scale, typical);
  if (request.omega) {
    add_arrows(scene, present::Overlay::omega, bodies, omegas, omega_scale);
    scene.notes.push_back({present::Overlay::omega, "(" + which + number(omega_max) + " rad/s)", ""});
  }
  if (request.momentum) {
    add_arrows(scene, present::Overlay::momentum, bodies, moments, momentum_scale);
    scene.notes.push_back({present::Overlay::momentum,
                           "(" + which + number(momentum_max) + " kg m²/s)",
                           "(" + which + number(momentum_max) + " kg m^2/s)"});
  }
  if (request.ellipsoid && omega_scale > 0.0)
    scene.notes.push_back({present::Overlay::ellipsoid, "ωᵀIω = 2T: the tip of ω stays on it",
                           "w.I.w = 2T: the tip of w stays on it"});
  if (request.contacts) add_contacts(scene, world, typical);
  if (request.joints) add_joints(scene, world);
  for (const std::vector<Vec3>& trail : request.trails)
    if (trail.size() > 1) scene.curves.push_back(present::SceneCurve{present::Overlay::trail, trail});
  return scene;
}

present::Scene scene_from_articulation(Articulation& art, const SceneRequest& request) {
  present::Scene scene;
  const ArticulationModel& model = art.model();
  const int n = model.link_count();
  std::vector<Vec3> joints(n), coms(n), omegas(n);
  std::vector<double> lengths;
  for (int i = 0; i < n; ++i) {
    joints[i] = art.link_position(i);
    coms[i] = art.link_com(i);
    omegas[i] = art.angular_velocity(i);
  }
  for (int i = 0; i < n; ++i) {
    const LinkSpec& spec = model.links()[i].spec;
    present::SceneBody link;
    link.shape = present::BodyShape::segments;
    link.position = coms[i];
    link.rotation = art.link_rotation(i);
    link.segments.emplace_back(joints[i], coms[i]);
    for (int j = 0; j < n; ++j)
      if (model.links()[j].spec.parent == i) link.segments.emplace_back(joints[i], joints[j]);
    for (const auto& [from, to] : link.segments) lengths.push_back((to - from).norm());
    link.name = spec.name.empty() ? "link" : "link " + spec.name;
    scene.bodies.push_back(link);
    if (request.joints && spec.joint != JointType::fixed)
      scene.markers.push_back(present::SceneMarker{present::Overlay::joint, joints[i]});
  }
  if (request.joints && !model.free_base())
    scene.markers.push_back(present::SceneMarker{present::Overlay::joint, model.base_position()});
  std::sort(lengths.begin(), lengths.end());
  const double typical = lengths.empty() || !(lengths[lengths.size() / 2] > 0.0)
                             ? 0.5 : lengths[lengths.size() / 2];
  if (request.frames)
    for (int i = 0; i < n; ++i) {
      const Mat3 R = art.link_rotation(i);
      const present::Overlay axes[3] = {present::Overlay::axis_x, present::Overlay::axis_y,
                                        present::Overlay::axis_z};
      for (int k = 0; k < 3; ++k)
        scene.arrows.push_back(present::SceneArrow{axes[k], joints[i], 0.5 * typical * R.col(k)});
    }
  if (request.omega) {
    double largest = 0.0;
    const double scale = scale_for(omegas, typical, largest);
    for (int i = 0; i < n; ++i)
      if (is_finite(omegas[i]))
        scene.arrows.push_back(present::SceneArrow{present::Overlay::omega, coms[i], scale * omegas[i]});
    scene.notes.push_back({present::Overlay::omega,
                           "(" + std::string(n > 1 ? "largest " : "") + number(largest) + " rad/s)", ""});
  }
  for (const std::vector<Vec3>& trail : request.trails)
    if (trail.size() > 1) scene.curves.push_back(present::SceneCurve{present::Overlay::trail, trail});
  return scene;
}

}  // namespace rigidlab::lua
