// One step of the classic explicit integrators, as free functions over the engine's one
// integration core (engine/runge_kutta.hpp), for
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

#include "engine/integrator_kind.hpp"
#include "engine/math.hpp"
#include "engine/runge_kutta.hpp"

namespace rigidlab::ode {

// A second-order system takes the world's Integrator (engine/integrator_kind.hpp).
enum class FirstOrderMethod { euler, midpoint, heun, rk4 };

// The user-facing names, in enum order, for option parsing and messages.
inline constexpr const char* first_order_method_names[] = {"euler", "midpoint", "heun", "rk4"};

// The method called `name`, or nothing for an unknown name.
std::optional<FirstOrderMethod> parse_first_order_method(std::string_view name);

// ---- second order: x'' = a(t, x, v) ------------------------------------------------------
// `accel(t, x, v)` returns the acceleration (m/s² for a particle) as a State. Each function
// advances (x, v) from time t to t + dt (s), by the engine's one integration core
// (engine/runge_kutta.hpp) with the state (x, v) and the slopes (v, a).

// The system of runge_kutta() for x'' = a(t, x, v): stage states and slopes kept by value, so
// the caller's (x, v) change only when the step has succeeded.
template <class State, class Accel, int S>
class SecondOrderSystem {
 public:
  SecondOrderSystem(const State& x, const State& v, Accel& accel)
      : x0_(x), v0_(v), x_(x), v_(v), accel_(accel) {}
  void begin() {}
  void slope(int i, double t, bool velocity) {
    kx_[i] = v_;
    if (velocity) kv_[i] = accel_(t, x_, v_);
  }
  bool move(double h, const double* aq, const double* av, int count) {
    rk::combine(x_, x0_, h, aq, kx_, count);
    rk::combine(v_, v0_, h, av, kv_, count);
    return true;
  }
  const State& x() const { return x_; }
  const State& v() const { return v_; }

 private:
  const State x0_, v0_;
  State x_, v_;
  State kx_[S], kv_[S];
  Accel& accel_;
};

template <int S, class State, class Accel>
void second_order_step(const rk::Tableau<S>& method, double t, State& x, State& v, double dt,
                       Accel& accel) {
  SecondOrderSystem<State, Accel, S> system(x, v, accel);
  rk::runge_kutta(method, system, t, dt);
  x = system.x();
  v = system.v();
}

// Explicit (forward) Euler: both updates use the state at the start of the step,
//   x_{n+1} = x_n + Δt v_n,   v_{n+1} = v_n + Δt a(t_n, x_n, v_n).   Order 1.
template <class State, class Accel>
void euler_step(double t, State& x, State& v, double dt, Accel&& accel) {
  second_order_step(rk::euler, t, x, v, dt, accel);
}

// Semi-implicit (symplectic) Euler: velocity first, then the position from the new velocity,
//   v_{n+1} = v_n + Δt a(t_n, x_n, v_n),   x_{n+1} = x_n + Δt v_{n+1}.   Order 1, but it
// keeps the energy of an oscillator bounded (Hairer et al. I.1); 003_* "Explicit Euler" table.
template <class State, class Accel>
void semi_implicit_euler_step(double t, State& x, State& v, double dt, Accel&& accel) {
  second_order_step(rk::semi_implicit, t, x, v, dt, accel);
}

// Classical RK4 on the first-order form (x, v)' = (v, a(t, x, v)) (003_* "Fourth-Order
// Runge-Kutta"): the position slopes of stages 2-4 are the stage velocities. Order 4.
template <class State, class Accel>
void rk4_step(double t, State& x, State& v, double dt, Accel&& accel) {
  second_order_step(rk::rk4, t, x, v, dt, accel);
}

// One step of `method`.
template <class State, class Accel>
void step(Integrator method, double t, State& x, State& v, double dt, Accel&& accel) {
  switch (method) {
    case Integrator::euler: euler_step(t, x, v, dt, accel); return;
    case Integrator::semi_implicit: semi_implicit_euler_step(t, x, v, dt, accel); return;
    case Integrator::rk4: rk4_step(t, x, v, dt, accel); return;
  }
}

// ---- first order: y' = f(t, y) -------------------------------------------------------------
// `f(t, y)` returns dy/dt as a State. Each function returns y at t + dt: the core with the
// state y alone (its position part; the velocity weights of these tableaux are the same).

template <class State, class F, int S>
class FirstOrderSystem {
 public:
  FirstOrderSystem(const State& y, F& f) : y0_(y), y_(y), f_(f) {}
  void begin() {}
  void slope(int i, double t, bool) { k_[i] = f_(t, y_); }
  bool move(double h, const double* a, const double*, int count) {
    rk::combine(y_, y0_, h, a, k_, count);
    return true;
  }
  const State& y() const { return y_; }

 private:
  const State y0_;
  State y_;
  State k_[S];
  F& f_;
};

template <int S, class State, class F>
State first_order_step(const rk::Tableau<S>& method, double t, const State& y, double dt, F& f) {
  FirstOrderSystem<State, F, S> system(y, f);
  rk::runge_kutta(method, system, t, dt);
  return system.y();
}

// Forward Euler: y_{n+1} = y_n + Δt f(t_n, y_n). Order 1.
template <class State, class F>
State euler_step(double t, const State& y, double dt, F&& f) {
  return first_order_step(rk::euler, t, y, dt, f);
}

// Explicit midpoint: y_{n+1} = y_n + Δt f(t_n + Δt/2, y_n + Δt/2 f(t_n, y_n)). Order 2.
template <class State, class F>
State midpoint_step(double t, const State& y, double dt, F&& f) {
  return first_order_step(rk::midpoint, t, y, dt, f);
}

// Heun (explicit trapezoid): k1 = f(t_n, y_n), k2 = f(t_n + Δt, y_n + Δt k1),
// y_{n+1} = y_n + Δt/2 (k1 + k2). Order 2.
template <class State, class F>
State heun_step(double t, const State& y, double dt, F&& f) {
  return first_order_step(rk::heun, t, y, dt, f);
}

// Classical RK4 (003_* "Fourth-Order Runge-Kutta"). Order 4.
template <class State, class F>
State rk4_step(double t, const State& y, double dt, F&& f) {
  return first_order_step(rk::rk4, t, y, dt, f);
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
