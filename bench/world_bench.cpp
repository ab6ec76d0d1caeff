// World step speed, in body-steps per second, for 1, 100 and 10,000 free bodies under gravity,
// for each integrator, side by side with a minimal hand-written Eigen loop over a
// std::vector of plain structs doing the same math (the practical limit). The engine also
// snapshots the state for undo and checks every body for NaN/Inf; the baseline does neither.
// The Euler family runs with the default gyroscopic mode, "conserving", on both sides, and
// once more with "implicit" (semi_implicit_implicit): the old default, for the cost of each.
// Goal: engine time / baseline time <= 1 (bench/run prints the ratios' inputs).
//   build/bench/world_bench --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <utility>
#include <random>
#include <vector>

#include "engine/world.hpp"

namespace {

using namespace rigidlab;

constexpr double dt = 1.0 / 240.0;

// The same bodies for both sides: boxes with random size, orientation and spin.
std::vector<Body> make_bodies(int n) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Body> bodies;
  for (int i = 0; i < n; ++i) {
    Body b = make_box_body(1.0 + 0.5 * u(rng), Vec3(1.5 + u(rng), 1.5 + u(rng), 1.5 + u(rng)));
    b.position = Vec3(10 * u(rng), 10 * u(rng), 10 * u(rng));
    b.orientation = quat_from_axis_angle(Vec3(u(rng), u(rng), 1.0), 3 * u(rng));
    b.velocity = Vec3(u(rng), u(rng), u(rng));
    b.angular_velocity = Vec3(3 * u(rng), 3 * u(rng), 3 * u(rng));
    b.shape = Shape{};  // free bodies: without a collision shape the step is integration alone
    bodies.push_back(b);
  }
  return bodies;
}

void engine_step(benchmark::State& state, Integrator integrator,
                 GyroscopicTerm gyroscopic = default_gyroscopic) {
  const int n = static_cast<int>(state.range(0));
  World world;
  world.set_integrator(integrator);
  if (integrator != Integrator::rk4) world.set_gyroscopic(gyroscopic);
  for (const Body& b : make_bodies(n)) world.add(b);
  for (auto _ : state) {
    world.step(dt);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n);
}

// ---- the baseline: what one would write by hand ---------------------------------------------

struct PlainBody {
  double inverse_mass;
  Mat3 inertia, inverse_inertia;
  Vec3 position;
  Quat orientation;
  Vec3 velocity, angular_velocity, force, torque;
};

std::vector<PlainBody> make_plain(int n) {
  std::vector<PlainBody> plain;
  for (const Body& b : make_bodies(n))
    plain.push_back({b.inverse_mass, b.inertia, b.inverse_inertia, b.position, b.orientation,
                     b.velocity, b.angular_velocity, b.force, b.torque});
  return plain;
}

Quat exact_rotation(const Quat& q, const Vec3& w, double h) {
  const Vec3 theta = h * w;
  const double angle = theta.norm();
  const double s = angle < 1e-4 ? 0.5 - angle * angle / 48.0 : std::sin(0.5 * angle) / angle;
  Quat r = Quat(std::cos(0.5 * angle), s * theta.x(), s * theta.y(), s * theta.z()) * q;
  r.normalize();
  return r;
}

// Torque impulse then one Newton step on the implicit gyroscopic term, in the body frame.
Vec3 new_angular_velocity(const PlainBody& b, const Mat3& r, double h) {
  Vec3 wb = r.transpose() * b.angular_velocity;
  wb += h * (b.inverse_inertia * (r.transpose() * b.torque));
  const Vec3 lb = b.inertia * wb;
  const Mat3 jacobian = b.inertia + h * (skew(wb) * b.inertia - skew(lb));
  wb -= jacobian.inverse() * (h * wb.cross(lb));
  return r * wb;
}

