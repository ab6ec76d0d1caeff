// The one integration core of the engine: an explicit (partitioned) Runge-Kutta step over a
// state y = (q, v) — positions and velocities — and its derivative ẏ = (q̇(q, v), v̇(t, q, v)),
// given as a Butcher tableau, in the manner of MuJoCo's mj_RungeKutta (engine_forward.c): the
// stage states y₀ + h Σⱼ aᵢⱼ kⱼ, the slopes kᵢ at them, y₁ = y₀ + h Σᵢ bᵢ kᵢ. Worlds
// (engine/integrators.cpp), articulations (engine/articulation_step.cpp) and the Lua `ode` and
// `motion` modules (engine/ode.hpp) all step through runge_kutta() below; each only says what
// its state is, how a slope is evaluated and how a weighted sum of slopes moves the state.
//
// The three methods of the world, as tableaux (Hairer, Lubich, Wanner, "Geometric Numerical
// Integration" (2006) II.2, partitioned Runge-Kutta methods: the positions and the velocities
// may use different coefficients):
//   euler          one stage, b = 1 for both: q₁ = q₀ + h q̇(y₀), v₁ = v₀ + h v̇(y₀)
//                  (003_* "Explicit Euler").
//   semi_implicit  symplectic Euler (GNI I.1): v₁ = v₀ + h v̇(y₀), q₁ = q₀ + h q̇(q₀, v₁). Two
//                  stages: the second is (q₀, v₁), and only its position slope q̇ is used, so
//                  its acceleration is never evaluated (velocity_slope_used below). One
//                  acceleration per step, as the table of 003_* "Explicit Euler" computes.
//   rk4            the classical fourth-order method of 003_* "Fourth-Order Runge-Kutta",
//                  c = (0, ½, ½, 1), a₂₁ = a₃₂ = ½, a₄₃ = 1, b = (1, 2, 2, 1)/6, for both.
// and, for first-order systems y' = f(t, y) (the position part alone): midpoint and Heun
// (Butcher, "Numerical Methods for Ordinary Differential Equations" (2016), 23).
//
// A system is any type with
//   void begin();                                   // keep y₀ (the state now)
//   void slope(int i, double t, bool velocity);     // kᵢ at the current state, time t; the
//                                                   // velocity slope (v̇) only if `velocity`
//   bool move(double h, const double* aq, const double* av, int count);
//                                                   // y = y₀ + h Σ_{j<count} (aq_j kq_j, av_j kv_j),
//                                                   // false to stop the step (not finite)
// runge_kutta() calls begin, then for each stage move (from the second stage on) and slope,
// then move with b. A zero weight must contribute nothing (skip it: 0 · ∞ would be NaN).
// Everything is inline templates over constant tableaux, so that a system of one body in
// registers compiles to the loop one would write by hand (bench/world_bench).
#pragma once

namespace rigidlab::rk {

// An explicit partitioned Runge-Kutta method of S stages: `aq`, `bq` weight position slopes,
// `av`, `bv` velocity slopes (the same for a classical, non-partitioned method); strictly lower
// triangular a. `c` are the stage times as fractions of h.
template <int S>
struct Tableau {
  static constexpr int stages = S;
  double c[S];
  double aq[S][S];
  double av[S][S];
  double bq[S];
  double bv[S];
};

inline constexpr Tableau<1> euler{{0.0}, {{0.0}}, {{0.0}}, {1.0}, {1.0}};

inline constexpr Tableau<2> semi_implicit{
    {0.0, 1.0}, {{0.0, 0.0}, {0.0, 0.0}}, {{0.0, 0.0}, {1.0, 0.0}}, {0.0, 1.0}, {1.0, 0.0}};

inline constexpr Tableau<4> rk4{
    {0.0, 0.5, 0.5, 1.0},
    {{0.0, 0.0, 0.0, 0.0}, {0.5, 0.0, 0.0, 0.0}, {0.0, 0.5, 0.0, 0.0}, {0.0, 0.0, 1.0, 0.0}},
    {{0.0, 0.0, 0.0, 0.0}, {0.5, 0.0, 0.0, 0.0}, {0.0, 0.5, 0.0, 0.0}, {0.0, 0.0, 1.0, 0.0}},
    {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0},
    {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0}};

inline constexpr Tableau<2> midpoint{
    {0.0, 0.5}, {{0.0, 0.0}, {0.5, 0.0}}, {{0.0, 0.0}, {0.5, 0.0}}, {0.0, 1.0}, {0.0, 1.0}};

inline constexpr Tableau<2> heun{
    {0.0, 1.0}, {{0.0, 0.0}, {1.0, 0.0}}, {{0.0, 0.0}, {1.0, 0.0}}, {0.5, 0.5}, {0.5, 0.5}};

// Whether stage i's velocity slope enters a later stage or the result: if not, a system need
// not evaluate its acceleration there (semi_implicit's second stage).
template <int S>
constexpr bool velocity_slope_used(const Tableau<S>& m, int i) {
  if (m.bv[i] != 0.0) return true;
  for (int j = i + 1; j < S; ++j)
    if (m.av[j][i] != 0.0) return true;
  return false;
}

// One step of `method` from time t to t + h. Returns false when the system stopped it (a stage
// or the result not finite); the system then holds whatever state it was moving to.
// Exceptions from the system propagate.
template <int S, class System>
inline bool runge_kutta(const Tableau<S>& method, System& system, double t, double h) {
  system.begin();
#pragma GCC unroll 4
  for (int i = 0; i < S; ++i) {
    if (i > 0 && !system.move(h, method.aq[i], method.av[i], i)) return false;
    system.slope(i, t + method.c[i] * h, velocity_slope_used(method, i));
  }
  return system.move(h, method.bq, method.bv, S);
}

// y = y₀ + h Σ_{j<count} w_j k_j for any type with += and scaling (double, Vec3, Eigen
// vectors), zero weights skipped; in place, so that a system of Eigen::VectorXd states moves
// without allocating. A helper for the systems' move.
template <class T, class Slopes>
inline void combine(T& y, const T& y0, double h, const double* w, const Slopes& k, int count) {
  y = y0;
#pragma GCC unroll 4
  for (int j = 0; j < count; ++j)
    if (w[j] != 0.0) y += (h * w[j]) * k[j];
}

}  // namespace rigidlab::rk
