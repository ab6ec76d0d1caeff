#include "engine/integrators.hpp"

#include <Eigen/LU>
#include <cmath>
#include <iterator>

#include "engine/free_rotation.hpp"
#include "engine/runge_kutta.hpp"

namespace rigidlab {
namespace {

using Vec4 = Eigen::Matrix<double, 4, 1, Eigen::DontAlign>;  // a quaternion's coefficients

// The body loops are the engine's hot path: every Eigen expression, 3x3 inverse and helper in
// them is inlined (GCC left several 3x3 products and the rotation as calls, which cost ~25 %
// more instructions per body than the same loop written by hand; bench/world_bench).
#if defined(__GNUC__)
#define RIGIDLAB_FLATTEN __attribute__((flatten))
#else
#define RIGIDLAB_FLATTEN
#endif

// rotate_by, here so the body loops inline it.
inline Quat exact_rotation(const Quat& q, const Vec3& omega_world, double dt) {
  return unit(Quat(rotation_quat(dt * omega_world) * q));
}

// implicit_gyroscopic_step, here so the body loops inline it.
inline Vec3 newton_gyroscopic_step(const Mat3& inertia, const Vec3& omega_body, double dt) {
  const Vec3 momentum = inertia * omega_body;
  const Mat3 jacobian = inertia + dt * (skew(omega_body) * inertia - skew(momentum));
  return omega_body - solve3(jacobian, dt * omega_body.cross(momentum));
}

// ω' of the Euler family for one body, computed in the body frame where I is constant:
// ω_b = Rᵀ ω, τ_b = Rᵀ τ, then back with R. The torque impulse dt I⁻¹ τ_b comes first, then
//   implicit:  one Newton step on backward Euler for −ω × I ω (001_*, Catto GDC 2015);
//   explicit:  forward Euler, −dt I⁻¹ (ω × I ω) at the old ω (002_* "Torque-Free Motion");
//   off:       the gyroscopic torque is dropped (002_* notes games often ignore it).
template <GyroscopicTerm gyroscopic>
Vec3 angular_velocity_update(const Body& b, const Mat3& r, double dt) {
  Vec3 omega_body = r.transpose() * b.angular_velocity;
  const Vec3 torque_body = r.transpose() * b.torque;
  if constexpr (gyroscopic == GyroscopicTerm::explicit_) {
    omega_body += dt * (b.inverse_inertia *
                        (torque_body - omega_body.cross(b.inertia * omega_body)));
  } else {
    omega_body += dt * (b.inverse_inertia * torque_body);
    if constexpr (gyroscopic == GyroscopicTerm::implicit)
      omega_body = newton_gyroscopic_step(b.inertia, omega_body, dt);
  }
  return r * omega_body;
}

// The sum of a body's state components: finite exactly when they all are (an infinity either
// stays or meets its opposite and gives NaN), so 0 · sum is 0 for a finite state, else NaN.
// Accumulating it costs a few additions per body and no branch; the index of the first bad
// body is searched for only when the accumulated probe is not 0.
double state_sum(const Body& b) {
  return b.position.sum() + b.orientation.coeffs().sum() + b.velocity.sum() +
         b.angular_velocity.sum();
}

std::size_t first_non_finite(const std::vector<Body>& bodies) {
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (!state_is_finite(bodies[i])) return i;
  return all_finite;
}

// One body of the Euler family with `conserving`: the translation as in the loop below, the
// rotation one step of free_rotation (its torque impulse included). Returns the state's sum.
template <bool semi_implicit>
double conserving_update(Body& b, const Vec3& gravity, double dt) {
  const Vec3 velocity = b.velocity + dt * (b.inverse_mass * b.force + gravity);
  if constexpr (semi_implicit) b.velocity = velocity;
  b.position += dt * b.velocity;
  b.velocity = velocity;
  free_rotation_step(b, dt);
  b.force = Vec3::Zero();
  b.torque = Vec3::Zero();
  return state_sum(b);
}

// The Euler-family loop, with the gyroscopic treatment and the saving of the old state fixed
// at compile time, so the body loop has no switch. `semi_implicit` selects whether x and q use
// the new (true) or old velocities. The old state is saved from locals at the end of each
// iteration: a store through save_to earlier could alias the body and force reloads.
template <bool semi_implicit, GyroscopicTerm gyroscopic, bool save>
RIGIDLAB_FLATTEN std::size_t euler_family_loop(std::vector<Body>& bodies, const Vec3& gravity, double dt,
                              BodyState* save_to) {
  double probe = 0.0;  // becomes NaN when any new state component is NaN or infinite
  const std::size_t n = bodies.size();
  for (std::size_t i = 0; i < n; ++i) {
    Body& b = bodies[i];
    const BodyState old = state_of(b);
    if constexpr (gyroscopic == GyroscopicTerm::conserving) {
      if (b.inverse_mass != 0.0) probe += 0.0 * conserving_update<semi_implicit>(b, gravity, dt);
    } else if (b.inverse_mass != 0.0) {
      const Mat3 r = b.orientation.toRotationMatrix();
      const Vec3 velocity = b.velocity + dt * (b.inverse_mass * b.force + gravity);
      const Vec3 angular_velocity = angular_velocity_update<gyroscopic>(b, r, dt);
      if constexpr (semi_implicit) {
        b.velocity = velocity;
        b.angular_velocity = angular_velocity;
      }
      b.position += dt * b.velocity;
      b.orientation = exact_rotation(b.orientation, b.angular_velocity, dt);
      if constexpr (!semi_implicit) {
        b.velocity = velocity;
        b.angular_velocity = angular_velocity;
      }
      b.force = Vec3::Zero();
      b.torque = Vec3::Zero();
      // Semi-implicit: x' = x + dt v' and q' = Rotate(dt ω') q are non-finite whenever v' or
      // ω' is (inf·dt stays inf, sin(inf) is NaN), so x' and q' are enough to check.
      if constexpr (semi_implicit)
        probe += 0.0 * (b.position.sum() + b.orientation.coeffs().sum());
      else
        probe += 0.0 * state_sum(b);
    }
    if constexpr (save) save_to[i] = old;
  }
  return probe == 0.0 ? all_finite : first_non_finite(bodies);
}

template <bool semi_implicit, GyroscopicTerm gyroscopic>
std::size_t euler_family_loop(std::vector<Body>& bodies, const Vec3& gravity, double dt,
                              BodyState* save_to) {
  return save_to != nullptr
             ? euler_family_loop<semi_implicit, gyroscopic, true>(bodies, gravity, dt, save_to)
             : euler_family_loop<semi_implicit, gyroscopic, false>(bodies, gravity, dt, save_to);
}

template <bool semi_implicit>
std::size_t euler_family_step(std::vector<Body>& bodies, const Vec3& gravity,
                              GyroscopicTerm gyroscopic, double dt, BodyState* save_to) {
  switch (gyroscopic) {
    case GyroscopicTerm::conserving:
      return euler_family_loop<semi_implicit, GyroscopicTerm::conserving>(bodies, gravity, dt,
                                                                          save_to);
    case GyroscopicTerm::implicit:
      return euler_family_loop<semi_implicit, GyroscopicTerm::implicit>(bodies, gravity, dt,
                                                                        save_to);
    case GyroscopicTerm::explicit_:
      return euler_family_loop<semi_implicit, GyroscopicTerm::explicit_>(bodies, gravity, dt,
                                                                         save_to);
    case GyroscopicTerm::off:
      break;
  }
  return euler_family_loop<semi_implicit, GyroscopicTerm::off>(bodies, gravity, dt, save_to);
}

// The time derivative of one body's state (the ODE in integrators.hpp). `q` is the raw stage
// quaternion: its normalised rotation gives R, and q̇ = ½ (0, ω) ⊗ q uses it as it is, so the
// quaternion is integrated as a plain 4-vector.
using Slope = BodySlope;

Slope slope(const Body& b, const Vec3& velocity, const Quat& q, const Vec3& angular_velocity,
            const Vec3& force, const Vec3& torque, const Vec3& gravity) {
  const Mat3 r = unit(q).toRotationMatrix();
  const Vec3 omega_body = r.transpose() * angular_velocity;
  const Vec3 torque_body = r.transpose() * torque;
  const Quat omega_quat(0.0, angular_velocity.x(), angular_velocity.y(), angular_velocity.z());
  Slope k;
  k.velocity = velocity;
  k.orientation = 0.5 * (omega_quat * q).coeffs();
  k.acceleration = b.inverse_mass * force + gravity;
  k.angular_acceleration =
      r * (b.inverse_inertia * (torque_body - omega_body.cross(b.inertia * omega_body)));
  return k;
}

// The world's state as a system of the integration core (engine/runge_kutta.hpp), per body
// y = (x, q, v, ω) with the slope of `slope` above; the quaternion is a 4-vector in the sums
// and normalised whenever it is written into a body (its raw value is kept for q̇).

// One body whose force and torque stay constant over the step: the slopes depend only on
// (v, q, ω), so the stages run in registers (the world's fast path for rk4, bench/world_bench).
// The position x enters no slope, so only the last move (count = S: the result) computes it.
template <int S>
class ConstantForceBody {
 public:
  ConstantForceBody(Body& b, const Vec3& gravity)
      : b_(b), gravity_(gravity), q0_(b.orientation), v0_(b.velocity), w0_(b.angular_velocity),
        q_(q0_), v_(v0_), w_(w0_) {}
  void begin() {}
  void slope(int i, double, bool) {
    k_[i] = rigidlab::slope(b_, v_, q_, w_, b_.force, b_.torque, gravity_);
  }
  bool move(double h, const double* aq, const double* av, int count) {
    Vec4 q = q0_.coeffs();
    v_ = v0_;
    w_ = w0_;
#pragma GCC unroll 4
    for (int j = 0; j < count; ++j) {
      if (aq[j] != 0.0) q += (h * aq[j]) * k_[j].orientation;
      if (av[j] != 0.0) {
        v_ += (h * av[j]) * k_[j].acceleration;
        w_ += (h * av[j]) * k_[j].angular_acceleration;
      }
    }
    q_.coeffs() = q;
    if (count == S) finish(h, aq);
    return true;
  }