// The "conserving" rotation of engine/free_rotation.hpp written plainly, for the diagonal
// tensors of these boxes: a half kick, the splitting A(h/2) B(h) A(h/2) S(h) of the kinetic
// energy into rotations about the principal axes and a spherical part, a half kick. (Plainly:
// general quaternion products and a sort; the engine turns about fixed axes of a permuted
// frame instead, which is why it is faster than this loop. Against the implicit hand loop,
// the cost of the method itself shows: four sin/cos pairs and a chain of three rotations
// against one pair and a 3x3 solve.)
void conserving_rotation(PlainBody& b, double h) {
  const Vec3 m = b.inertia.diagonal(), inv = b.inverse_inertia.diagonal();
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&m](int i, int j) { return m[i] < m[j]; });
  const int k = order[1];
  const bool low_outside = std::abs(inv[order[0]] - inv[k]) >= std::abs(inv[order[2]] - inv[k]);
  const int outer = low_outside ? order[0] : order[2], inner = low_outside ? order[2] : order[0];
  const Mat3 r = b.orientation.toRotationMatrix();
  Vec3 pi = m.cwiseProduct(r.transpose() * b.angular_velocity) +
            0.5 * h * (r.transpose() * b.torque);
  Quat turn = Quat::Identity();
  for (const auto& [axis, t] : {std::pair{outer, 0.5 * h}, {inner, h}, {outer, 0.5 * h}}) {
    const double angle = t * (inv[axis] - inv[k]) * pi[axis];
    Quat rotation(std::cos(0.5 * angle), 0, 0, 0);
    rotation.vec()[axis] = std::sin(0.5 * angle);
    pi = rotation.conjugate() * pi;
    turn = turn * rotation;
  }
  b.orientation = (b.orientation * exact_rotation(turn, turn * (inv[k] * pi), h))
                      .normalized();  // turn ⊗ exp(h ω_k), ω_k = Π/Ik in the body frame
  const Mat3 r_end = b.orientation.toRotationMatrix();
  pi += 0.5 * h * (r_end.transpose() * b.torque);
  b.angular_velocity = r_end * inv.cwiseProduct(pi);
}

template <bool semi_implicit, bool conserving>
void baseline_euler(std::vector<PlainBody>& bodies, const Vec3& g, double h) {
  for (PlainBody& b : bodies) {
    if (conserving) {
      const Vec3 v = b.velocity + h * (b.inverse_mass * b.force + g);
      b.position += h * (semi_implicit ? v : b.velocity);
      b.velocity = v;
      conserving_rotation(b, h);
      b.force.setZero();
      b.torque.setZero();
      continue;
    }
    const Mat3 r = b.orientation.toRotationMatrix();
    const Vec3 v = b.velocity + h * (b.inverse_mass * b.force + g);
    const Vec3 w = new_angular_velocity(b, r, h);
    if (semi_implicit) b.velocity = v, b.angular_velocity = w;
    b.position += h * b.velocity;
    b.orientation = exact_rotation(b.orientation, b.angular_velocity, h);
    if (!semi_implicit) b.velocity = v, b.angular_velocity = w;
    b.force.setZero();
    b.torque.setZero();
  }
}

