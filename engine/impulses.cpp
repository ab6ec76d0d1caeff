#include "engine/impulses.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <Eigen/Cholesky>

#include "engine/constraint_row.hpp"

namespace rigidlab {
namespace {

std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.14g", x);
  return buffer;
}

std::string format_vec3(const Vec3& v) {
  return "(" + number(v.x()) + ", " + number(v.y()) + ", " + number(v.z()) + ")";
}

// v/|v| without overflow or underflow in |v|² (scaled by the largest component first, as
// LAPACK's dnrm2): (1e300, 1e300, 0) is the direction (1, 1, 0)/√2. Zero for a zero vector.
Vec3 direction(const Vec3& v) {
  const double largest = v.cwiseAbs().maxCoeff();
  if (!(largest > 0.0)) return Vec3::Zero();
  const Vec3 scaled = v / largest;
  return scaled / scaled.norm();
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
  if (!std::isfinite(result.impulse) || !std::isfinite(result.velocity_a) ||
      !std::isfinite(result.velocity_b))
    throw std::invalid_argument("the impulse overflows: the velocities or 1/mass are too large");
  return result;
}

Mat3 inverse_mass_matrix(const Body& b, const Vec3& r1, const Vec3& r2) {
  if (is_static(b)) return Mat3::Zero();
  return b.inverse_mass * Mat3::Identity() - skew(r2) * inverse_world_inertia(b) * skew(r1);
}

// K = J W Jᵀ for the three point rows along the world axes (engine/constraint_row.hpp
// coupling: the engine's one J W Jᵀ). It equals M_a⁻¹(r_a, r_a) + M_b⁻¹(r_b, r_b) of 002_*
// "Inverse Mass Matrix" (inverse_mass_matrix above), which the tests check.
Mat3 contact_inverse_mass(const Body& a, const Body& b, const Vec3& point) {
  const Vec3 ra = point - a.position, rb = point - b.position;
  const Mat3 inverse_a = inverse_world_inertia(a), inverse_b = inverse_world_inertia(b);
  Jacobian rows[3];
  for (int k = 0; k < 3; ++k) rows[k] = point_jacobian(Vec3::Unit(k), ra, rb);
  Mat3 k;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      k(i, j) = coupling(rows[i], rows[j], a.inverse_mass, inverse_a, b.inverse_mass, inverse_b);
  return k;
}

double effective_mass(const Body& a, const Body& b, const Vec3& point, const Vec3& normal) {
  if (&a == &b) throw std::invalid_argument("a and b are the same body");
  if (!is_finite(normal) || !(normal.cwiseAbs().maxCoeff() > 0.0))
    throw std::invalid_argument("normal must be a finite non-zero vector");
  if (!is_finite(point)) throw std::invalid_argument("point must be finite");
  if (is_static(a) && is_static(b)) throw std::invalid_argument("both bodies are immovable");
  const Vec3 n = direction(normal);
  const Jacobian j = point_jacobian(n, point - a.position, point - b.position);
  const double jwj = coupling(j, j, a.inverse_mass, inverse_world_inertia(a), b.inverse_mass,
                              inverse_world_inertia(b));
  if (!std::isfinite(jwj) || !(jwj > 0.0))
    throw std::invalid_argument("point " + format_vec3(point) +
                                " is too far from the centres of mass: J W Jᵀ overflows");
  return 1.0 / jwj;
}

std::string contact_problem(const Body& a, const Body& b, const Contact& contact) {
  if (&a == &b) return "a and b are the same body";
  if (is_static(a) && is_static(b)) return "both bodies are immovable";
  if (!is_finite(contact.point)) return "point must be finite";
  if (!is_finite(contact.normal)) return "normal must be finite";
  if (!(contact.normal.cwiseAbs().maxCoeff() > 0.0)) return "normal must not be zero";
  std::string problem = restitution_problem(contact.restitution);
  if (!problem.empty()) return problem;
  if (!std::isfinite(contact.friction) || !(contact.friction >= 0.0))
    return "friction must be >= 0, got " + number(contact.friction);
  return "";
}

namespace {

// The largest s in [0, 1] for which ok(s) holds, given that ok(0) holds and that the set where
// it holds is an interval (the predicates below are convex sets met along a segment):
// bisection to the last bit, keeping the end where ok holds.
template <class Predicate>
double last_true(Predicate ok) {
  if (ok(1.0)) return 1.0;
  double low = 0.0, high = 1.0;
  for (int k = 0; k < 64 && high - low > 0.0; ++k) {
    const double middle = 0.5 * (low + high);
    if (middle <= low || middle >= high) break;
    (ok(middle) ? low : high) = middle;
  }
  return low;
}

// The change of kinetic energy of a contact impulse P (b gets P, a gets −P) at a point with
// relative velocity v: P·v + ½ P·K P (J).
double energy_change(const Vec3& impulse, const Vec3& v, const Mat3& k) {
  return impulse.dot(v) + 0.5 * impulse.dot(k * impulse);
}

// One phase of the impact (see the header): from relative velocity u, the impulse that brings
// the normal velocity to `target`, moved from the frictionless one toward the one that leaves
// the point at rest tangentially, as far as `allowed(total impulse)` holds.
template <class Allowed>
Vec3 phase_impulse(const Vec3& u, const Vec3& n, const Mat3& k, const Eigen::LLT<Mat3>& k_llt,
                   double target, const Vec3& before, Allowed allowed) {
  const Vec3 frictionless = ((target - n.dot(u)) / n.dot(k * n)) * n;
  const Vec3 sticking = k_llt.solve(target * n - u);
  const Vec3 step = sticking - frictionless;
  const double s = last_true([&](double x) { return allowed(before + frictionless + x * step); });
  return frictionless + s * step;
}

}  // namespace

ContactImpulse resolve_contact(Body& a, Body& b, const Contact& contact) {
  const std::string problem = contact_problem(a, b, contact);
  if (!problem.empty()) throw std::invalid_argument(problem);
  const Vec3& p = contact.point;
  const Vec3 n = direction(contact.normal);
  const Mat3 k = contact_inverse_mass(a, b, p);
  const Vec3 v = point_velocity(b, p) - point_velocity(a, p);
  const double vn = n.dot(v);
  ContactImpulse result;
  const auto too_far = [&p] {
    return std::invalid_argument("point " + format_vec3(p) +
                                 " is too far from the centres of mass: the impulse overflows");
  };
  if (!is_finite(k) || !std::isfinite(vn)) throw too_far();
  if (vn >= 0.0) return result;  // separating or resting: no impulse
  // K is symmetric positive definite when a body can move (m⁻¹E plus a positive semidefinite
  // rotational part), so the Cholesky factor exists.
  const Eigen::LLT<Mat3> k_llt(k);
  const double mu = contact.friction;
  auto in_cone = [mu, &n](const Vec3& impulse) {
    const double normal = n.dot(impulse);
    return normal >= 0.0 && (impulse - normal * n).norm() <= mu * normal;
  };
  const Vec3 compression = phase_impulse(v, n, k, k_llt, 0.0, Vec3::Zero(), in_cone);
  const Vec3 rest = v + k * compression;  // v_n = 0
  auto allowed = [&](const Vec3& total) {
    return in_cone(total) && energy_change(total, v, k) <= 0.0;
  };
  const Vec3 total = compression + phase_impulse(rest, n, k, k_llt, -contact.restitution * vn,
                                                 compression, allowed);
  Body new_a = a, new_b = b;
  apply_impulse(new_a, -total, p);
  apply_impulse(new_b, total, p);
  const bool finite = is_finite(total) && is_finite(new_a.velocity) &&
                      is_finite(new_a.angular_velocity) && is_finite(new_b.velocity) &&
                      is_finite(new_b.angular_velocity);
  if (!finite) throw too_far();
  a = new_a, b = new_b;
  result.normal_impulse = n.dot(total);
  result.friction_impulse = total - result.normal_impulse * n;
  return result;
}

}  // namespace rigidlab