 private:
  // The result into the body; its force and torque are consumed.
  void finish(double h, const double* bq) {
    Vec3 x = b_.position;
#pragma GCC unroll 4
    for (int j = 0; j < S; ++j)
      if (bq[j] != 0.0) x += (h * bq[j]) * k_[j].velocity;
    b_.position = x;
    b_.orientation = unit(q_);
    b_.velocity = v_;
    b_.angular_velocity = w_;
    b_.force = Vec3::Zero();
    b_.torque = Vec3::Zero();
  }

  Body& b_;
  const Vec3& gravity_;
  const Quat q0_;
  const Vec3 v0_, w0_;
  Quat q_;  // raw (un-normalised) stage quaternion
  Vec3 v_, w_;
  Slope k_[S];
};

// All bodies, with state-dependent forces: `evaluate_forces(t)` runs before every slope, on
// the stage state written into the bodies (orientation normalised) with each body's force and
// torque reset to what was applied before the step. A stage state that is not finite stops the
// step before the force elements (user callbacks among them) can see it: they would read, and
// could store, infinities. One pass over the bodies per stage: slope(i) only runs the force
// elements; the next move computes each body's slope kᵢ just before moving that body (a
// body's slope depends on its own state and forces alone). The last move (count = S) writes
// the result and consumes the applied forces.
template <int S>
class WorldBodies {
 public:
  WorldBodies(std::vector<Body>& bodies, const Vec3& gravity, Rk4Workspace& ws,
              const std::function<void(double)>& evaluate_forces, BodyState* save_to)
      : bodies_(bodies), gravity_(gravity), ws_(ws), evaluate_forces_(evaluate_forces),
        save_to_(save_to) {}
  void begin() {
    const std::size_t n = bodies_.size();
    ws_.base.resize(n);
    ws_.stage_q.resize(n);
    ws_.slopes.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      ws_.base[i] = state_of(bodies_[i]);
      if (save_to_ != nullptr) save_to_[i] = ws_.base[i];
      ws_.stage_q[i] = bodies_[i].orientation;
    }
  }
  void slope(int, double t, bool) { evaluate_forces_(t); }
  RIGIDLAB_FLATTEN bool move(double h, const double* aq, const double* av, int count) {
    double probe = 0.0;  // becomes NaN when any written state component is NaN or infinite
    const bool last = count == S;
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      Body& b = bodies_[i];
      if (b.inverse_mass == 0.0) continue;
      Slope* k = ws_.slopes[i].data();
      k[count - 1] = rigidlab::slope(b, b.velocity, ws_.stage_q[i], b.angular_velocity, b.force,
                                     b.torque, gravity_);
      const BodyState& base = ws_.base[i];
      Vec4 q = base.orientation.coeffs();
      b.position = base.position;
      b.velocity = base.velocity;
      b.angular_velocity = base.angular_velocity;
      for (int j = 0; j < count; ++j) {
        if (aq[j] != 0.0) {
          b.position += (h * aq[j]) * k[j].velocity;
          q += (h * aq[j]) * k[j].orientation;
        }
        if (av[j] != 0.0) {
          b.velocity += (h * av[j]) * k[j].acceleration;
          b.angular_velocity += (h * av[j]) * k[j].angular_acceleration;
        }
      }
      ws_.stage_q[i].coeffs() = q;
      b.orientation = unit(ws_.stage_q[i]);
      b.force = last ? Vec3::Zero() : base.force;
      b.torque = last ? Vec3::Zero() : base.torque;
      probe += 0.0 * state_sum(b);
    }
    first_bad_ = probe == 0.0 ? all_finite : first_non_finite(bodies_);
    return first_bad_ == all_finite;
  }
  std::size_t first_bad() const { return first_bad_; }