// RK4 of one free body with constant force and torque: the four stages in registers.
void baseline_rk4(std::vector<PlainBody>& bodies, const Vec3& g, double h) {
  using Vec4 = Eigen::Matrix<double, 4, 1, Eigen::DontAlign>;
  for (PlainBody& b : bodies) {
    const Vec3 a = b.inverse_mass * b.force + g;
    auto spin = [&b](const Vec4& q, const Vec3& w, Vec4& dq, Vec3& dw) {
      Quat qq;
      qq.coeffs() = q;
      const Mat3 r = qq.normalized().toRotationMatrix();
      const Vec3 wb = r.transpose() * w;
      dw = r * (b.inverse_inertia * (r.transpose() * b.torque - wb.cross(b.inertia * wb)));
      dq = 0.5 * (Quat(0, w.x(), w.y(), w.z()) * qq).coeffs();
    };
    const Vec4 q0 = b.orientation.coeffs();
    const Vec3 w0 = b.angular_velocity, v0 = b.velocity;
    Vec4 dq1, dq2, dq3, dq4;
    Vec3 dw1, dw2, dw3, dw4;
    spin(q0, w0, dq1, dw1);
    spin(q0 + 0.5 * h * dq1, w0 + 0.5 * h * dw1, dq2, dw2);
    spin(q0 + 0.5 * h * dq2, w0 + 0.5 * h * dw2, dq3, dw3);
    spin(q0 + h * dq3, w0 + h * dw3, dq4, dw4);
    b.position += h * (v0 + 0.5 * h * a);  // Σ of the stage velocities v0 + c h a
    b.velocity += h * a;
    b.orientation.coeffs() = q0 + h / 6 * (dq1 + 2 * (dq2 + dq3) + dq4);
    b.orientation.normalize();
    b.angular_velocity += h / 6 * (dw1 + 2 * (dw2 + dw3) + dw4);
    b.force.setZero();
    b.torque.setZero();
  }
}

void baseline_step(benchmark::State& state, Integrator integrator,
                   GyroscopicTerm gyroscopic = default_gyroscopic) {
  const int n = static_cast<int>(state.range(0));
  std::vector<PlainBody> bodies = make_plain(n);
  const Vec3 g(0, -9.81, 0);
  const bool conserving = gyroscopic == GyroscopicTerm::conserving;
  for (auto _ : state) {
    switch (integrator) {
      case Integrator::euler:
        if (conserving) baseline_euler<false, true>(bodies, g, dt);
        else baseline_euler<false, false>(bodies, g, dt);
        break;
      case Integrator::semi_implicit:
        if (conserving) baseline_euler<true, true>(bodies, g, dt);
        else baseline_euler<true, false>(bodies, g, dt);
        break;
      case Integrator::rk4: baseline_rk4(bodies, g, dt); break;
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n);
}

// A world with one force callback (a no-op): RK4 then evaluates forces stage by stage over all
// bodies (four passes) instead of integrating each body in one pass.
void engine_rk4_staged(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  World world;
  world.set_integrator(Integrator::rk4);
  world.add_force([](World&, double) {});
  for (const Body& b : make_bodies(n)) world.add(b);
  for (auto _ : state) {
    world.step(dt);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n);
}

}  // namespace

BENCHMARK_CAPTURE(engine_step, euler, Integrator::euler)->Arg(1)->Arg(100)->Arg(10000);
BENCHMARK_CAPTURE(baseline_step, euler, Integrator::euler)->Arg(1)->Arg(100)->Arg(10000);
BENCHMARK_CAPTURE(engine_step, semi_implicit, Integrator::semi_implicit)->Arg(1)->Arg(100)->Arg(10000);
BENCHMARK_CAPTURE(baseline_step, semi_implicit, Integrator::semi_implicit)->Arg(1)->Arg(100)->Arg(10000);
BENCHMARK_CAPTURE(engine_step, semi_implicit_implicit, Integrator::semi_implicit,
                  GyroscopicTerm::implicit)->Arg(1)->Arg(100)->Arg(10000);
BENCHMARK_CAPTURE(baseline_step, semi_implicit_implicit, Integrator::semi_implicit,
                  GyroscopicTerm::implicit)->Arg(1)->Arg(100)->Arg(10000);
BENCHMARK_CAPTURE(engine_step, rk4, Integrator::rk4)->Arg(1)->Arg(100)->Arg(10000);
BENCHMARK_CAPTURE(baseline_step, rk4, Integrator::rk4)->Arg(1)->Arg(100)->Arg(10000);
BENCHMARK(engine_rk4_staged)->Arg(1)->Arg(100)->Arg(10000);

BENCHMARK_MAIN();
