// The time step of an articulation: the world's three integrators (engine/integrators.hpp, same
// names and meaning) over the reduced state y = (q, q̇) with ẏ = (rates(q, q̇), q̈), q̈ from the
// articulated-body algorithm. Kept in this one file, each integrator a few lines over
// coordinate_rates / integrate_coordinates / evaluate, so that one integration core can later
// serve worlds and articulations alike (issue 15, item 3).
#include <algorithm>
#include <cmath>
#include <string>

#include "engine/articulation.hpp"
#include "engine/format.hpp"

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
    switch (integrator_) {
      case Integrator::euler: euler(dt, false); break;
      case Integrator::semi_implicit: euler(dt, true); break;
      case Integrator::rk4: rk4(dt); break;
    }
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

// Explicit Euler: q' = q ⊕ dt q̇, q̇' = q̇ + dt q̈(q, q̇) (003 "Explicit Euler");
// semi-implicit (symplectic) Euler: q̇' first, then q' = q ⊕ dt q̇' (the update of the table in
// 003 "Explicit Euler"; Hairer, Lubich, Wanner, "Geometric Numerical Integration" I.1).
void Articulation::euler(double dt, bool semi_implicit) {
  evaluate(qdd_);
  if (semi_implicit) {
    v_ += dt * qdd_;
    integrate_coordinates(model_, q_, v_, dt);
  } else {
    integrate_coordinates(model_, q_, v_, dt);
    v_ += dt * qdd_;
  }
}

// Classical RK4 on y = (q, q̇) (003 "Fourth-Order Runge-Kutta"): stage states y0 + c dt k,
// slopes k = (rates, q̈), y' = y0 + dt/6 (k1 + 2k2 + 2k3 + k4). A free base's quaternion is
// integrated as a 4-vector and normalised at the end, as the world's rk4 does; each stage is
// evaluated (controls included) at the normalised orientation and at time t0 + c dt.
void Articulation::rk4(double dt) {
  const double t0 = time_;
  coordinate_rates(model_, q_, v_, q_rate_);  // k1
  evaluate(qdd_);
  q_sum_ = q_rate_;
  v_sum_ = qdd_;
  const double c[3] = {0.5, 0.5, 1.0}, weight[3] = {2.0, 2.0, 1.0};
  for (int stage = 0; stage < 3; ++stage) {  // k2, k3, k4 from the previous slope
    q_ = q0_ + (c[stage] * dt) * q_rate_;
    v_ = v0_ + (c[stage] * dt) * qdd_;
    time_ = t0 + c[stage] * dt;
    coordinate_rates(model_, q_, v_, q_rate_);
    normalize_base_orientation(model_, q_);
    evaluate(qdd_);
    q_sum_ += weight[stage] * q_rate_;
    v_sum_ += weight[stage] * qdd_;
  }
  q_ = q0_ + (dt / 6.0) * q_sum_;
  v_ = v0_ + (dt / 6.0) * v_sum_;
  normalize_base_orientation(model_, q_);
  time_ = t0;
}

}  // namespace rigidlab