 private:
  std::vector<Body>& bodies_;
  const Vec3& gravity_;
  Rk4Workspace& ws_;
  const std::function<void(double)>& evaluate_forces_;
  BodyState* save_to_;
  std::size_t first_bad_ = all_finite;
};

RIGIDLAB_FLATTEN void rk4_constant_forces(Body& b, const Vec3& gravity, double dt) {
  ConstantForceBody<rk::rk4.stages> system(b, gravity);
  rk::runge_kutta(rk::rk4, system, 0.0, dt);
}

}  // namespace

std::optional<GyroscopicTerm> parse_gyroscopic(std::string_view name) {
  return parse_name<GyroscopicTerm>(gyroscopic_names, name);
}

Quat rotate_by(const Quat& q, const Vec3& omega_world, double dt) {
  return exact_rotation(q, omega_world, dt);
}

Vec3 implicit_gyroscopic_step(const Mat3& inertia, const Vec3& omega_body, double dt) {
  return newton_gyroscopic_step(inertia, omega_body, dt);
}

std::size_t euler_step(std::vector<Body>& bodies, const Vec3& gravity, GyroscopicTerm gyroscopic,
                       double dt, BodyState* save_to) {
  return euler_family_step<false>(bodies, gravity, gyroscopic, dt, save_to);
}

