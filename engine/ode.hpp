// One step of the classic explicit integrators, as free functions, for
//   - a second-order system x'' = a(t, x, v) (a particle, or any mass-spring-like system), and
//   - a first-order system y' = f(t, y).
// The state type is a double, a Vec3 or an Eigen::VectorXd (any type with +, - and scaling by
// a double); the right-hand side is any callable. Templates, so that a hot loop inlines the
// callable: no std::function and no virtual dispatch.
//
// Sources:
//   /work/shared/seeds/003_* "Explicit Euler" (its table, v_n = v_0 + a Δt then
//     r_n = r_0 + v_n Δt, is the semi-implicit variant: the car reaches 550 m, not 450 m) and
//     "Fourth-Order Runge-Kutta" (k1..k4, r_{n+1} = r_n + Δt/6 (k1 + 2k2 + 2k3 + k4)).
//   Hairer, Lubich, Wanner, "Geometric Numerical Integration" (2006), I.1: symplectic Euler.
//   Butcher, "Numerical Methods for Ordinary Differential Equations" (2016), 23: explicit
//     midpoint and Heun (trapezoidal) methods, both of order 2.
//
// Exceptions thrown by the callable propagate unchanged; the state passed by reference is then
// left as it was before the step (every method computes the new state before assigning it).
#pragma once

#include <optional>
#include <string_view>

#include "engine/math.hpp"

namespace rigidlab::ode {

enum class SecondOrderMethod { euler, semi_implicit, rk4 };
enum class FirstOrderMethod { euler, midpoint, heun, rk4 };

// The user-facing names, in enum order, for option parsing and messages.
inline constexpr const char* second_order_method_names[] = {"euler", "semi_implicit", "rk4"};
inline constexpr const char* first_order_method_names[] = {"euler", "midpoint", "heun", "rk4"};

// The method called `name`, or nothing for an unknown name.
std::optional<SecondOrderMethod> parse_second_order_method(std::string_view name);
std::optional<FirstOrderMethod> parse_first_order_method(std::string_view name);

// ---- second order: x'' = a(t, x, v) ------------------------------------------------------
// `accel(t, x, v)` returns the acceleration (m/s² for a particle) as a State. Each function
// advances (x, v) from time t to t + dt (s).

// Explicit (forward) Euler: both updates use the state at the start of the step,
//   x_{n+1} = x_n + Δt v_n,   v_{n+1} = v_n + Δt a(t_n, x_n, v_n).   Order 1.
template <class State, class Accel>
void euler_step(double t, State& x, State& v, double dt, Accel&& accel) {
  const State a = accel(t, x, v);
  const State x_next = x + dt * v;
  v = v + dt * a;
  x = x_next;
}

// Semi-implicit (symplectic) Euler: velocity first, then the position from the new velocity,
//   v_{n+1} = v_n + Δt a(t_n, x_n, v_n),   x_{n+1} = x_n + Δt v_{n+1}.   Order 1, but it
// keeps the energy of an oscillator bounded (Hairer et al. I.1); 003_* "Explicit Euler" table.
template <class State, class Accel>
void semi_implicit_euler_step(double t, State& x, State& v, double dt, Accel&& accel) {
  const State v_next = v + dt * accel(t, x, v);
  x = x + dt * v_next;
  v = v_next;
}

// Classical RK4 on the first-order form (x, v)' = (v, a(t, x, v)) (003_* "Fourth-Order
// Runge-Kutta"): the position slopes of stages 2-4 are the stage velocities. Order 4.
template <class State, class Accel>
void rk4_step(double t, State& x, State& v, double dt, Accel&& accel) {
  const double half = 0.5 * dt;
  const State& k1x = v;
  const State k1v = accel(t, x, v);
  const State k2x = v + half * k1v;
  const State k2v = accel(t + half, State(x + half * k1x), k2x);
  const State k3x = v + half * k2v;
  const State k3v = accel(t + half, State(x + half * k2x), k3x);
  const State k4x = v + dt * k3v;
  const State k4v = accel(t + dt, State(x + dt * k3x), k4x);
  const State x_next = x + (dt / 6.0) * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
  v = v + (dt / 6.0) * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  x = x_next;
}

// One step of `method`.
template <class State, class Accel>
void step(SecondOrderMethod method, double t, State& x, State& v, double dt, Accel&& accel) {
  switch (method) {
    case SecondOrderMethod::euler: euler_step(t, x, v, dt, accel); return;
    case SecondOrderMethod::semi_implicit: semi_implicit_euler_step(t, x, v, dt, accel); return;
    case SecondOrderMethod::rk4: rk4_step(t, x, v, dt, accel); return;
  }
}

// ---- first order: y' = f(t, y) -------------------------------------------------------------
// `f(t, y)` returns dy/dt as a State. Each function returns y at t + dt.

// Forward Euler: y_{n+1} = y_n + Δt f(t_n, y_n). Order 1.
template <class State, class F>
State euler_step(double t, const State& y, double dt, F&& f) {
  return State(y + dt * f(t, y));
}

// Explicit midpoint: y_{n+1} = y_n + Δt f(t_n + Δt/2, y_n + Δt/2 f(t_n, y_n)). Order 2.
template <class State, class F>
State midpoint_step(double t, const State& y, double dt, F&& f) {
  const State k1 = f(t, y);
  return State(y + dt * f(t + 0.5 * dt, State(y + (0.5 * dt) * k1)));
}

// Heun (explicit trapezoid): k1 = f(t_n, y_n), k2 = f(t_n + Δt, y_n + Δt k1),
// y_{n+1} = y_n + Δt/2 (k1 + k2). Order 2.
template <class State, class F>
State heun_step(double t, const State& y, double dt, F&& f) {
  const State k1 = f(t, y);
  const State k2 = f(t + dt, State(y + dt * k1));
  return State(y + (0.5 * dt) * (k1 + k2));
}

// Classical RK4 (003_* "Fourth-Order Runge-Kutta"). Order 4.
template <class State, class F>
State rk4_step(double t, const State& y, double dt, F&& f) {
  const double half = 0.5 * dt;
  const State k1 = f(t, y);
  const State k2 = f(t + half, State(y + half * k1));
  const State k3 = f(t + half, State(y + half * k2));
  const State k4 = f(t + dt, State(y + dt * k3));
  return State(y + (dt / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4));
}

// One step of `method`: y at t + dt.
template <class State, class F>
State step(FirstOrderMethod method, double t, const State& y, double dt, F&& f) {
  switch (method) {
    case FirstOrderMethod::euler: return euler_step(t, y, dt, f);
    case FirstOrderMethod::midpoint: return midpoint_step(t, y, dt, f);
    case FirstOrderMethod::heun: return heun_step(t, y, dt, f);
    case FirstOrderMethod::rk4: break;
  }
  return rk4_step(t, y, dt, f);
}

}  // namespace rigidlab::ode
