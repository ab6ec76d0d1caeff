// The unit of work of the constraint solver: one scalar constraint row between two solver
// bodies, in the manner of Jolt's AxisConstraintPart (Jacobian, effective mass, accumulated
// impulse, clamp, apply). Contact normals and friction directions are rows; so are the rows of
// a joint (engine/constraint.hpp): linear or angular, equality, one-sided (limits), soft
// (springs) or bounded (motors).
//
// A row constrains the velocity J v of its two bodies a and b, with the Jacobian
//   J = [−linear, −angular_a, linear, angular_b]   (acting on (v_a, ω_a, v_b, ω_b)),
//   J v = linear·(v_b − v_a) + angular_b·ω_b − angular_a·ω_a.
// A contact at lever arms r_a, r_b with normal n has linear = n, angular_x = r_x × n (so J v is
// the normal relative velocity of the contact point, n·(v_b + ω_b × r_b − v_a − ω_a × r_a));
// an angular row about an axis k has linear = 0 and angular_a = angular_b = k.
// An impulse λ along the row gives b the impulse linear·λ and the angular impulse angular_b·λ,
// and a their opposites (001_* Appendix D: P = Jᵀ λ).
//
// The effective mass (001_* Appendix D) is 1/(J W Jᵀ), W the block-diagonal inverse mass
// (m_a⁻¹ E, I_a⁻¹, m_b⁻¹ E, I_b⁻¹, world frame). coupling_parts() below is the one place in
// the engine where J W Jᵀ is written: the solver's rows, the contacts' normal rows and
// manifold block matrices, the friction patches and collide.effective_mass / collide.resolve
// (engine/impulses.hpp) all reach it through coupling() and its variants.
//
// Soft rows (E. Catto, "Soft Step", Solver2D notes and Box2D v3's b2MakeSoft; E. Catto, "Soft
// Constraints", GDC 2011): the velocity constraint J v + β C = 0 is replaced by
//   J v' + β C + γ λ' = 0,
// which is a damped spring (stiffness ω², damping ratio ζ, per unit effective mass) integrated
// with implicit Euler over the substep h; make_soft turns (hertz, ζ, h) into the three
// coefficients of the impulse update below (biasRate = β, and massScale/impulseScale for γ).
// Rigid rows are Softness{0, 1, 0}.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/math.hpp"