std::size_t semi_implicit_euler_step(std::vector<Body>& bodies, const Vec3& gravity,
                                     GyroscopicTerm gyroscopic, double dt, BodyState* save_to) {
  return euler_family_step<true>(bodies, gravity, gyroscopic, dt, save_to);
}

std::size_t rk4_step(std::vector<Body>& bodies, const Vec3& gravity, double t, double dt,
                     Rk4Workspace& ws, const std::function<void(double t)>& evaluate_forces,
                     BodyState* save_to) {
  std::size_t first_bad = all_finite;
  const std::size_t n = bodies.size();
  if (!evaluate_forces) {
    for (std::size_t i = 0; i < n; ++i) {
      Body& b = bodies[i];
      if (save_to != nullptr) save_to[i] = state_of(b);
      if (b.inverse_mass == 0.0) continue;
      rk4_constant_forces(b, gravity, dt);
      if (!state_is_finite(b) && first_bad == all_finite) first_bad = i;
    }
    return first_bad;
  }
  WorldBodies<rk::rk4.stages> system(bodies, gravity, ws, evaluate_forces, save_to);
  rk::runge_kutta(rk::rk4, system, t, dt);
  return system.first_bad();
}

// ---- the staged step ---------------------------------------------------------------------------

namespace {

template <bool semi_implicit, GyroscopicTerm gyroscopic>
void euler_family_velocities(std::vector<Body>& bodies, const Vec3& gravity, double h,
                             SolverBody* solver, Acceleration* acceleration, StageWorkspace& ws) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    Body& b = bodies[i];
    SolverBody& s = solver[i];
    if (b.inverse_mass == 0.0) {
      s = SolverBody{};
      acceleration[i] = Acceleration{};
      ws.lead[i] = ws.angular_lead[i] = Vec3::Zero();
      continue;
    }
    const Mat3 r = b.orientation.toRotationMatrix();
    const Vec3 a = b.inverse_mass * b.force + gravity;
    Vec3 omega;
    if constexpr (gyroscopic == GyroscopicTerm::conserving) {
      ws.turns[i] = free_rotation(b, h);
      omega = ws.turns[i].angular_velocity;
    } else {
      omega = angular_velocity_update<gyroscopic>(b, r, h);
    }
    s.inverse_mass = b.inverse_mass;
    s.inverse_inertia = r * b.inverse_inertia * r.transpose();
    s.delta_position = s.delta_rotation = Vec3::Zero();
    acceleration[i].linear = a;
    acceleration[i].angular = (omega - b.angular_velocity) / h;
    // The conserving rotation is the same under both (engine/free_rotation.hpp): its ω is
    // the velocity the orientation turns with.
    constexpr bool new_omega = semi_implicit || gyroscopic == GyroscopicTerm::conserving;
    s.velocity = semi_implicit ? Vec3(b.velocity + h * a) : b.velocity;
    s.angular_velocity = new_omega ? omega : b.angular_velocity;
    ws.lead[i] = semi_implicit ? Vec3::Zero() : Vec3(h * a);
    ws.angular_lead[i] = new_omega ? Vec3::Zero() : Vec3(omega - b.angular_velocity);
    b.force = Vec3::Zero();
    b.torque = Vec3::Zero();
  }
}

