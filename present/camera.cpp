#include "present/camera.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace rigidlab::present {
namespace {

constexpr double pi = 3.14159265358979323846;

bool finite(const Point3& p) { return p.allFinite(); }

}  // namespace

std::string camera_problem(const Camera& c) {
  if (!finite(c.eye) || !finite(c.target) || !finite(c.up) || !std::isfinite(c.fov))
    return "must be finite";
  const Point3 sight = c.target - c.eye;
  if (!(sight.norm() > 0.0)) return "eye and target must differ";
  if (!(c.up.norm() > 0.0)) return "up must not be zero";
  if (sight.normalized().cross(c.up.normalized()).norm() < 1e-6)
    return "up must not be parallel to the line from eye to target";
  if (!(c.fov >= 1.0 && c.fov <= 170.0)) return "fov must be from 1 to 170 degrees";
  return "";
}

void scene_bounds(const Scene& scene, Point3& center, double& radius) {
  std::vector<std::pair<Point3, double>> spheres;
  for (const SceneBody& b : scene.bodies) {
    const double r = b.shape == BodyShape::box      ? b.half_extents.norm()
                     : b.shape == BodyShape::sphere ? b.radius
                                                    : 0.0;
    spheres.emplace_back(b.position, r);
    for (const auto& [from, to] : b.segments) {
      spheres.emplace_back(from, 0.0);
      spheres.emplace_back(to, 0.0);
    }
  }
  // An arrow counts as the sphere it sweeps as it turns, so the framing does not follow its
  // direction from frame to frame.
  for (const SceneArrow& a : scene.arrows) spheres.emplace_back(a.origin, a.vector.norm());
  for (const SceneEllipsoid& e : scene.ellipsoids) spheres.emplace_back(e.center, e.semi_axes.maxCoeff());
  for (const SceneMarker& m : scene.markers) spheres.emplace_back(m.position, 0.0);
  for (const SceneCurve& c : scene.curves)
    for (const Point3& p : c.points) spheres.emplace_back(p, 0.0);
  spheres.erase(std::remove_if(spheres.begin(), spheres.end(),
                               [](const auto& s) { return !finite(s.first) || !std::isfinite(s.second); }),
                spheres.end());
  if (spheres.empty()) {
    center = Point3::Zero();
    radius = 0.0;
    return;
  }
  Point3 lo = spheres[0].first, hi = lo;
  for (const auto& [c, r] : spheres) {
    lo = lo.cwiseMin(c - Point3::Constant(r));
    hi = hi.cwiseMax(c + Point3::Constant(r));
  }
  center = 0.5 * (lo + hi);
  radius = 0.0;
  for (const auto& [c, r] : spheres) radius = std::max(radius, (c - center).norm() + r);
}

Camera fit_camera(const Scene& scene, double fov, int columns, int rows, double cell_aspect) {
  Point3 center;
  double radius;
  scene_bounds(scene, center, radius);
  if (!(radius > 0.0) || !std::isfinite(radius)) radius = 1.0;
  const double azimuth = 30 * pi / 180, elevation = 20 * pi / 180;
  const Point3 direction(std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                         std::cos(azimuth) * std::cos(elevation));
  const double half_v = fov * pi / 360;
  const double frame_aspect = columns / (rows * cell_aspect);  // width over height
  const double half_h = std::atan(std::tan(half_v) * frame_aspect);
  const double distance = 1.1 * radius / std::sin(std::min(half_v, half_h));
  Camera camera;
  camera.target = center;
  camera.eye = center + distance * direction;
  camera.up = Point3::UnitY();
  camera.fov = fov;
  return camera;
}

Camera orbit(const Camera& camera, double azimuth, double elevation) {
  const Point3 up = camera.up.normalized();
  const Point3 offset = camera.eye - camera.target;
  const double distance = offset.norm();
  // Spherical coordinates of the eye about the target, with `up` as the pole.
  const double height = std::clamp(offset.normalized().dot(up), -1.0, 1.0);
  double lift = std::asin(height) + elevation;
  const double limit = 85 * pi / 180;
  lift = std::clamp(lift, -limit, limit);
  Point3 flat = offset - offset.dot(up) * up;
  if (flat.norm() < 1e-12 * distance)  // looking along up: any horizontal direction will do
    flat = up.cross(std::fabs(up.x()) < 0.9 ? Point3::UnitX() : Point3::UnitZ());
  const Point3 toward = Eigen::AngleAxisd(azimuth, up) * flat.normalized();
  Camera out = camera;
  out.eye = camera.target + distance * (std::cos(lift) * toward + std::sin(lift) * up);
  return out;
}

Projection::Projection(const Camera& camera, int dots_x, int dots_y, double dot_aspect)
    : eye_(camera.eye) {
  forward_ = (camera.target - camera.eye).normalized();
  right_ = forward_.cross(camera.up).normalized();
  up_ = right_.cross(forward_);
  focal_y_ = 0.5 * dots_y / std::tan(camera.fov * pi / 360);
  focal_x_ = focal_y_ * dot_aspect;  // a dot is dot_aspect times taller than wide
  center_x_ = 0.5 * (dots_x - 1);
  center_y_ = 0.5 * (dots_y - 1);
  near_ = std::max(1e-9, 1e-3 * (camera.target - camera.eye).norm());
}

bool Projection::point(const Point3& p, double& x, double& y) const {
  const Point3 d = p - eye_;
  const double z = d.dot(forward_);
  if (!(z >= near_)) return false;
  x = center_x_ + focal_x_ * d.dot(right_) / z;
  y = center_y_ - focal_y_ * d.dot(up_) / z;
  return std::isfinite(x) && std::isfinite(y);
}

bool Projection::segment(Point3 a, Point3 b, double& x0, double& y0, double& x1,
                         double& y1) const {
  const double za = depth(a), zb = depth(b);
  if (!(za >= near_) && !(zb >= near_)) return false;
  if (za < near_) a += (near_ - za) / (zb - za) * (b - a);
  else if (zb < near_) b += (near_ - zb) / (za - zb) * (a - b);
  return point(a, x0, y0) && point(b, x1, y1);
}

}  // namespace rigidlab::present
