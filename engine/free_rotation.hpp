// The "conserving" rotational update of the Euler-family integrators: a rigid body's rotation
// over one step as a symmetric splitting into exact rotations, so that a torque-free body keeps
// its world angular momentum to round-off and its kinetic energy without drift.
//
// ---- Interface (for a staged step: integrate velocities -> solve constraints -> positions) ---
//
//   velocity stage, per dynamic body (uses b.inertia, b.orientation, b.angular_velocity and
//   b.torque; changes nothing):
//       const FreeRotation turn = free_rotation(b, dt);
//       b.angular_velocity = turn.angular_velocity;   // ω at the end of the free step
//       keep turn (per body, 7 doubles) until the position stage
//   constraint stage: impulses change b.angular_velocity as they like
//   position stage:
//       b.orientation = finish_rotation(b.orientation, turn, b.angular_velocity, dt);
//
// finish_rotation applies the splitting's rotation ΔR exactly when the constraints left ω
// alone (ω == turn.angular_velocity: a free body is then integrated by the method below, with
// its conservation laws), and otherwise also the rotation exp(dt (ω_solved − ω_free)), so the
// orientation follows the velocity the constraints chose, to first order as the Euler family's
// rotate-by-ω update does. ΔR is stored in the world frame (q' = ΔR q), so the position stage
// may run on an orientation that something else (a position correction) has changed since.
// A body whose principal axes are not the body axes is diagonalised at each call
// (rotation_splitting); a caller that keeps a RotationSplitting per body (recomputed when the
// inertia changes) can pass it instead and skip that.
//
// ---- The method -------------------------------------------------------------------------------
//
// In the principal frame (moments I1, I2, I3, body angular momentum Π = I ω_body, world
// L = R Π) the kinetic energy T = Σ Πi² / 2Ii is split, with Ik the intermediate moment and
// ci = 1/Ii − 1/Ik, as
//     T = |Π|² / 2Ik  +  ca Πa² / 2  +  cb Πb² / 2          ({a, b, k} = {1, 2, 3}).
// Each part's flow is an exact rotation (Lie–Poisson: Π̇ = Π × ∂T/∂Π, Ṙ = R [∂T/∂Π]×):
//   the spherical part turns R by dt Π/Ik about Π and leaves Π alone;
//   the part ci Πi²/2 keeps Πi, turns R by θ = dt ci Πi about principal axis i, and Π by −θ.
// So L = R Π is unchanged by every one of them, exactly. The step is the symmetric (Strang)
// composition  A(dt/2) B(dt) A(dt/2) S(dt): second order, time-reversible, a Poisson map, and
// so (backward error analysis) its energy error stays bounded, O(dt²), without drift. |Π|² is
// a Casimir, so S commutes with A and B and only A and B are split: for a body with two equal
// moments one of ca, cb is 0 and the step is the exact motion. Ik intermediate makes the
// largest |ci| as small as it can be; the part with the larger |ci| goes outside, where the
// leading error term (dt³/24 [A,[A,B]] against dt³/12 [B,[B,A]]) weighs it least.
// Sources: R. McLachlan, "Explicit Lie-Poisson integration and the Euler equations", Phys.
// Rev. Lett. 71 (1993) 3043 (the splitting into exactly solvable rotations); A. Dullweber,
// B. Leimkuhler, R. McLachlan, "Symplectic splitting methods for rigid body molecular
// dynamics", J. Chem. Phys. 107 (1997) 5840 (the same rotations acting on the orientation, and
// kick–drift–kick with torques); F. Fassò, "Comparison of splitting algorithms for the rigid
// body", J. Comput. Phys. 189 (2003) 527 (which split and order give the smallest energy error);
// Hairer, Lubich, Wanner, "Geometric Numerical Integration" VII.5.
//
// Torques: a kick–drift–kick composition L += dt/2 τ, free step, L += dt/2 τ (world frame, τ
// as accumulated before the step). For a constant τ this is second order; a torque that
// depends on the state but is evaluated once per step (the Euler family's forces, springs,
// callbacks) makes it first order, like the translation of the Euler family.
#pragma once

#include "engine/body.hpp"

namespace rigidlab {

// The principal moments and axes of a body-frame inertia tensor, and the order of the
// splitting. `axes` maps principal coordinates to body coordinates (identity, `aligned`, for
// a diagonal tensor: the moments are then the diagonal in body-axis order).
struct RotationSplitting {
  Vec3 moments;          // kg m², principal frame
  Vec3 inverse_moments;  // 1/(kg m²)
  Quat axes;             // principal -> body
  bool aligned = true;   // axes is the identity
  int spherical = 1;     // k: the intermediate moment, in the spherical part |Π|²/2Ik
  int outer = 0;         // a: the axis rotated twice by dt/2 (the larger |ci|)
  int inner = 2;         // b: the axis rotated once by dt
};
// Diagonal tensors are read directly; others through principal_inertia (engine/inertia.hpp).
RotationSplitting rotation_splitting(const Mat3& inertia);

// The result of the velocity stage: ω at the end of the free step (world, rad/s) and the
// rotation of the step, in the world frame (unit up to rounding; q_end = rotation ⊗ q).
struct FreeRotation {
  Vec3 angular_velocity;
  Quat rotation;
};

// One step of dt (s) of the method above for a body with inertia `p`, orientation q (body ->
// world), angular velocity ω (world, rad/s) and torque τ (world, N m, constant over the step).
FreeRotation free_rotation(const RotationSplitting& p, const Quat& q, const Vec3& omega,
                           const Vec3& torque, double dt);
// The same for a dynamic body, with its inertia, orientation, angular velocity and torque.
FreeRotation free_rotation(const Body& b, double dt);

// The single-pass form (no constraint between the stages): one step of dt (s) of b's
// orientation and angular velocity, with b.torque; nothing else of b changes. The same as
// free_rotation followed by finish_rotation with the ω it returned, one product cheaper.
void free_rotation_step(Body& b, double dt);

// The orientation at the end of the step: unit(exp(dt (ω − turn.angular_velocity)) ⊗
// turn.rotation ⊗ q), the first factor omitted when the constraints left ω as it was (ω world,
// rad/s; dt in s).
Quat finish_rotation(const Quat& q, const FreeRotation& turn, const Vec3& omega, double dt);

// The unit quaternion of the rotation by the rotation vector θ (angle |θ| rad about θ):
// (cos |θ|/2, sin(|θ|/2) θ/|θ|). Inline: the integrators' body loops use it.
inline Quat rotation_quat(const Vec3& theta) {
  const double angle = stable_norm(theta);
  const double sine = std::sin(0.5 * angle), cosine = std::cos(0.5 * angle);  // one sincos
  // sin(angle/2)/angle, by its Taylor series 1/2 − angle²/48 near 0 (error < angle⁴/3840).
  const double s = angle < 1e-4 ? 0.5 - angle * angle / 48.0 : sine / angle;
  return Quat(cosine, s * theta.x(), s * theta.y(), s * theta.z());
}

}  // namespace rigidlab
