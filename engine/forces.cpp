#include "engine/forces.hpp"

#include <cmath>

#include "engine/format.hpp"

namespace rigidlab {
namespace {

std::string nonnegative_problem(double x, const char* what) {
  if (!std::isfinite(x)) return std::string(what) + " must be finite, got " + format_number(x);
  if (!(x >= 0.0)) return std::string(what) + " must be >= 0, got " + format_number(x);
  return {};
}

// Velocity of the end of the spring on body b at world point p, or 0 for an anchor.
Vec3 end_velocity(const Body* b, const Vec3& p) {
  return b == nullptr ? Vec3::Zero() : point_velocity(*b, p);
}

}  // namespace

std::string spring_problem(const Spring& s) {
  for (const auto& [value, what] : {std::pair{s.stiffness, "stiffness"},
                                    std::pair{s.damping, "damping"},
                                    std::pair{s.rest_length, "rest length"}}) {
    std::string problem = nonnegative_problem(value, what);
    if (!problem.empty()) return problem;
  }
  if (!is_finite(s.a_point) || !is_finite(s.b_point) || !is_finite(s.anchor))
    return "attachment points must be finite";
  if (s.a == s.b) return "a spring needs two different bodies";
  return {};
}

std::string drag_problem(const Drag& d) {
  std::string problem = nonnegative_problem(d.linear, "linear drag");
  return problem.empty() ? nonnegative_problem(d.angular, "angular drag") : problem;
}

Vec3 spring_end_a(const Body& a, const Spring& s) { return to_world(a, s.a_point); }

Vec3 spring_end_b(const Body* b, const Spring& s) {
  return b == nullptr ? s.anchor : to_world(*b, s.b_point);
}

// Baraff & Witkin 2001, "Particle System Dynamics" 4.3 (damped spring), sign for body a.
Vec3 spring_force(const Body& a, const Body* b, const Spring& s) {
  const Vec3 pa = spring_end_a(a, s);
  const Vec3 pb = spring_end_b(b, s);
  const Vec3 d = pb - pa;
  if (is_zero(d)) return Vec3::Zero();
  const double length = stable_norm(d);
  const Vec3 u = unit(d);
  const Vec3 relative_velocity = end_velocity(b, pb) - end_velocity(&a, pa);
  return (s.stiffness * (length - s.rest_length) + s.damping * relative_velocity.dot(u)) * u;
}

void apply_spring(Body& a, Body* b, const Spring& s) {
  const Vec3 f = spring_force(a, b, s);
  apply_force(a, f, spring_end_a(a, s));
  if (b != nullptr) apply_force(*b, -f, spring_end_b(b, s));
}

double spring_potential_energy(const Body& a, const Body* b, const Spring& s) {
  const double stretch = stable_norm(spring_end_b(b, s) - spring_end_a(a, s)) - s.rest_length;
  return 0.5 * s.stiffness * stretch * stretch;
}

void apply_drag(Body& b, const Drag& d) {
  apply_force(b, -d.linear * b.velocity);
  apply_torque(b, -d.angular * b.angular_velocity);
}

}  // namespace rigidlab
