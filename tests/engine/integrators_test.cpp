// Tests for engine/integrators.cpp against closed forms and conservation laws, run through a
// World (the integrators' only caller):
//   - measured convergence orders on a harmonic oscillator x(t) = cos t (≈1, ≈1, ≈4);
//   - constant acceleration: RK4 exact; the Euler variants miss ½ g t² by ∓½ g t dt exactly
//     (003_* "Explicit Euler": the car at 10 m/s² reaches 550 m, not 500 m, after 10 s of 1 s);
//   - torque-free motion: conservation of world angular momentum and kinetic energy, the
//     closed-form precession of an axisymmetric body, the intermediate-axis (Dzhanibekov) flip;
//   - at 60 Hz the explicit gyroscopic term gains energy, the implicit one never does;
//   - the one integration core (engine/runge_kutta.hpp): its tableaux meet Butcher's order
//     conditions, its semi_implicit is symplectic (the one-step map of an oscillator has
//     determinant 1), and a world body and a free-floating articulation of the same body,
//     both stepped by it, move identically.
#include "engine/integrators.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/articulation.hpp"
#include "engine/runge_kutta.hpp"
#include "engine/world.hpp"

namespace rigidlab {
namespace {

constexpr double pi = 3.14159265358979323846;

// A world without gravity holding one body.
struct OneBody {
  World world;
  explicit OneBody(const Body& b, Integrator integrator, GyroscopicTerm g = GyroscopicTerm::implicit) {
    world.set_gravity(Vec3::Zero());
    world.set_integrator(integrator);
    world.set_gyroscopic(g);
    world.add(b);
  }
  Body& body() { return world.bodies()[0]; }
  void run(double dt, double duration) {
    const long n = std::lround(duration / dt);
    for (long i = 0; i < n; ++i) world.step(dt);
  }
};

// |x(T) − cos T| for a unit mass on a spring of k = 1 to the origin, x(0) = 1, v(0) = 0.
double oscillator_error(Integrator integrator, double dt) {
  OneBody o(make_sphere_body(1.0, 0.1), integrator);
  o.body().position = Vec3(1, 0, 0);
  Spring s;
  s.a = o.world.store().id_at(0);
  s.stiffness = 1.0;
  o.world.add_spring(s);
  const double duration = 2.0;
  o.run(dt, duration);
  return std::abs(o.body().position.x() - std::cos(duration));
}

double measured_order(Integrator integrator, double dt) {
  return std::log2(oscillator_error(integrator, dt) / oscillator_error(integrator, dt / 2));
}

TEST(Convergence, HarmonicOscillatorOrders) {
  EXPECT_NEAR(measured_order(Integrator::euler, 1e-3), 1.0, 0.05);
  EXPECT_NEAR(measured_order(Integrator::semi_implicit, 1e-3), 1.0, 0.05);
  EXPECT_NEAR(measured_order(Integrator::rk4, 0.05), 4.0, 0.1);
}

// x(t) = x0 + v0 t + ½ g t² under gravity alone.
TEST(ConstantAcceleration, Rk4IsExactAndEulerErrorsAreTheKnownSums) {
  const Vec3 g(0, -9.81, 0), x0(1, 2, 3), v0(4, 5, -6);
  const double dt = 0.1, t = 3.0;
  const Vec3 exact = x0 + v0 * t + 0.5 * g * t * t;
  for (Integrator integrator : {Integrator::rk4, Integrator::euler, Integrator::semi_implicit}) {
    World w;
    w.set_integrator(integrator);
    Body b = make_sphere_body(1.0, 1.0);
    b.position = x0;
    b.velocity = v0;
    w.add(b);
    for (int i = 0; i < 30; ++i) w.step(dt);
    // Σ v_k dt over n steps: explicit Euler uses v_0..v_{n−1}, semi-implicit v_1..v_n.
    const Vec3 want = integrator == Integrator::rk4     ? exact
                      : integrator == Integrator::euler ? Vec3(exact - 0.5 * g * t * dt)
                                                        : Vec3(exact + 0.5 * g * t * dt);
    EXPECT_LT((w.bodies()[0].position - want).norm(), 1e-12) << integrator_names[int(integrator)];
    EXPECT_LT((w.bodies()[0].velocity - (v0 + g * t)).norm(), 1e-12);
  }
}

TEST(ConstantAcceleration, TheCarOf003) {
  World w;  // 10 m/s² for 10 s in 1 s steps: the table of 003_* "Explicit Euler" gives 550 m
  w.set_gravity(Vec3(10, 0, 0));
  w.add(make_sphere_body(1.0, 1.0));
  for (int i = 0; i < 10; ++i) w.step(1.0);
  EXPECT_NEAR(w.bodies()[0].position.x(), 550.0, 1e-12);
}

Body tumbling_body() {
  Body b = make_body(2.0, Vec3(1, 2, 3).asDiagonal());
  b.orientation = quat_from_axis_angle(Vec3(1, 2, 3), 0.7);
  b.angular_velocity = Vec3(1.0, 0.3, -2.0);
  return b;
}

// The largest drift over the whole 10 s, not only at the end (a drift that comes and goes
// would pass an end-only check). Measured: about 5e-13 for L, 7e-14 for T.
TEST(TorqueFree, Rk4ConservesAngularMomentumAndEnergy) {
  OneBody o(tumbling_body(), Integrator::rk4);
  const Vec3 l0 = angular_momentum(o.body());
  const double e0 = kinetic_energy(o.body());
  double l_drift = 0.0, e_drift = 0.0;
  for (int i = 0; i < 10000; ++i) {
    o.world.step(1e-3);
    l_drift = std::max(l_drift, (angular_momentum(o.body()) - l0).norm() / l0.norm());
    e_drift = std::max(e_drift, std::abs(kinetic_energy(o.body()) - e0) / e0);
  }
  EXPECT_LT(l_drift, 1e-11);
  EXPECT_LT(e_drift, 1e-11);
  // And the body really tumbled: ω changed direction.
  EXPECT_GT((o.body().angular_velocity - Vec3(1.0, 0.3, -2.0)).norm(), 0.1);
}

// Euler's equations for I1 = I2: in the body frame ω⊥ turns at Ω = (I3 − I1)/I1 · ω3, so
// ω_b(t) = (a cos Ωt, a sin Ωt, ω3) (002_* "Torque-Free Motion").
TEST(TorqueFree, AxisymmetricBodyPrecessesAtTheClosedFormRate) {
  const double i1 = 1.0, i3 = 1.8, a = 0.4, w3 = 3.0;  // a flat disc: I3 <= 2 I1
  Body b = make_body(1.0, Vec3(i1, i1, i3).asDiagonal());
  b.angular_velocity = Vec3(a, 0, w3);
  OneBody o(b, Integrator::rk4);
  const double rate = (i3 - i1) / i1 * w3;
  const double dt = 1e-3;
  for (int step = 1; step <= 4000; ++step) {
    o.world.step(dt);
    if (step % 500 != 0) continue;
    const double t = step * dt;
    const Vec3 body_omega = o.body().orientation.conjugate() * o.body().angular_velocity;
    EXPECT_LT((body_omega - Vec3(a * std::cos(rate * t), a * std::sin(rate * t), w3)).norm(), 1e-9)
        << "t = " << t;
  }
}

// Spin about principal axis `axis` (of I = diag(1, 2, 3)) with a small perturbation on the
// others; returns the smallest body-frame component along that axis over 20 s, relative to
// the initial spin.
double smallest_spin_fraction(int axis, Integrator integrator) {
  Body b = make_body(1.0, Vec3(1, 2, 3).asDiagonal());
  Vec3 omega = Vec3::Constant(1e-3);
  omega[axis] = 2.0;
  b.angular_velocity = omega;
  OneBody o(b, integrator);
  double smallest = 1.0;
  for (int step = 0; step < 2000; ++step) {
    o.world.step(0.01);
    const Vec3 body_omega = o.body().orientation.conjugate() * o.body().angular_velocity;
    smallest = std::min(smallest, body_omega[axis] / 2.0);
  }
  return smallest;
}

TEST(TorqueFree, IntermediateAxisFlipsAndTheOthersDoNot) {
  for (Integrator integrator : {Integrator::rk4, Integrator::semi_implicit}) {
    EXPECT_LT(smallest_spin_fraction(1, integrator), -0.9);  // the spin reverses
    EXPECT_GT(smallest_spin_fraction(0, integrator), 0.99);
    EXPECT_GT(smallest_spin_fraction(2, integrator), 0.99);
  }
}

// Catto, "Numerical Methods" (GDC 2015), cited by 001_*: with semi-implicit Euler at 60 Hz an
// explicit gyroscopic term feeds energy into a tumbling body; the implicit one does not.
TEST(Gyroscopic, ExplicitGainsEnergyImplicitNeverDoes) {
  Body b = make_box_body(1.0, Vec3(0.2, 1.0, 3.0));
  b.angular_velocity = Vec3(0.5, 8.0, 0.5);
  OneBody explicit_world(b, Integrator::semi_implicit, GyroscopicTerm::explicit_);
  OneBody implicit_world(b, Integrator::semi_implicit, GyroscopicTerm::implicit);
  const double e0 = kinetic_energy(b);
  double implicit_max = 0.0;
  for (int step = 0; step < 600; ++step) {
    explicit_world.world.step(1.0 / 60);
    implicit_world.world.step(1.0 / 60);
    implicit_max = std::max(implicit_max, kinetic_energy(implicit_world.body()));
  }
  EXPECT_GT(kinetic_energy(explicit_world.body()), 1.1 * e0);
  EXPECT_LE(implicit_max, e0 * (1 + 1e-12));
}

TEST(Gyroscopic, OffKeepsBodyAngularVelocityConstantInTheWorld) {
  OneBody o(tumbling_body(), Integrator::semi_implicit, GyroscopicTerm::off);
  o.run(0.01, 1.0);
  EXPECT_LT((o.body().angular_velocity - Vec3(1.0, 0.3, -2.0)).norm(), 1e-13);
}

// The Newton step solves backward Euler I(ω' − ω) + dt ω' × Iω' = 0 to second order: its
// residual is far below the residual of doing nothing, and shrinks like dt² relative to it.
TEST(Gyroscopic, NewtonStepConvergesQuadratically) {
  const Mat3 inertia = Vec3(1, 2, 3).asDiagonal();
  const Vec3 omega(1.0, 2.0, -0.5);
  auto residual = [&](const Vec3& w, double dt) {
    return (inertia * (w - omega) + dt * w.cross(inertia * w)).norm();
  };
  double previous_ratio = 0.0;
  for (double dt : {1e-2, 5e-3}) {
    const double ratio = residual(implicit_gyroscopic_step(inertia, omega, dt), dt) /
                         residual(omega, dt);
    EXPECT_LT(ratio, 0.05);
    if (previous_ratio > 0.0) EXPECT_NEAR(previous_ratio / ratio, 4.0, 0.5);
    previous_ratio = ratio;
  }
  // Isotropic inertia: ω × Iω = 0, nothing to do.
  EXPECT_EQ(implicit_gyroscopic_step(Mat3::Identity() * 2.0, omega, 0.1), omega);
}

TEST(RotateBy, IsTheExactRotationOfOmegaDt) {
  const Quat q = quat_from_axis_angle(Vec3(1, 0, 1), 0.3);
  const Vec3 omega(0.2, -0.5, 1.5);
  const double dt = 0.7;
  const Quat want = quat_from_axis_angle(omega, omega.norm() * dt) * q;
  EXPECT_LT((rotate_by(q, omega, dt).coeffs() - want.coeffs()).norm(), 1e-15);
  // The small-angle series agrees with the closed form on both sides of its switch.
  for (double angle : {0.99e-4, 1.01e-4, 1e-9}) {
    const Quat r = rotate_by(Quat::Identity(), Vec3(0, 0, angle), 1.0);
    EXPECT_NEAR(r.z(), std::sin(angle / 2), 1e-18);
    EXPECT_NEAR(r.w(), std::cos(angle / 2), 1e-16);
  }
  EXPECT_EQ(rotate_by(q, Vec3::Zero(), 1.0).coeffs(), q.normalized().coeffs());
}

TEST(Names, ParseEveryNameAndRefuseOthers) {
  EXPECT_EQ(parse_integrator("rk4"), Integrator::rk4);
  EXPECT_EQ(parse_integrator("semi_implicit"), Integrator::semi_implicit);
  EXPECT_EQ(parse_integrator("RK4"), std::nullopt);
  EXPECT_EQ(parse_gyroscopic("explicit"), GyroscopicTerm::explicit_);
  EXPECT_EQ(parse_gyroscopic("off"), GyroscopicTerm::off);
  EXPECT_EQ(parse_gyroscopic(""), std::nullopt);
}

// Constant force and torque: the single-pass RK4 (no force elements) and the staged RK4 (a
// callback that adds nothing) integrate the same ODE and must agree to rounding.
TEST(Rk4, SinglePassAndStagedPathsAgree) {
  World plain, staged;
  staged.add_force([](World&, double) {});
  for (World* w : {&plain, &staged}) {
    w->set_integrator(Integrator::rk4);
    w->add(tumbling_body());
    for (int i = 0; i < 100; ++i) {
      apply_force(w->bodies()[0], Vec3(1, 2, 3), Vec3(0.1, 0.2, 0.3));
      w->step(0.01);
    }
  }
  const Body &a = plain.bodies()[0], &b = staged.bodies()[0];
  EXPECT_LT((a.position - b.position).norm(), 1e-13);
  EXPECT_LT((a.angular_velocity - b.angular_velocity).norm(), 1e-13);
  EXPECT_LT((a.orientation.coeffs() - b.orientation.coeffs()).norm(), 1e-13);
}

// The staged RK4 evaluates force callbacks at the stage times and states, checked against a
// closed form and not against the built-in spring: a callback force m(−x + cos 2t) gives
// ẍ = −x + cos 2t, whose solution from rest at 0 is x = (cos t − cos 2t)/3. Fourth order
// shows only if the callback sees the stage states (the −x) at the stage times (the cos 2t);
// evaluated once per step at its start, the error would shrink as dt¹. The error is the
// largest over 3 s (at single instants errors of opposite signs can cancel).
double forced_oscillator_error(double dt) {
  OneBody o(make_sphere_body(2.0, 0.1), Integrator::rk4);
  o.world.add_force([](World& w, double t) {
    Body& b = w.bodies()[0];
    apply_force(b, Vec3(b.mass * (-b.position.x() + std::cos(2 * t)), 0, 0));
  });
  double largest = 0.0;
  for (long i = 1; i <= std::lround(3.0 / dt); ++i) {
    o.world.step(dt);
    const double t = o.world.time();
    const double exact = (std::cos(t) - std::cos(2 * t)) / 3;
    largest = std::max(largest, std::abs(o.body().position.x() - exact));
  }
  return largest;
}

TEST(Rk4, CallbackForcesConvergeAtFourthOrderToTheClosedForm) {
  const double coarse = forced_oscillator_error(0.1), fine = forced_oscillator_error(0.05);
  EXPECT_LT(coarse, 1e-5);
  EXPECT_NEAR(std::log2(coarse / fine), 4.0, 0.1);
}

// A stage state that overflows ends the step before any callback sees it: the callback here
// records every position it is shown (velocity 1e306 m/s, dt = 1000 s: the second stage's
// position x + dt/2 v is inf). Before, it was shown (inf, 0, 0) and could keep it.
TEST(Rk4, CallbacksNeverSeeANonFiniteStageState) {
  Body b = make_sphere_body(1.0, 1.0);
  b.velocity = Vec3(1e306, 0, 0);
  OneBody o(b, Integrator::rk4);
  std::vector<Vec3> seen;
  o.world.add_force([&seen](World& w, double) { seen.push_back(w.bodies()[0].position); });
  try {
    o.world.step(1000.0);
    ADD_FAILURE() << "no error";
  } catch (const StepError& e) {
    EXPECT_EQ(std::string(e.what()),
              "body 1 of 1 would get a non-finite position in the step from t = 0 s to "
              "t = 1000 s; nothing was changed (the world is still at t = 0 s)");
  }
  EXPECT_EQ(seen, std::vector<Vec3>{Vec3::Zero()}) << "only the first (finite) stage";
  EXPECT_EQ(o.body().position, Vec3::Zero());
  EXPECT_EQ(o.body().velocity, Vec3(1e306, 0, 0));
}

// ---- the integration core --------------------------------------------------------------------

// Butcher's order conditions up to order 4 for an explicit tableau (Butcher 2016, 31; Hairer,
// Nørsett, Wanner, "Solving ODEs I", II.2 Table 2.2): Σ bᵢ = 1, Σ bᵢcᵢ = ½, Σ bᵢcᵢ² = ⅓,
// Σ bᵢaᵢⱼcⱼ = ⅙, Σ bᵢcᵢ³ = ¼, Σ bᵢcᵢaᵢⱼcⱼ = ⅛, Σ bᵢaᵢⱼcⱼ² = 1/12, Σ bᵢaᵢⱼaⱼₖcₖ = 1/24;
// and cᵢ = Σⱼ aᵢⱼ (the stage times). Returns the order the tableau `a`, `b` reaches (0..4).
template <int S>
int order_of(const double (&a)[S][S], const double (&b)[S], const double (&c)[S]) {
  auto sum = [](auto term) {
    double s = 0.0;
    for (int i = 0; i < S; ++i) s += term(i);
    return s;
  };
  auto ac = [&](int i, int power) {  // Σⱼ aᵢⱼ cⱼ^power
    double s = 0.0;
    for (int j = 0; j < S; ++j) s += a[i][j] * std::pow(c[j], power);
    return s;
  };
  for (int i = 0; i < S; ++i)
    if (std::abs(c[i] - ac(i, 0)) > 1e-15) return 0;
  auto near = [](double x, double want) { return std::abs(x - want) < 1e-15; };
  if (!near(sum([&](int i) { return b[i]; }), 1.0)) return 0;
  if (!near(sum([&](int i) { return b[i] * c[i]; }), 0.5)) return 1;
  if (!near(sum([&](int i) { return b[i] * c[i] * c[i]; }), 1.0 / 3) ||
      !near(sum([&](int i) { return b[i] * ac(i, 1); }), 1.0 / 6))
    return 2;
  const double aac = sum([&](int i) {
    double s = 0.0;
    for (int j = 0; j < S; ++j) s += a[i][j] * ac(j, 1);
    return b[i] * s;
  });
  if (!near(sum([&](int i) { return b[i] * std::pow(c[i], 3); }), 0.25) ||
      !near(sum([&](int i) { return b[i] * c[i] * ac(i, 1); }), 0.125) ||
      !near(sum([&](int i) { return b[i] * ac(i, 2); }), 1.0 / 12) || !near(aac, 1.0 / 24))
    return 3;
  return 4;
}

TEST(IntegrationCore, TableauxMeetTheirOrderConditions) {
  EXPECT_EQ(order_of(rk::euler.av, rk::euler.bv, rk::euler.c), 1);
  EXPECT_EQ(order_of(rk::midpoint.av, rk::midpoint.bv, rk::midpoint.c), 2);
  EXPECT_EQ(order_of(rk::heun.av, rk::heun.bv, rk::heun.c), 2);
  EXPECT_EQ(order_of(rk::rk4.av, rk::rk4.bv, rk::rk4.c), 4);
  EXPECT_EQ(order_of(rk::rk4.aq, rk::rk4.bq, rk::rk4.c), 4);
  // semi_implicit's velocity part is explicit Euler; only its first stage's acceleration is
  // ever evaluated.
  EXPECT_EQ(order_of(rk::semi_implicit.av, rk::semi_implicit.bv, rk::semi_implicit.c), 1);
  EXPECT_TRUE(rk::velocity_slope_used(rk::semi_implicit, 0));
  EXPECT_FALSE(rk::velocity_slope_used(rk::semi_implicit, 1));
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(rk::velocity_slope_used(rk::rk4, i));
}

// A linear system x'' = −x through the core as the world's bodies see it: one step is a 2×2
// matrix acting on (x, v). Symplectic Euler preserves area (det = 1, Hairer et al. GNI VI.3);
// explicit Euler multiplies it by 1 + h² exactly (its matrix is [[1, h], [−h, 1]]), and RK4's
// determinant is that of the degree-4 Taylor polynomial of the rotation by h, 1 − h⁶/72 + h⁸/576.
struct Oscillator {
  double x0, v0, x, v, kx[4], kv[4];
  void begin() {
    x0 = x;
    v0 = v;
  }
  void slope(int i, double, bool velocity) {
    kx[i] = v;
    if (velocity) kv[i] = -x;
  }
  bool move(double h, const double* aq, const double* av, int count) {
    rk::combine(x, x0, h, aq, kx, count);
    rk::combine(v, v0, h, av, kv, count);
    return true;
  }
};

template <int S>
double step_determinant(const rk::Tableau<S>& method, double h) {
  Oscillator a{0, 0, 1, 0, {}, {}}, b{0, 0, 0, 1, {}, {}};  // the images of (1, 0) and (0, 1)
  rk::runge_kutta(method, a, 0.0, h);
  rk::runge_kutta(method, b, 0.0, h);
  return a.x * b.v - a.v * b.x;
}

TEST(IntegrationCore, OneStepDeterminantsOfAnOscillator) {
  const double h = 0.1;
  EXPECT_NEAR(step_determinant(rk::semi_implicit, h), 1.0, 1e-15);
  EXPECT_NEAR(step_determinant(rk::euler, h), 1.0 + h * h, 1e-15);
  EXPECT_NEAR(step_determinant(rk::rk4, h), 1.0 - std::pow(h, 6) / 72 + std::pow(h, 8) / 576,
              1e-15);
}

// The same tumbling body (mass 2, principal inertia 1, 2, 3) as a world body and as a
// free-floating articulation of one link welded to its base: both are stepped by the core with
// the same tableau and the same quaternion treatment, so their motions agree to rounding
// (Newton-Euler in the world, the articulated-body algorithm in the articulation).
TEST(IntegrationCore, WorldBodyAndFreeArticulationMoveAlike) {
  const Body b = tumbling_body();
  OneBody o(b, Integrator::rk4);
  Articulation art(BaseType::free, Vec3::Zero(), b.orientation);
  LinkSpec link;
  link.joint = JointType::fixed;
  link.mass = 2.0;
  link.inertia = Vec3(1, 2, 3).asDiagonal();
  art.add_link(link);
  art.set_gravity(Vec3::Zero());
  art.set_integrator(Integrator::rk4);
  Eigen::VectorXd v = art.v();
  v.segment<3>(3) = b.angular_velocity;
  art.set_state(art.q(), v);
  double worst = 0.0;
  for (int i = 0; i < 1000; ++i) {
    o.world.step(0.01);
    art.step(0.01);
    const Quat qa(art.q()[3], art.q()[4], art.q()[5], art.q()[6]);
    const Eigen::Vector3d wa = art.v().segment<3>(3);
    worst = std::max({worst, qa.angularDistance(o.body().orientation),
                      (wa - o.body().angular_velocity).norm()});
  }
  EXPECT_LT(worst, 1e-11);
}

}  // namespace
}  // namespace rigidlab
