#include "engine/body.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "engine/format.hpp"
#include "engine/inertia.hpp"

namespace rigidlab {
namespace {

// The tensor a static body reports: infinite about every axis, like its mass. Only the
// diagonal is infinite, so the off-diagonal zeros stay exact.
Mat3 infinite_inertia() {
  return Vec3::Constant(std::numeric_limits<double>::infinity()).asDiagonal();
}

}  // namespace

std::string mass_problem(double mass) {
  if (!std::isfinite(mass)) return "must be finite, got " + format_number(mass);
  if (!(mass > 0.0)) return "must be > 0, got " + format_number(mass);
  if (!std::isfinite(1.0 / mass))
    return "is too small: 1/mass overflows, got " + format_number(mass);
  return {};
}

Body make_body(double mass, const Mat3& inertia) {
  const std::string mass_rule = mass_problem(mass);
  if (!mass_rule.empty()) throw std::invalid_argument("mass " + mass_rule);
  if (!is_finite(inertia)) throw std::invalid_argument("inertia must be finite");
  const std::string problem = inertia_tensor_problem(inertia);
  if (!problem.empty()) throw std::invalid_argument("inertia is not a valid tensor: " + problem);
  Body b;
  b.mass = mass;
  b.inverse_mass = 1.0 / mass;
  // Symmetrise: the validator admits an asymmetry of 1e-9 relative, and an exactly symmetric
  // tensor keeps R I Rᵀ exactly symmetric, so the angular momentum I ω is frame-consistent.
  b.inertia = 0.5 * (inertia + inertia.transpose());
  // I⁻¹ = (I/s)⁻¹/s with s the power of two nearest the largest entry (so the scaling is
  // exact): the cofactor formula's determinant, a product of three moments, would underflow for
  // moments near 1e-110 (or overflow near 1e110) although the inverse itself is representable;
  // the validator ensured that 1/(smallest moment) is finite.
  const int exponent = std::ilogb(b.inertia.cwiseAbs().maxCoeff());
  const auto unscale = [exponent](double x) { return std::scalbn(x, -exponent); };
  b.inverse_inertia = Mat3(b.inertia.unaryExpr(unscale)).inverse().unaryExpr(unscale);
  b.inverse_inertia = 0.5 * (b.inverse_inertia + b.inverse_inertia.transpose());
  if (!is_finite(b.inverse_inertia))
    throw std::invalid_argument("inertia is too small: its inverse overflows");
  return b;
}

Body make_static_body() {
  Body b;
  make_static(b);
  return b;
}

void make_static(Body& b) {
  b.mass = std::numeric_limits<double>::infinity();
  b.inverse_mass = 0.0;
  b.inertia = infinite_inertia();
  b.inverse_inertia = Mat3::Zero();
  b.velocity = Vec3::Zero();
  b.angular_velocity = Vec3::Zero();
  b.force = Vec3::Zero();
  b.torque = Vec3::Zero();
}

Body make_sphere_body(double mass, double radius) {
  Body b = make_body(mass, inertia_solid_sphere(mass, radius));
  b.shape.kind = ShapeKind::sphere;
  b.shape.radius = radius;
  return b;
}

Body make_box_body(double mass, const Vec3& size) {
  Body b = make_body(mass, inertia_solid_box(mass, size));
  b.shape.kind = ShapeKind::box;
  b.shape.half_extents = 0.5 * size;
  return b;
}

// 002_* "Rotational Inertia": I' = A I₀ Aᵀ. A static body's infinite tensor is the same in
// every frame (and R ∞ Rᵀ would produce ∞ − ∞ = NaN off the diagonal).
Mat3 world_inertia(const Body& b) {
  if (is_static(b)) return b.inertia;
  const Mat3 r = rotation(b);
  return r * b.inertia * r.transpose();
}

// 002_* "Newton-Euler Equations": I⁻¹ = A I₀⁻¹ Aᵀ since A is orthonormal.
Mat3 inverse_world_inertia(const Body& b) {
  const Mat3 r = rotation(b);
  return r * b.inverse_inertia * r.transpose();
}

// 002_* "Newton-Euler Equations": f = Σ fᵢ, τ = Σ rᵢ × fᵢ.
void apply_force(Body& b, const Vec3& f, const Vec3& p_world) {
  if (is_static(b)) return;
  b.force += f;
  b.torque += (p_world - b.position).cross(f);
}

void apply_force(Body& b, const Vec3& f) {
  if (is_static(b)) return;
  b.force += f;
}

void apply_torque(Body& b, const Vec3& torque) {
  if (is_static(b)) return;
  b.torque += torque;
}

// 001_* "apply_impulse": Δv = j/m, Δω = I_world⁻¹ (r × j).
void apply_impulse(Body& b, const Vec3& j, const Vec3& p_world) {
  if (is_static(b)) return;
  b.velocity += b.inverse_mass * j;
  b.angular_velocity += inverse_world_inertia(b) * (p_world - b.position).cross(j);
}

void apply_impulse(Body& b, const Vec3& j) {
  if (is_static(b)) return;
  b.velocity += b.inverse_mass * j;
}

void apply_angular_impulse(Body& b, const Vec3& h) {
  if (is_static(b)) return;
  b.angular_velocity += inverse_world_inertia(b) * h;
}

// 002_* "Momentum and inertia": L = I ω with I in world axes.
Vec3 angular_momentum(const Body& b) {
  if (is_static(b)) return Vec3::Zero();
  return world_inertia(b) * b.angular_velocity;
}

// T = ½ m v·v + ½ ω·I ω. The rotational part is computed in the body frame (ω_b = Rᵀ ω) with
// the body tensor, which equals ω·(R I Rᵀ)ω without forming the world tensor.
double kinetic_energy(const Body& b) {
  if (is_static(b)) return 0.0;
  const Vec3 omega_body = b.orientation.conjugate() * b.angular_velocity;
  return 0.5 * b.mass * b.velocity.squaredNorm() +
         0.5 * omega_body.dot(b.inertia * omega_body);
}

}  // namespace rigidlab