template <bool semi_implicit>
void euler_family_velocities(GyroscopicTerm gyroscopic, std::vector<Body>& bodies,
                             const Vec3& gravity, double h, SolverBody* solver,
                             Acceleration* acceleration, StageWorkspace& ws) {
  switch (gyroscopic) {
    case GyroscopicTerm::conserving:
      ws.conserving = true;
      ws.turns.resize(bodies.size());
      return euler_family_velocities<semi_implicit, GyroscopicTerm::conserving>(
          bodies, gravity, h, solver, acceleration, ws);
    case GyroscopicTerm::implicit:
      return euler_family_velocities<semi_implicit, GyroscopicTerm::implicit>(
          bodies, gravity, h, solver, acceleration, ws);
    case GyroscopicTerm::explicit_:
      return euler_family_velocities<semi_implicit, GyroscopicTerm::explicit_>(
          bodies, gravity, h, solver, acceleration, ws);
    case GyroscopicTerm::off:
      break;
  }
  euler_family_velocities<semi_implicit, GyroscopicTerm::off>(bodies, gravity, h, solver,
                                                              acceleration, ws);
}

// RK4's prediction of the mean velocity of the step, for a constant acceleration: the applied
// forces before the step and gravity, and the full Euler equations for the rotation.
void rk4_velocities(const std::vector<Body>& bodies, const Vec3& gravity, double h,
                    SolverBody* solver, Acceleration* acceleration, StageWorkspace& ws) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    SolverBody& s = solver[i];
    if (b.inverse_mass == 0.0) {
      s = SolverBody{};
      acceleration[i] = Acceleration{};
      ws.free_velocity[i] = ws.free_angular_velocity[i] = Vec3::Zero();
      continue;
    }
    const Mat3 r = b.orientation.toRotationMatrix();
    s.inverse_mass = b.inverse_mass;
    s.inverse_inertia = r * b.inverse_inertia * r.transpose();
    s.delta_position = s.delta_rotation = Vec3::Zero();
    const Vec3 omega_body = r.transpose() * b.angular_velocity;
    acceleration[i].linear = b.inverse_mass * b.force + gravity;
    acceleration[i].angular =
        r * (b.inverse_inertia *
             (r.transpose() * b.torque - omega_body.cross(b.inertia * omega_body)));
    s.velocity = b.velocity + 0.5 * h * acceleration[i].linear;
    s.angular_velocity = b.angular_velocity + 0.5 * h * acceleration[i].angular;
    ws.free_velocity[i] = s.velocity;
    ws.free_angular_velocity[i] = s.angular_velocity;
  }
}

