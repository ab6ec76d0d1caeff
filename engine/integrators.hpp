// Time integrators for a set of rigid bodies, one free function per method (STYLE.md 7).
//
// The state of a body is y = (x, q, v, ω): COM position, orientation quaternion, COM velocity,
// angular velocity (world). Its ODE is the Newton-Euler system
//   ẋ = v,   q̇ = ½ (0, ω) ⊗ q,   v̇ = F/m + g,   ω̇ = I_w⁻¹ (τ − ω × I_w ω),   I_w = R I Rᵀ
// (/work/shared/seeds/002_* "Newton-Euler Equations" and "Torque-Free Motion"; 003_* "Solving
// Angular Equations in 3D" for q̇ = ½ ω q). F and τ are what has been accumulated in each
// body's force and torque; gravity g is added here to every dynamic body as an acceleration.
// Static bodies (inverse mass 0) never move. Each integrator consumes the accumulators: after
// the step every force and torque is zero.
//
// Every integrator returns the index of the first body whose new state is not finite (or
// `all_finite`), so the world can refuse the step and name the body. Given `save_to` (an
// array of bodies.size() states), each also writes every body's state before the step there,
// in the same pass: the world's undo snapshot costs no extra sweep over memory. Nothing here allocates
// except RK4's workspace, which grows to the number of bodies once and is then reused.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string_view>
#include <vector>

#include "engine/body.hpp"
#include "engine/constraint_row.hpp"
#include "engine/free_rotation.hpp"
#include "engine/integrator_kind.hpp"

