#include "engine/time_of_impact.hpp"

#include <cmath>

namespace rigidlab {
namespace {

constexpr int max_iterations = 64;

// Conservative advancement on a distance bound `distance(t)` that shrinks at most at `speed`.
template <class Distance>
double advance_to_contact(Distance distance, double speed, double dt, double tolerance) {
  double t = 0.0;
  for (int k = 0; k < max_iterations; ++k) {
    const double d = distance(t);
    if (!(d > tolerance)) return t;  // touching (or a NaN: let the caller look)
    if (!(speed > 0.0) || d >= speed * (dt - t)) return -1.0;  // cannot close it in time
    // Aim a little short of contact (Box2D's b2TimeOfImpact targets the tolerance band
    // too), so that the last advance lands inside the band instead of creeping up to it.
    t += (d - 0.5 * tolerance) / speed;
  }
  return t;
}

// The pose after time t as the shape's distances see it: a sphere's (or no shape's) distance
// depends on its centre alone, so its rotation is left as it was (no sine and cosine per
// iteration); every other shape turns as advance() turns it.
Pose advance_shape(const Shape& shape, const Pose& pose, const Motion& motion, double t) {
  if (shape.kind == ShapeKind::sphere || shape.kind == ShapeKind::none)
    return {pose.position + t * motion.velocity, pose.rotation};
  return advance(pose, motion, t);
}

}  // namespace

Pose advance(const Pose& pose, const Motion& motion, double t) {
  Pose p;
  p.position = pose.position + t * motion.velocity;
  const double angle = motion.angular_velocity.norm() * t;
  p.rotation = angle > 0.0 ? Mat3(Eigen::AngleAxisd(angle, motion.angular_velocity.normalized()) *
                                  pose.rotation)
                           : pose.rotation;
  return p;
}

double time_of_impact(const Shape& a, const Pose& pose_a, const Motion& motion_a, const Shape& b,
                      const Pose& pose_b, const Motion& motion_b, double dt, double tolerance) {
  const double speed = (motion_b.velocity - motion_a.velocity).norm() +
                       motion_a.angular_velocity.norm() * bounding_radius(a) +
                       motion_b.angular_velocity.norm() * bounding_radius(b);
  auto distance = [&](double t) {
    return separation(a, advance_shape(a, pose_a, motion_a, t), b,
                      advance_shape(b, pose_b, motion_b, t));
  };
  return advance_to_contact(distance, speed, dt, tolerance);
}

double time_of_impact(const Shape& shape, const Pose& pose, const Motion& motion,
                      const Plane& plane, double dt, double tolerance) {
  // Only the motion along the normal brings a shape closer to a plane.
  const double speed = std::max(0.0, -plane.normal.dot(motion.velocity)) +
                       motion.angular_velocity.norm() * bounding_radius(shape);
  auto distance = [&](double t) {
    return separation(shape, advance_shape(shape, pose, motion, t), plane);
  };
  return advance_to_contact(distance, speed, dt, tolerance);
}

}  // namespace rigidlab