// The conserving rotation's end angular velocity when the constraints changed ω (the lead the
// finish stage adds to the solved ω), for body b that has just turned from `start` to
// b.orientation. The free step ends with the angular momentum L_free = I(R_free) ω_free (world,
// R_free = ΔR R_start, I(R) = R I Rᵀ), which the free rotation keeps as the body turns; the
// solver's change Δω = ω_solved − ω_free is an angular impulse ΔL = I(R_start) Δω, its inverse
// inertia being the start pose's (velocity_stage). So the body ends with L_free + ΔL and its
// end angular velocity is that through the inertia of the pose it ends in:
//   ω_end = I(R_end)⁻¹ (I(R_free) ω_free + I(R_start) Δω),
// not ω_free + Δω: that keeps Δω as a world vector while the body turns under it, so the
// angular momentum it stands for, I(R) Δω, and the energy change with the pose. The sum lost
// energy at first order in h: a top on a ball pivot (box 0.3 x 0.2 x 0.1 m, 1 kg, 20 rad/s
// about its axis, pivot 0.3 m from its centre; semi_implicit, gyroscopic "conserving",
// soft_step) lost 217 mJ in 5 s at 1 ms and 108 mJ at 0.5 ms, where the free body keeps its
// energy to 2e-8 J; now it oscillates by ±12 mJ at 1 ms and the mean of its last second is
// within 0.2 mJ of its first's after 10 s (tests/engine/joint_energy_test.cpp). The push
// velocities (soft_step) move positions only, so they are not in ΔL.
// A body with equal moments (a sphere, a cube) gets ω_solved back, to rounding.
Vec3 momentum_lead(const Body& b, const Quat& start, const FreeRotation& free,
                   const Vec3& solved) {
  const Vec3 change = solved - free.angular_velocity;
  if (is_zero(change)) return Vec3::Zero();
  const Mat3 r_start = start.toRotationMatrix();
  const Mat3 r_free = unit(Quat(free.rotation * start)).toRotationMatrix();
  const Mat3 r_end = b.orientation.toRotationMatrix();
  const Vec3 momentum = r_free * (b.inertia * (r_free.transpose() * free.angular_velocity)) +
                        r_start * (b.inertia * (r_start.transpose() * change));
  return r_end * (b.inverse_inertia * (r_end.transpose() * momentum)) - solved;
}

}  // namespace

Quat orientation_after(const StageWorkspace& ws, const Body& b, std::size_t i, const Vec3& omega,
                       double h) {
  if (!ws.conserving || b.inverse_mass == 0.0) return exact_rotation(b.orientation, omega, h);
  return finish_rotation(b.orientation, ws.turns[i], omega, h);
}