namespace rigidlab {

// How the Euler family treats the gyroscopic torque −ω × I ω (`explicit` is a keyword):
// `conserving` replaces the whole rotational update by the splitting of engine/free_rotation.hpp.
enum class GyroscopicTerm { conserving, implicit, explicit_, off };
inline constexpr GyroscopicTerm default_gyroscopic = GyroscopicTerm::conserving;

// The user-facing names, in enum order.
inline constexpr const char* gyroscopic_names[] = {"conserving", "implicit", "explicit", "off"};
std::optional<GyroscopicTerm> parse_gyroscopic(std::string_view name);

inline constexpr std::size_t all_finite = static_cast<std::size_t>(-1);

// The part of a body that a step changes.
struct BodyState {
  Vec3 position;
  Quat orientation;
  Vec3 velocity;
  Vec3 angular_velocity;
  Vec3 force;
  Vec3 torque;
};
inline BodyState state_of(const Body& b) {
  return {b.position, b.orientation, b.velocity, b.angular_velocity, b.force, b.torque};
}
inline void set_state(Body& b, const BodyState& s) {
  b.position = s.position;
  b.orientation = s.orientation;
  b.velocity = s.velocity;
  b.angular_velocity = s.angular_velocity;
  b.force = s.force;
  b.torque = s.torque;
}
// True when position, orientation, velocity and angular velocity are all finite.
inline bool state_is_finite(const Body& b) {
  const double sum = (b.position - b.position).sum() +
                     (b.orientation.coeffs() - b.orientation.coeffs()).sum() +
                     (b.velocity - b.velocity).sum() +
                     (b.angular_velocity - b.angular_velocity).sum();
  return sum == 0.0;
}

// ---- building blocks (exposed for tests and benchmarks) -------------------------------------

// The exact rotation of angle |ω| dt about ω applied to q: exp(½ dt (0, ω)) ⊗ q, normalised.
// This is the orientation update of 002_* "Newton-Euler Equations" (A' = Rotate(ω Δt) A) with
// ω held constant over the step; unlike q + ½ ω q dt (003_*) it has no first-order norm drift.
Quat rotate_by(const Quat& q, const Vec3& omega_world, double dt);

// One Newton step on the implicit gyroscopic update in the body frame,
//   f(ω') = I (ω' − ω) + dt ω' × I ω' = 0,   Jacobian J = I + dt (ω̂ I − (I ω)^),
//   ω' ≈ ω − J⁻¹ (dt ω × I ω),
// as in /work/shared/seeds/001_* "update_rigid_body_state" (after E. Catto, "Numerical Methods",
// GDC 2015). Backward Euler on Euler's equations dissipates a little energy instead of gaining
// it, so a spinning body does not blow up at game time steps. ω and the result in rad/s, body
// frame; `inertia` the body-frame tensor.
Vec3 implicit_gyroscopic_step(const Mat3& inertia, const Vec3& omega_body, double dt);

// ---- the integrators ------------------------------------------------------------------------

// Explicit (forward) Euler on the whole state: every right-hand side at the start of the step,
//   x' = x + dt v,  q' = Rotate(dt ω) q,  v' = v + dt (F/m + g),  ω' = ω + dt ω̇
// with ω̇ per `gyroscopic` (see angular_velocity_update in the .cpp). Order 1; gains energy on
// an oscillator. 003_* "Explicit Euler", 002_* "Newton-Euler Equations". With `conserving`,
// (q, ω) take one step of free_rotation (engine/free_rotation.hpp) under either integrator.
std::size_t euler_step(std::vector<Body>& bodies, const Vec3& gravity, GyroscopicTerm gyroscopic,
                       double dt, BodyState* save_to = nullptr);

// Semi-implicit (symplectic) Euler: velocities first, then positions from the new velocities,
//   v' = v + dt (F/m + g),  ω' = ω + dt ω̇,  x' = x + dt v',  q' = Rotate(dt ω') q.
// Order 1, energy of an oscillator bounded (Hairer, Lubich, Wanner, "Geometric Numerical
// Integration" I.1). This is the update of 002_* ("p' = p + fΔt ... x' = x + vΔt") and of the
// table in 003_* "Explicit Euler".
std::size_t semi_implicit_euler_step(std::vector<Body>& bodies, const Vec3& gravity,
                                     GyroscopicTerm gyroscopic, double dt,
                                     BodyState* save_to = nullptr);

// The time derivative of one body's state: ẋ, q̇ (a quaternion's coefficients in Eigen's
// x, y, z, w order), v̇ and ω̇.
struct BodySlope {
  Vec3 velocity;
  Eigen::Matrix<double, 4, 1, Eigen::DontAlign> orientation;
  Vec3 acceleration;
  Vec3 angular_acceleration;
};

// Scratch storage of rk4_step, kept by the world so a step does not allocate.
struct Rk4Workspace {
  std::vector<BodyState> base;   // y_n and the forces applied before the step
  std::vector<Quat> stage_q;     // un-normalised stage quaternions (4-vectors)
  std::vector<std::array<BodySlope, 4>> slopes;  // k1..k4 of every body
};

// Classical fourth-order Runge-Kutta on the whole state y = (x, q, v, ω) with the ODE above
// (003_* "Fourth-Order Runge-Kutta"), by the engine's one integration core
// (engine/runge_kutta.hpp, the tableau rk::rk4); the quaternion is integrated as a 4-vector with
// q̇ = ½ (0, ω) ⊗ q and normalised once at the end of the step; the gyroscopic term is always
// included. Order 4.
//
// `evaluate_forces(t)` is called at every stage, after the stage state has been written into
// the bodies (orientation normalised) and their force and torque reset to what was applied
// before the step; it adds the state-dependent forces (springs, drag, user callbacks). It only
// ever sees finite states: when a stage state is not finite the step stops there and returns
// that body's index (the bodies then hold the stage state; the caller restores them). When it
// is empty the forces are constant over the step and every body is integrated on its own in
// one pass. Exceptions from evaluate_forces propagate; the bodies then hold a stage state and
// the caller restores them.
std::size_t rk4_step(std::vector<Body>& bodies, const Vec3& gravity, double t, double dt,
                     Rk4Workspace& workspace, const std::function<void(double t)>& evaluate_forces,
                     BodyState* save_to = nullptr);

// ---- the staged step ---------------------------------------------------------------------------
//
// With constraints in the world (contacts, joints) each integrator runs as stages of the one
// step pipeline of engine/world.cpp (docs/architecture.md), document 000 "Sequential
// impulses": 1. integrate the applied forces into the velocities the positions will move with,
// 2. the constraint solver changes them, 3. the positions move with the solved velocities.
// Every integrator here moves positions by x' = x + h u over a substep, for some velocity u:
//   semi_implicit  u = v + h a (the new velocity),            end velocity v' = u
//   euler          u = v (the old velocity),                    v' = u + h a
//   rk4            u = v + h a/2 (the mean velocity for a constant a: x' = x + h v + h²a/2);
//                  the impulses are applied at the start and the four stages (force callbacks
//                  at each) run from the changed state.
// The solver works on u only; it never asks which integrator runs. What an integrator adds to
// the solved u to get the end-of-step velocity (h a for euler) is its `lead`, kept here. A
// body no constraint touches is integrated exactly as by the functions above.

// What the velocity stage leaves for the position and finish stages, per body (sized by the
// velocity stage; allocates only when the number of bodies grows).
struct StageWorkspace {
  std::vector<Vec3> lead, angular_lead;  // end velocity − u of the free motion (m/s, rad/s)
  // gyroscopic = conserving (`conserving` true, Euler family): each body's free rotation of
  // the step (engine/free_rotation.hpp), applied exactly by the position stage when no
  // constraint changed ω.
  bool conserving = false;
  std::vector<FreeRotation> turns;
  std::vector<Vec3> free_velocity, free_angular_velocity;  // rk4: u before the solve
};

// Stage 1 over all bodies: the solver bodies (u, ω, world inverse inertia, inverse mass; static
// bodies get zeros) and the free accelerations. The Euler family consumes the force and torque
// accumulators; rk4 keeps them for its stages.
void velocity_stage(Integrator integrator, GyroscopicTerm gyroscopic, std::vector<Body>& bodies,
                    const Vec3& gravity, double h, SolverBody* solver,
                    Acceleration* acceleration, StageWorkspace& ws);
// Stage 3: moves every body with its solved u and ω plus the solver's push velocities, which
// move positions only (engine/solver.hpp; rk4: its four stages from v + Δu + u_push, Δu the
// solver's change, with evaluate_forces at each stage as rk4_step). Returns the index of the
// first body whose new state is not finite, or all_finite.
std::size_t position_stage(Integrator integrator, GyroscopicTerm gyroscopic,
                           std::vector<Body>& bodies, const Vec3& gravity, double t, double h,
                           const SolverBody* solver, const SolverBody* push, StageWorkspace& ws,
                           Rk4Workspace& rk4,
                           const std::function<void(double t)>& evaluate_forces);
// The orientation the position stage gives body i (the body as it was before the step,
// `b`) when the solver leaves it the angular velocity ω (world, rad/s), pushes left out: the
// constraint solver's look-ahead (engine/solver.cpp), so that its rows are built for the pose
// the integrator reaches. exp(h ω) q, or with `ws.conserving` exp(h (ω − ω_free)) ΔR q
// (finish_rotation, engine/free_rotation.hpp).
Quat orientation_after(const StageWorkspace& ws, const Body& b, std::size_t i, const Vec3& omega,
                       double h);

// After relax and restitution changed u: the end-of-step velocities, solved u + lead. Returns
// the first body whose velocities are not finite, or all_finite.
std::size_t finish_stage(std::vector<Body>& bodies, const SolverBody* solver,
                         const StageWorkspace& ws);

}  // namespace rigidlab
