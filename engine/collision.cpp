#include "engine/collision.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace rigidlab {
namespace {

std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.14g", x);
  return buffer;
}

// e in [0, 1]: e = 0 perfectly inelastic, e = 1 elastic (001_* Appendix C).
std::string restitution_problem(double e) {
  if (!(e >= 0.0 && e <= 1.0)) return "restitution must be in [0, 1], got " + number(e);
  return "";
}

}  // namespace

Impulse1D impulse_1d(double inverse_mass_a, double velocity_a, double inverse_mass_b,
                     double velocity_b, double restitution) {
  if (!(inverse_mass_a >= 0.0 && inverse_mass_b >= 0.0) || !std::isfinite(inverse_mass_a) ||
      !std::isfinite(inverse_mass_b))
    throw std::invalid_argument("inverse masses must be finite and >= 0");
  if (inverse_mass_a + inverse_mass_b == 0.0)
    throw std::invalid_argument("both bodies are immovable");
  const std::string problem = restitution_problem(restitution);
  if (!problem.empty()) throw std::invalid_argument(problem);
  Impulse1D result;
  result.impulse =
      -(1.0 + restitution) * (velocity_b - velocity_a) / (inverse_mass_a + inverse_mass_b);
  result.velocity_a = velocity_a - result.impulse * inverse_mass_a;
  result.velocity_b = velocity_b + result.impulse * inverse_mass_b;
  return result;
}

Mat3 inverse_mass_matrix(const Body& b, const Vec3& r1, const Vec3& r2) {
  if (is_static(b)) return Mat3::Zero();
  return b.inverse_mass * Mat3::Identity() - skew(r2) * inverse_world_inertia(b) * skew(r1);
}

Mat3 contact_inverse_mass(const Body& a, const Body& b, const Vec3& point) {
  const Vec3 ra = point - a.position, rb = point - b.position;
  return inverse_mass_matrix(a, ra, ra) + inverse_mass_matrix(b, rb, rb);
}

double effective_mass(const Body& a, const Body& b, const Vec3& point, const Vec3& normal) {
  if (&a == &b) throw std::invalid_argument("a and b are the same body");
  const double length = normal.norm();
  if (!(length > 0.0) || !std::isfinite(length))
    throw std::invalid_argument("normal must be a finite non-zero vector");
  const Vec3 n = normal / length;
  const double jwj = n.dot(contact_inverse_mass(a, b, point) * n);
  if (!(jwj > 0.0)) throw std::invalid_argument("both bodies are immovable");
  return 1.0 / jwj;
}

std::string contact_problem(const Body& a, const Body& b, const Contact& contact) {
  if (&a == &b) return "a and b are the same body";
  if (is_static(a) && is_static(b)) return "both bodies are immovable";
  if (!is_finite(contact.point)) return "point must be finite";
  if (!is_finite(contact.normal)) return "normal must be finite";
  if (!(contact.normal.norm() > 0.0)) return "normal must not be zero";
  std::string problem = restitution_problem(contact.restitution);
  if (!problem.empty()) return problem;
  if (!std::isfinite(contact.friction) || !(contact.friction >= 0.0))
    return "friction must be >= 0, got " + number(contact.friction);
  return "";
}

ContactImpulse resolve_contact(Body& a, Body& b, const Contact& contact) {
  const std::string problem = contact_problem(a, b, contact);
  if (!problem.empty()) throw std::invalid_argument(problem);
  const Vec3& p = contact.point;
  const Vec3 n = contact.normal.normalized();
  const Mat3 k = contact_inverse_mass(a, b, p);
  ContactImpulse result;
  const double approach = n.dot(point_velocity(b, p) - point_velocity(a, p));
  if (approach >= 0.0) return result;  // separating or resting: no impulse

  // 001_* Appendix C: J = −(1 + e) v_rel·n / (n·K n); n·K n is the API's denominator.
  result.normal_impulse = -(1.0 + contact.restitution) * approach / n.dot(k * n);
  apply_impulse(a, -result.normal_impulse * n, p);
  apply_impulse(b, result.normal_impulse * n, p);

  // 001_* "Collisions": friction along the tangential relative velocity, with the effective
  // mass along that direction; Coulomb's bound μ J, and never more than stops the sliding.
  const Vec3 relative = point_velocity(b, p) - point_velocity(a, p);
  const Vec3 tangential = relative - n.dot(relative) * n;
  const double slip = tangential.norm();
  if (contact.friction > 0.0 && slip > 0.0) {
    const Vec3 t = tangential / slip;
    const double stopping = slip / t.dot(k * t);
    result.friction_impulse = -std::min(contact.friction * result.normal_impulse, stopping) * t;
    apply_impulse(a, -result.friction_impulse, p);
    apply_impulse(b, result.friction_impulse, p);
  }
  return result;
}

}  // namespace rigidlab