namespace rigidlab {

// A body as the solver sees it: the velocities being solved, its inverse mass properties in
// the world frame, and how far it has moved in the current substep (Box2D v3's b2BodyState).
// Static bodies and planes have inverse mass 0 and never change.
// Layout: what the sweeps read for every row (the velocities and the inverse mass; the rows
// carry I⁻¹ Jᵀ themselves) is the first 56 bytes, and the struct starts on a cache line, so a
// row touches one line of each body instead of two or three (settle/4096 streams its bodies
// from L3: bench/contacts_bench.cpp).
struct alignas(64) SolverBody {
  Vec3 velocity = Vec3::Zero();          // m/s, world
  Vec3 angular_velocity = Vec3::Zero();  // rad/s, world
  double inverse_mass = 0.0;             // 1/kg
  Mat3 inverse_inertia = Mat3::Zero();   // 1/(kg m²), world: R I⁻¹ Rᵀ
  Vec3 delta_position = Vec3::Zero();    // m, moved in this substep
  Vec3 delta_rotation = Vec3::Zero();    // rad, rotation vector turned in this substep
};

// The free acceleration of a body over the substep (what it would do without constraints):
// m/s² and rad/s², world. Written by the integrator's velocity stage; the contacts use it for
// the impact velocity and the bounce (engine/contact_constraints.hpp, "Restitution").
struct Acceleration {
  Vec3 linear = Vec3::Zero();
  Vec3 angular = Vec3::Zero();
};

// The row's Jacobian (see above).
struct Jacobian {
  Vec3 linear = Vec3::Zero();     // on b (a gets −linear); unitless for a direction
  Vec3 angular_a = Vec3::Zero();  // m for a lever arm r_a × n, unitless for an axis
  Vec3 angular_b = Vec3::Zero();
};

// The Jacobian of the point constraint along unit direction d at lever arms r_a, r_b.
inline Jacobian point_jacobian(const Vec3& d, const Vec3& r_a, const Vec3& r_b) {
  return {d, r_a.cross(d), r_b.cross(d)};
}
// The Jacobian of a relative rotation row about unit axis k (ω_b − ω_a)·k.
inline Jacobian angular_jacobian(const Vec3& k) { return {Vec3::Zero(), k, k}; }

// J_i W J_jᵀ of two rows on the same two bodies (1/kg, or 1/(kg m) and 1/(kg m²) for angular
// rows): 001_* Appendix D,
//   m_a⁻¹ l_i·l_j + (A_a,i)·I_a⁻¹(A_a,j) + m_b⁻¹ l_i·l_j + (A_b,i)·I_b⁻¹(A_b,j).
// With i = j it is the inverse of the row's effective mass; a manifold's K matrix and the
// 3 x 3 inverse mass matrix of a contact point are made of these entries.
// The same with row j's angular parts already weighted (weighted_a = I_a⁻¹ angular_a, as a
// prepared ConstraintRow holds them): no 3 x 3 products for the rows of a step's contacts.
// The same from the rows' parts: the product of their linear parts l_i·l_j, row i's angular
// parts and row j's weighted ones (a row stored without its linear part, as a contact's normal
// row whose linear part is its manifold's normal, passes these).
inline double coupling_parts(double linear_product, const Vec3& angular_a, const Vec3& angular_b,
                             double inverse_mass_a, const Vec3& weighted_a, double inverse_mass_b,
                             const Vec3& weighted_b) {
  return (inverse_mass_a + inverse_mass_b) * linear_product + angular_a.dot(weighted_a) +
         angular_b.dot(weighted_b);
}
inline double coupling_weighted(const Jacobian& i, const Jacobian& j, double inverse_mass_a,
                                const Vec3& weighted_a, double inverse_mass_b,
                                const Vec3& weighted_b) {
  return coupling_parts(i.linear.dot(j.linear), i.angular_a, i.angular_b, inverse_mass_a,
                        weighted_a, inverse_mass_b, weighted_b);
}
inline double coupling(const Jacobian& i, const Jacobian& j, double inverse_mass_a,
                       const Mat3& inverse_inertia_a, double inverse_mass_b,
                       const Mat3& inverse_inertia_b) {
  return coupling_weighted(i, j, inverse_mass_a, Vec3(inverse_inertia_a * j.angular_a),
                           inverse_mass_b, Vec3(inverse_inertia_b * j.angular_b));
}
inline double coupling(const Jacobian& i, const Jacobian& j, const SolverBody& a,
                       const SolverBody& b) {
  return coupling(i, j, a.inverse_mass, a.inverse_inertia, b.inverse_mass, b.inverse_inertia);
}

// The impulse-update coefficients of a soft row over a substep h (Box2D v3 b2MakeSoft):
// with ω = 2π·hertz, a1 = 2ζ + hω, a2 = hω·a1, a3 = 1/(1 + a2):
//   bias_rate = ω/a1 (1/s),  mass_scale = a2·a3,  impulse_scale = a3.
// hertz = 0 gives a rigid row without position feedback.
struct Softness {
  double bias_rate = 0.0;
  double mass_scale = 1.0;
  double impulse_scale = 0.0;
  // γ/K of the soft constraint J v' + β C + γ λ' = 0 (see above): impulse_scale/mass_scale
  // = 1/a2. 0 for a rigid row.
  double compliance() const { return mass_scale > 0.0 ? impulse_scale / mass_scale : 0.0; }
};
inline constexpr Softness rigid_softness{0.0, 1.0, 0.0};
Softness make_soft(double hertz, double damping_ratio, double h);

inline constexpr double unbounded = std::numeric_limits<double>::infinity();

struct ConstraintRow {
  Jacobian jacobian;
  Vec3 weighted_a = Vec3::Zero();  // I_a⁻¹ angular_a (the angular part of W Jᵀ for a)
  Vec3 weighted_b = Vec3::Zero();  // I_b⁻¹ angular_b
  double mass = 0.0;               // 1/(J W Jᵀ); 0 when neither body can move along the row
  double impulse = 0.0;            // accumulated λ over the step (N s, or N m s)
  double lower = -unbounded;       // bounds of the accumulated impulse
  double upper = unbounded;
};

// 1/k, the effective mass of a row whose J W Jᵀ is k; 0 when neither body can move along it.
inline double inverse_or_zero(double k) { return k > 0.0 && std::isfinite(k) ? 1.0 / k : 0.0; }

// Caches W Jᵀ and the effective mass for the bodies' present inverse inertias.
inline void prepare_row(ConstraintRow& row, const SolverBody& a, const SolverBody& b) {
  row.weighted_a = a.inverse_inertia * row.jacobian.angular_a;
  row.weighted_b = b.inverse_inertia * row.jacobian.angular_b;
  const double k = coupling_weighted(row.jacobian, row.jacobian, a.inverse_mass, row.weighted_a,
                                     b.inverse_mass, row.weighted_b);
  row.mass = inverse_or_zero(k);
}

// J v: the row's velocity (m/s or rad/s).
// J v of a Jacobian, from the pair's relative velocity dv = v_b − v_a and angular velocities
// (a sweep that keeps a pair's velocities in locals passes those).
// The same from a Jacobian's parts (a row stored without its linear part passes it).
inline double velocity_along(const Vec3& linear, const Vec3& angular_a, const Vec3& angular_b,
                             const Vec3& dv, const Vec3& w_a, const Vec3& w_b) {
  return linear.dot(dv) + angular_b.dot(w_b) - angular_a.dot(w_a);
}
// The same for a Jacobian with no linear part (a twist row: angular_jacobian).
inline double angular_velocity_along(const Vec3& angular_a, const Vec3& angular_b,
                                     const Vec3& w_a, const Vec3& w_b) {
  return angular_b.dot(w_b) - angular_a.dot(w_a);
}
inline double jacobian_velocity(const Jacobian& j, const Vec3& dv, const Vec3& w_a,
                                const Vec3& w_b) {
  return velocity_along(j.linear, j.angular_a, j.angular_b, dv, w_a, w_b);
}
inline double row_velocity(const ConstraintRow& row, const SolverBody& a, const SolverBody& b) {
  return jacobian_velocity(row.jacobian, b.velocity - a.velocity, a.angular_velocity,
                           b.angular_velocity);
}

// Applies the impulse λ along the row: Δv = W Jᵀ λ; from the parts: the linear part and W's
// angular parts of Jᵀ (weighted_a, weighted_b).
inline void apply_parts(const Vec3& linear, const Vec3& weighted_a, const Vec3& weighted_b,
                        SolverBody& a, SolverBody& b, double lambda) {
  a.velocity -= (a.inverse_mass * lambda) * linear;
  a.angular_velocity -= lambda * weighted_a;
  b.velocity += (b.inverse_mass * lambda) * linear;
  b.angular_velocity += lambda * weighted_b;
}
inline void apply_row(const ConstraintRow& row, SolverBody& a, SolverBody& b, double lambda) {
  apply_parts(row.jacobian.linear, row.weighted_a, row.weighted_b, a, b, lambda);
}

// One Gauss-Seidel update of the row (Catto 2005, accumulated and clamped; Box2D v3's soft
// form): with `bias` the velocity bias (m/s: J v is driven toward −bias),
//   Δλ = −mass (mass_scale·J v + bias) − impulse_scale·λ,
// then λ + Δλ is clamped to [lower, upper] and the change applied. A rigid row with bias −t
// reaches J v = t exactly. Returns |J v + bias| before the update, the row's velocity error.
// updated_impulse is that update of an accumulated impulse at the row's velocity v (for a row
// stored in another form: a contact's normal row).
inline double updated_impulse(double mass, double impulse, double v, double bias,
                              const Softness& soft, double lower, double upper) {
  const double change = -mass * (soft.mass_scale * v + bias) - soft.impulse_scale * impulse;
  return std::clamp(impulse + change, lower, upper);
}
inline double solve_row(ConstraintRow& row, SolverBody& a, SolverBody& b, double bias,
                        const Softness& soft) {
  const double v = row_velocity(row, a, b);
  const double total =
      updated_impulse(row.mass, row.impulse, v, bias, soft, row.lower, row.upper);
  apply_row(row, a, b, total - row.impulse);
  row.impulse = total;
  return std::abs(v + bias);
}

}  // namespace rigidlab