void velocity_stage(Integrator integrator, GyroscopicTerm gyroscopic, std::vector<Body>& bodies,
                    const Vec3& gravity, double h, SolverBody* solver,
                    Acceleration* acceleration, StageWorkspace& ws) {
  const std::size_t n = bodies.size();
  ws.lead.resize(n);
  ws.angular_lead.resize(n);
  ws.conserving = false;
  switch (integrator) {
    case Integrator::euler:
      return euler_family_velocities<false>(gyroscopic, bodies, gravity, h, solver, acceleration,
                                            ws);
    case Integrator::semi_implicit:
      return euler_family_velocities<true>(gyroscopic, bodies, gravity, h, solver, acceleration,
                                           ws);
    case Integrator::rk4:
      break;
  }
  ws.free_velocity.resize(n);
  ws.free_angular_velocity.resize(n);
  rk4_velocities(bodies, gravity, h, solver, acceleration, ws);
}

std::size_t position_stage(Integrator integrator, GyroscopicTerm gyroscopic,
                           std::vector<Body>& bodies, const Vec3& gravity, double t, double h,
                           const SolverBody* solver, const SolverBody* push, StageWorkspace& ws,
                           Rk4Workspace& rk4,
                           const std::function<void(double t)>& evaluate_forces) {
  const std::size_t n = bodies.size();
  if (integrator != Integrator::rk4) {
    const bool conserving = gyroscopic == GyroscopicTerm::conserving;
    double probe = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      Body& b = bodies[i];
      if (b.inverse_mass == 0.0) continue;
      b.position += h * (solver[i].velocity + push[i].velocity);
      const Vec3 omega = solver[i].angular_velocity + push[i].angular_velocity;
      if (conserving) {
        const Quat start = b.orientation;
        b.orientation = finish_rotation(start, ws.turns[i], omega, h);
        ws.angular_lead[i] = momentum_lead(b, start, ws.turns[i], solver[i].angular_velocity);
      } else {
        b.orientation = exact_rotation(b.orientation, omega, h);
      }
      probe += 0.0 * (b.position.sum() + b.orientation.coeffs().sum());
    }
    return probe == 0.0 ? all_finite : first_non_finite(bodies);
  }
  // RK4 from the state the solver's impulses (and pushes) changed at the start of the step.
  for (std::size_t i = 0; i < n; ++i) {
    Body& b = bodies[i];
    if (b.inverse_mass == 0.0) continue;
    b.velocity += solver[i].velocity + push[i].velocity - ws.free_velocity[i];
    b.angular_velocity +=
        solver[i].angular_velocity + push[i].angular_velocity - ws.free_angular_velocity[i];
  }
  const std::size_t bad = rk4_step(bodies, gravity, t, h, rk4, evaluate_forces);
  if (bad != all_finite) return bad;
  for (std::size_t i = 0; i < n; ++i) {
    if (bodies[i].inverse_mass == 0.0) {
      ws.lead[i] = ws.angular_lead[i] = Vec3::Zero();
      continue;
    }
    ws.lead[i] = bodies[i].velocity - solver[i].velocity - push[i].velocity;
    ws.angular_lead[i] =
        bodies[i].angular_velocity - solver[i].angular_velocity - push[i].angular_velocity;
  }
  return all_finite;
}

std::size_t finish_stage(std::vector<Body>& bodies, const SolverBody* solver,
                         const StageWorkspace& ws) {
  double probe = 0.0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    Body& b = bodies[i];
    if (b.inverse_mass == 0.0) continue;
    b.velocity = solver[i].velocity + ws.lead[i];
    b.angular_velocity = solver[i].angular_velocity + ws.angular_lead[i];
    probe += 0.0 * (b.velocity.sum() + b.angular_velocity.sum());
  }
  return probe == 0.0 ? all_finite : first_non_finite(bodies);
}

}  // namespace rigidlab
