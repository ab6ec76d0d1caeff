// The time step of an articulation: the world's three integrators (engine/integrators.hpp, same
// names and meaning) over the reduced state y = (q, q̇) with ẏ = (rates(q, q̇), q̈), q̈ from the
// articulated-body algorithm, by the engine's one integration core (engine/runge_kutta.hpp, the
// tableaux rk::euler, rk::semi_implicit, rk::rk4) — the same code that steps a world's bodies.
#include <algorithm>
#include <cmath>
#include <string>

#include "engine/articulation.hpp"
#include "engine/format.hpp"
#include "engine/runge_kutta.hpp"

namespace rigidlab {
namespace {

// The quaternion ½ (0, ω) ⊗ q for q = (w, x, y, z) stored in that order at q[3..6].
Eigen::Vector4d quaternion_rate(const Eigen::VectorXd& q, const Vec3& omega) {
  const double w = q[3];
  const Vec3 xyz(q[4], q[5], q[6]);
  const Vec3 vector_part = w * omega + omega.cross(xyz);
  return 0.5 * Eigen::Vector4d(-omega.dot(xyz), vector_part.x(), vector_part.y(),
                               vector_part.z());
}

std::string diverged_message(double t0) {
  return "the step from t = " + format_number(t0) +
         " s would leave a state that is not finite (the motion diverged: take a smaller dt or "
         "smaller torques); the state is as before the step";
}

void normalize_base_orientation(const ArticulationModel& model, Eigen::VectorXd& q) {
  if (model.free_base()) q.segment<4>(3).normalize();
}

}  // namespace

void coordinate_rates(const ArticulationModel& model, const Eigen::VectorXd& q,
                      const Eigen::VectorXd& v, Eigen::VectorXd& rates) {
  rates.resize(model.nq());
  if (model.free_base()) {
    rates.head<3>() = v.head<3>();
    rates.segment<4>(3) = quaternion_rate(q, v.segment<3>(3));
  }
  for (const Link& link : model.links())
    if (link.q_index >= 0) rates[link.q_index] = v[link.v_index];
}

void integrate_coordinates(const ArticulationModel& model, Eigen::VectorXd& q,
                           const Eigen::VectorXd& v, double dt) {
  if (model.free_base()) {
    q.head<3>() += dt * v.head<3>();
    const Quat turned = rotate_by(Quat(q[3], q[4], q[5], q[6]), v.segment<3>(3), dt);
    q.segment<4>(3) << turned.w(), turned.x(), turned.y(), turned.z();
  }
  for (const Link& link : model.links())
    if (link.q_index >= 0) q[link.q_index] += dt * v[link.v_index];
}

void Articulation::step(double dt, int count, const std::function<void()>& poll) {
  check_not_stepping("step");
  if (!(std::isfinite(dt) && dt > 0.0))
    throw std::invalid_argument("dt must be finite and > 0, got " + format_number(dt));
  if (count < 0) throw std::invalid_argument("n must be >= 0, got " + std::to_string(count));
  for (int k = 0; k < count; ++k) {
    if (poll) poll();
    step_once(dt);
    for (const std::shared_ptr<ArticulationObserver>& o : observers_) o->after_step(*this);
  }
}

void Articulation::add_step_observer(std::shared_ptr<ArticulationObserver> observer) {
  check_not_stepping("add an observer");
  observers_.push_back(std::move(observer));
}

void Articulation::remove_step_observer(const ArticulationObserver* observer) {
  check_not_stepping("remove an observer");
  observers_.erase(std::remove_if(observers_.begin(), observers_.end(),
                                  [&](const auto& o) { return o.get() == observer; }),
                   observers_.end());
}

// One step; on any failure the state and the time are put back as they were.
void Articulation::step_once(double dt) {
  const double t0 = time_;
  q0_ = q_;
  v0_ = v_;
  auto restore = [&] {
    q_ = q0_;
    v_ = v0_;
    time_ = t0;
    stepping_ = false;
  };
  stepping_ = true;
  try {
    integrate_step(dt);
  } catch (const std::domain_error& singular) {
    // A stage state that overflowed makes the algorithm's pivots NaN: say what happened.
    const bool diverged = !(q_.allFinite() && v_.allFinite());
    restore();
    if (diverged) throw ArticulationStepError(diverged_message(t0), t0);
    throw ArticulationStepError(std::string(singular.what()) + " (in the step from t = " +
                                    format_number(t0) + " s)",
                                t0);
  } catch (...) {
    restore();
    throw;
  }
  stepping_ = false;
  if (!(q_.allFinite() && v_.allFinite())) {
    restore();
    throw ArticulationStepError(diverged_message(t0), t0);
  }
  time_ = t0 + dt;
}

// The articulation's state as a system of the integration core (engine/runge_kutta.hpp): the
// position slope of a stage is coordinate_rates (a free base's quaternion as a 4-vector,
// q̇ = ½ (0, ω) ⊗ q, as the world's rk4 integrates it), the velocity slope q̈ from the
// articulated-body algorithm with the held torques and the controls at the stage time. Rates
// are taken at the raw stage quaternion; the dynamics at the normalised one. With euler, q' =
// q + dt q̇ is then normalised; semi_implicit takes the rates at (q, q̇') (003 "Explicit Euler";
// Hairer, Lubich, Wanner, "Geometric Numerical Integration" I.1); rk4 is 003 "Fourth-Order
// Runge-Kutta". step_once has saved (q₀, q̇₀) and restores them on any failure.
class ArticulationSystem {
 public:
  explicit ArticulationSystem(Articulation& art) : a_(art) {}
  void begin() {}
  void slope(int i, double t, bool velocity) {
    a_.time_ = t;
    coordinate_rates(a_.model_, a_.q_, a_.v_, a_.q_slopes_[i]);
    normalize_base_orientation(a_.model_, a_.q_);
    if (velocity) a_.evaluate(a_.v_slopes_[i]);
  }
  bool move(double h, const double* aq, const double* av, int count) {
    rk::combine(a_.q_, a_.q0_, h, aq, a_.q_slopes_, count);
    rk::combine(a_.v_, a_.v0_, h, av, a_.v_slopes_, count);
    return true;
  }

 private:
  Articulation& a_;
};

void Articulation::integrate_step(double dt) {
  ArticulationSystem system(*this);
  const double t0 = time_;
  switch (integrator_) {
    case Integrator::euler: rk::runge_kutta(rk::euler, system, t0, dt); break;
    case Integrator::semi_implicit: rk::runge_kutta(rk::semi_implicit, system, t0, dt); break;
    case Integrator::rk4: rk::runge_kutta(rk::rk4, system, t0, dt); break;
  }
  normalize_base_orientation(model_, q_);
  time_ = t0;
}

}  // namespace rigidlab
