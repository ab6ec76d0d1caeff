#include "engine/integrators.hpp"

#include <Eigen/LU>
#include <cmath>
#include <iterator>

#include "engine/free_rotation.hpp"

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

template <std::size_t N, class Enum>
std::optional<Enum> parse_name(const char* const (&names)[N], std::string_view name) {
  for (std::size_t i = 0; i < N; ++i)
    if (name == names[i]) return static_cast<Enum>(i);
  return std::nullopt;
}

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
struct Slope {
  Vec3 velocity;          // ẋ
  Vec4 orientation;       // q̇ (x, y, z, w coefficients, Eigen's order)
  Vec3 acceleration;      // v̇
  Vec3 angular_acceleration;  // ω̇
};

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

Quat add(const Quat& q, double scale, const Vec4& dq) {
  Quat result;
  result.coeffs() = q.coeffs() + scale * dq;
  return result;
}

// RK4 of one body whose force and torque stay constant over the step: the slopes depend only
// on (v, q, ω), so the four stages run in registers.
RIGIDLAB_FLATTEN void rk4_constant_forces(Body& b, const Vec3& gravity, double dt) {
  const double half = 0.5 * dt;
  const Vec3& v = b.velocity;
  const Vec3& w = b.angular_velocity;
  const Quat& q = b.orientation;
  const Slope k1 = slope(b, v, q, w, b.force, b.torque, gravity);
  const Slope k2 = slope(b, v + half * k1.acceleration, add(q, half, k1.orientation),
                         w + half * k1.angular_acceleration, b.force, b.torque, gravity);
  const Slope k3 = slope(b, v + half * k2.acceleration, add(q, half, k2.orientation),
                         w + half * k2.angular_acceleration, b.force, b.torque, gravity);
  const Slope k4 = slope(b, v + dt * k3.acceleration, add(q, dt, k3.orientation),
                         w + dt * k3.angular_acceleration, b.force, b.torque, gravity);
  const double sixth = dt / 6.0;
  b.position += sixth * (k1.velocity + 2.0 * (k2.velocity + k3.velocity) + k4.velocity);
  b.orientation = add(q, sixth, k1.orientation + 2.0 * (k2.orientation + k3.orientation) +
                                    k4.orientation);
  b.orientation = unit(b.orientation);
  b.velocity += sixth * (k1.acceleration + 2.0 * (k2.acceleration + k3.acceleration) +
                         k4.acceleration);
  b.angular_velocity += sixth * (k1.angular_acceleration +
                                 2.0 * (k2.angular_acceleration + k3.angular_acceleration) +
                                 k4.angular_acceleration);
  b.force = Vec3::Zero();
  b.torque = Vec3::Zero();
}

// Writes base + h·(dx, dq, dv, dω) into the body as a stage (or final) state: the raw
// quaternion goes to `stage_q`, the body gets it normalised; forces are reset to the ones
// applied before the step (the caller zeroes them after the last stage).
void write_state(Body& b, const BodyState& base, double h, const Vec3& dx, const Vec4& dq,
                 const Vec3& dv, const Vec3& dw, Quat& stage_q) {
  b.position = base.position + h * dx;
  b.velocity = base.velocity + h * dv;
  b.angular_velocity = base.angular_velocity + h * dw;
  stage_q = add(base.orientation, h, dq);
  b.orientation = unit(stage_q);
  b.force = base.force;
  b.torque = base.torque;
}

// One stage of the staged RK4: the slope at the state the bodies hold is added to the
// weighted sum, then the next stage's state base + c·dt·slope is written into the bodies, or
// after the fourth stage the final state base + dt/6 · sum. Returns the index of the first body
// whose written state is not finite, or all_finite.
RIGIDLAB_FLATTEN std::size_t rk4_stage(std::vector<Body>& bodies, const Vec3& gravity, Rk4Workspace& ws,
                      int stage, double dt) {
  double probe = 0.0;  // becomes NaN when any written state component is NaN or infinite
  static constexpr double weights[] = {1.0, 2.0, 2.0, 1.0};
  static constexpr double next_offsets[] = {0.5, 0.5, 1.0};
  const double weight = weights[stage];
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    Body& b = bodies[i];
    if (b.inverse_mass == 0.0) continue;
    const Slope k = slope(b, b.velocity, ws.stage_q[i], b.angular_velocity, b.force, b.torque,
                          gravity);
    BodyState& sum = ws.sum[i];
    sum.position += weight * k.velocity;
    sum.orientation.coeffs() += weight * k.orientation;
    sum.velocity += weight * k.acceleration;
    sum.angular_velocity += weight * k.angular_acceleration;
    if (stage < 3)
      write_state(b, ws.base[i], next_offsets[stage] * dt, k.velocity, k.orientation,
                  k.acceleration, k.angular_acceleration, ws.stage_q[i]);
    else {
      write_state(b, ws.base[i], dt / 6.0, sum.position, sum.orientation.coeffs(), sum.velocity,
                  sum.angular_velocity, ws.stage_q[i]);
      b.force = Vec3::Zero();
      b.torque = Vec3::Zero();
    }
    probe += 0.0 * state_sum(b);
  }
  return probe == 0.0 ? all_finite : first_non_finite(bodies);
}

}  // namespace

std::optional<Integrator> parse_integrator(std::string_view name) {
  return parse_name<std::size(integrator_names), Integrator>(integrator_names, name);
}

std::optional<GyroscopicTerm> parse_gyroscopic(std::string_view name) {
  return parse_name<std::size(gyroscopic_names), GyroscopicTerm>(gyroscopic_names, name);
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
  ws.base.resize(n);
  ws.stage_q.resize(n);
  ws.sum.resize(n);
  const BodyState zero{Vec3::Zero(), Quat(0, 0, 0, 0), Vec3::Zero(), Vec3::Zero(),
                       Vec3::Zero(), Vec3::Zero()};
  for (std::size_t i = 0; i < n; ++i) {
    ws.base[i] = state_of(bodies[i]);
    if (save_to != nullptr) save_to[i] = ws.base[i];
    ws.stage_q[i] = bodies[i].orientation;
    ws.sum[i] = zero;
  }
  static constexpr double stage_times[] = {0.0, 0.5, 0.5, 1.0};
  for (int stage = 0; stage < 4; ++stage) {
    evaluate_forces(t + stage_times[stage] * dt);
    // A stage state that is not finite ends the step before the force elements (user
    // callbacks among them) can see it: they would read, and could store, infinities.
    first_bad = rk4_stage(bodies, gravity, ws, stage, dt);
    if (first_bad != all_finite) return first_bad;
  }
  return all_finite;
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

}  // namespace

void velocity_stage(Integrator integrator, GyroscopicTerm gyroscopic, std::vector<Body>& bodies,
                    const Vec3& gravity, double h, SolverBody* solver,
                    Acceleration* acceleration, StageWorkspace& ws) {
  const std::size_t n = bodies.size();
  ws.lead.resize(n);
  ws.angular_lead.resize(n);
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
      b.orientation = conserving ? finish_rotation(b.orientation, ws.turns[i], omega, h)
                                 : exact_rotation(b.orientation, omega, h);
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
