// engine/ode.hpp against closed forms: the car of 003_* "Explicit Euler", the projectile of
// the same document, Taylor series of e^h, exact polynomial solutions, and the measured
// convergence order on the harmonic oscillator.
#include "engine/ode.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <stdexcept>

namespace rigidlab::ode {
namespace {

// Integrates x'' = accel from (x0, v0) at t = 0 for `steps` steps of dt.
template <class State, class Accel>
void integrate(Integrator method, State& x, State& v, double dt, int steps, Accel accel) {
  for (int n = 0; n < steps; ++n) step(method, n * dt, x, v, dt, accel);
}

TEST(OdeSecondOrder, CarOfDocument003) {
  // 003_* "Explicit Euler": a car at rest accelerates at 10 m/s², Δt = 1 s, 10 s. Analytic
  // ½ a t² = 500 m; the document's table (velocity first) reaches 550 m; Euler with the old
  // velocity lags behind, Σ_{n<10} 10 n = 450 m; RK4 is exact for a constant acceleration.
  const auto accel = [](double, double, double) { return 10.0; };
  const struct { Integrator method; double x; } cases[] = {
      {Integrator::euler, 450.0},
      {Integrator::semi_implicit, 550.0},
      {Integrator::rk4, 500.0}};
  for (const auto& c : cases) {
    double x = 0.0, v = 0.0;
    integrate(c.method, x, v, 1.0, 10, accel);
    EXPECT_NEAR(x, c.x, 1e-12);
    EXPECT_NEAR(v, 100.0, 1e-12);  // every method gets v = a t right for constant a
  }
}

TEST(OdeSecondOrder, DocumentTableSemiImplicitRowByRow) {
  // The rows of the table in 003_* "Explicit Euler": r = 10, 30, 60, 100, ..., 550.
  const double table[] = {10, 30, 60, 100, 150, 210, 280, 360, 450, 550};
  double x = 0.0, v = 0.0;
  for (int n = 0; n < 10; ++n) {
    semi_implicit_euler_step(n * 1.0, x, v, 1.0, [](double, double, double) { return 10.0; });
    EXPECT_NEAR(x, table[n], 1e-12) << "t = " << n + 1;
    EXPECT_NEAR(v, 10.0 * (n + 1), 1e-12);
  }
}

TEST(OdeSecondOrder, ProjectileIsExactForRk4) {
  // 003_* "Explicit Euler" (analytic part): y(t) = ½ g t² + v0 t + y0 with g = −9.8 m/s².
  const Vec3 g(0.0, -9.8, 0.0), x0(1.0, 20.0, -2.0), v0(3.0, 15.0, 0.5);
  Vec3 x = x0, v = v0;
  const double dt = 0.1;
  for (int n = 1; n <= 40; ++n) {
    rk4_step((n - 1) * dt, x, v, dt, [&](double, const Vec3&, const Vec3&) { return g; });
    const double t = n * dt;
    const Vec3 exact = 0.5 * g * t * t + v0 * t + x0;
    EXPECT_NEAR((x - exact).norm(), 0.0, 1e-12) << "t = " << t;
    EXPECT_NEAR((v - (g * t + v0)).norm(), 0.0, 1e-12);
  }
}

TEST(OdeSecondOrder, Rk4UsesTheStageTimes) {
  // x'' = t from rest: x = t³/6, v = t²/2. RK4's quadrature is Simpson's rule, exact here;
  // a wrong stage time would break it.
  double x = 0.0, v = 0.0;
  const double dt = 0.25;
  integrate(Integrator::rk4, x, v, dt, 8, [](double t, double, double) { return t; });
  EXPECT_NEAR(x, 8.0 / 6.0, 1e-13);  // t = 2
  EXPECT_NEAR(v, 2.0, 1e-13);
}

// The error of (x, v) at T = 2 s for x'' = −ω² x, x(0) = 1, v(0) = 0 (ω = 3 rad/s); the
// closed form is x = cos ωt, v = −ω sin ωt.
double oscillator_error(Integrator method, double dt) {
  const double omega = 3.0, duration = 2.0;
  const int steps = static_cast<int>(std::lround(duration / dt));
  double x = 1.0, v = 0.0;
  integrate(method, x, v, dt, steps,
            [omega](double, double position, double) { return -omega * omega * position; });
  return std::hypot(x - std::cos(omega * duration), v + omega * std::sin(omega * duration));
}

TEST(OdeSecondOrder, ConvergenceOrdersOnTheHarmonicOscillator) {
  // Global error ~ C dt^p: p = log2(e(dt) / e(dt/2)).
  const struct { Integrator method; double dt; double order; } cases[] = {
      {Integrator::euler, 1e-3, 1.0},
      {Integrator::semi_implicit, 1e-3, 1.0},
      {Integrator::rk4, 2e-2, 4.0}};
  for (const auto& c : cases) {
    const double order =
        std::log2(oscillator_error(c.method, c.dt) / oscillator_error(c.method, c.dt / 2));
    EXPECT_NEAR(order, c.order, 0.1) << integrator_names[static_cast<int>(c.method)];
  }
}

TEST(OdeSecondOrder, SemiImplicitKeepsTheOscillatorEnergyBounded) {
  // Symplectic Euler conserves a modified energy, so E stays within O(dt) of E0 forever;
  // explicit Euler multiplies E by (1 + ω²dt²) every step (Hairer et al. I.1).
  const double omega = 2.0, dt = 0.01;
  const auto accel = [omega](double, double x, double) { return -omega * omega * x; };
  const auto energy = [omega](double x, double v) { return 0.5 * v * v + 0.5 * omega * omega * x * x; };
  double xs = 1.0, vs = 0.0, xe = 1.0, ve = 0.0;
  const double e0 = energy(1.0, 0.0);
  double worst = 0.0;
  for (int n = 0; n < 100000; ++n) {
    semi_implicit_euler_step(n * dt, xs, vs, dt, accel);
    euler_step(n * dt, xe, ve, dt, accel);
    worst = std::max(worst, std::abs(energy(xs, vs) - e0) / e0);
  }
  EXPECT_LT(worst, omega * dt);  // bounded, of order ω dt
  const double euler_growth = std::pow(1.0 + omega * omega * dt * dt, 100000);
  EXPECT_NEAR(energy(xe, ve) / e0, euler_growth, 1e-9 * euler_growth);
}

TEST(OdeSecondOrder, AThrowingAccelerationLeavesTheStateUnchanged) {
  for (Integrator method :
       {Integrator::euler, Integrator::semi_implicit, Integrator::rk4}) {
    Vec3 x(1, 2, 3), v(4, 5, 6);
    int calls = 0;
    const auto accel = [&](double, const Vec3&, const Vec3&) -> Vec3 {
      if (++calls == 3 || method != Integrator::rk4) throw std::runtime_error("boom");
      return Vec3(1, 1, 1);
    };
    EXPECT_THROW(step(method, 0.0, x, v, 0.1, accel), std::runtime_error);
    EXPECT_EQ(x, Vec3(1, 2, 3));
    EXPECT_EQ(v, Vec3(4, 5, 6));
  }
}

// ---- first order -----------------------------------------------------------------------------

TEST(OdeFirstOrder, OneStepOfExponentialGrowthIsItsTaylorPolynomial) {
  // y' = y, y(0) = 1: one step of an order-p Runge-Kutta method applied to a linear autonomous
  // equation gives the Taylor polynomial of e^h of degree p (Butcher 2016, 23).
  const auto f = [](double, double y) { return y; };
  for (double h : {0.5, 0.1, 1e-3}) {
    const double taylor2 = 1 + h + h * h / 2;
    const double taylor4 = taylor2 + h * h * h / 6 + h * h * h * h / 24;
    EXPECT_NEAR(step(FirstOrderMethod::euler, 0.0, 1.0, h, f), 1 + h, 1e-15);
    EXPECT_NEAR(step(FirstOrderMethod::midpoint, 0.0, 1.0, h, f), taylor2, 1e-15);
    EXPECT_NEAR(step(FirstOrderMethod::heun, 0.0, 1.0, h, f), taylor2, 1e-15);
    EXPECT_NEAR(step(FirstOrderMethod::rk4, 0.0, 1.0, h, f), taylor4, 1e-15);
  }
}

TEST(OdeFirstOrder, QuadratureOfPolynomialsInTime) {
  // y' = g(t): the methods become quadrature rules. Midpoint and trapezoid are exact for
  // linear g, Simpson's rule (RK4) for cubic g.
  const double t = 0.7, h = 0.3;
  const auto linear = [](double s, double) { return 2.0 * s; };    // y = s²
  const auto cubic = [](double s, double) { return 4.0 * s * s * s; };  // y = s⁴
  const double linear_exact = (t + h) * (t + h) - t * t;
  EXPECT_NEAR(step(FirstOrderMethod::midpoint, t, 0.0, h, linear), linear_exact, 1e-15);
  EXPECT_NEAR(step(FirstOrderMethod::heun, t, 0.0, h, linear), linear_exact, 1e-15);
  EXPECT_NEAR(step(FirstOrderMethod::euler, t, 0.0, h, linear), 2 * t * h, 1e-15);
  EXPECT_NEAR(step(FirstOrderMethod::rk4, t, 0.0, h, cubic), std::pow(t + h, 4) - std::pow(t, 4),
              1e-15);
}

// The error at T = 1 of y' = −2 t y, y(0) = 1 (closed form e^{−t²}) with a VectorXd state of
// two copies, which must agree.
double gaussian_error(FirstOrderMethod method, double dt) {
  const auto f = [](double t, const Eigen::VectorXd& y) -> Eigen::VectorXd { return -2 * t * y; };
  Eigen::VectorXd y = Eigen::VectorXd::Constant(2, 1.0);
  const int steps = static_cast<int>(std::lround(1.0 / dt));
  for (int n = 0; n < steps; ++n) y = step(method, n * dt, y, dt, f);
  EXPECT_EQ(y[0], y[1]);
  return std::abs(y[0] - std::exp(-1.0));
}

TEST(OdeFirstOrder, ConvergenceOrders) {
  const struct { FirstOrderMethod method; double dt; double order; } cases[] = {
      {FirstOrderMethod::euler, 1e-3, 1.0},
      {FirstOrderMethod::midpoint, 1e-3, 2.0},
      {FirstOrderMethod::heun, 1e-3, 2.0},
      {FirstOrderMethod::rk4, 2e-2, 4.0}};
  for (const auto& c : cases) {
    const double order =
        std::log2(gaussian_error(c.method, c.dt) / gaussian_error(c.method, c.dt / 2));
    EXPECT_NEAR(order, c.order, 0.1) << first_order_method_names[static_cast<int>(c.method)];
  }
}

TEST(OdeFirstOrder, Vec3StateRotation) {
  // y' = ω × y with ω along z: in the xy plane this is u' = iω u for u = x + iy, and one RK4
  // step multiplies u by the Taylor polynomial T4(iωh) of e^{iωh}; z stays constant.
  const Vec3 omega(0, 0, 1.5);
  Vec3 y(1, 0, 0.5);
  const double dt = 0.01;
  const int steps = 100;
  for (int n = 0; n < steps; ++n)
    y = rk4_step(n * dt, y, dt, [&](double, const Vec3& p) -> Vec3 { return omega.cross(p); });
  const std::complex<double> z(0.0, 1.5 * dt);
  const std::complex<double> u = std::pow(1.0 + z + z * z / 2.0 + z * z * z / 6.0 +
                                              z * z * z * z / 24.0, steps);
  EXPECT_NEAR((y - Vec3(u.real(), u.imag(), 0.5)).norm(), 0.0, 1e-13);
  // And it is within the truncation error of the exact rotation by 1.5 rad.
  EXPECT_NEAR((y - Vec3(std::cos(1.5), std::sin(1.5), 0.5)).norm(), 0.0, 1e-9);
}

TEST(OdeMethods, NamesParse) {
  EXPECT_EQ(parse_integrator("euler"), Integrator::euler);
  EXPECT_EQ(parse_integrator("semi_implicit"), Integrator::semi_implicit);
  EXPECT_EQ(parse_integrator("rk4"), Integrator::rk4);
  EXPECT_FALSE(parse_integrator("midpoint").has_value());
  EXPECT_EQ(parse_first_order_method("heun"), FirstOrderMethod::heun);
  EXPECT_EQ(parse_first_order_method("midpoint"), FirstOrderMethod::midpoint);
  EXPECT_FALSE(parse_first_order_method("RK4").has_value());
  EXPECT_FALSE(parse_first_order_method("").has_value());
}

}  // namespace
}  // namespace rigidlab::ode
