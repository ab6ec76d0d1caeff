// Joints against contacts in the same run (issue 14, "Performance"): Box2D v3's joint_grid
// benchmark (an N x N grid of spheres joined to their right and lower neighbours by hinges,
// 2N(N−1) joints: 19,800 at N = 100; the middle of the top row static; 60 Hz, the default
// solver) against a contact scene (N x N spheres resting on the ground, one contact each),
// both per constraint and per step. bench/run prints µs per joint, µs per contact and their
// ratio, and the per-joint cost at N = 25, 50, 100 (linear: flat).
#include <benchmark/benchmark.h>

#include <memory>

#include "engine/joint.hpp"
#include "engine/world.hpp"

namespace rigidlab {
namespace {

std::unique_ptr<World> joint_grid(int n) {
  auto w = std::make_unique<World>();
  std::vector<BodyId> ids;
  for (int i = 0; i < n; ++i)      // column
    for (int j = 0; j < n; ++j) {  // row, from the top
      Body b = make_body(1.0, 0.1 * Mat3::Identity());  // no shape: joined spheres do not touch
      b.position = Vec3(i, -j, 0.0);
      if (j == 0 && i >= n / 2 - 3 && i <= n / 2 + 3) make_static(b);
      ids.push_back(w->add(b));
    }
  auto id = [&](int i, int j) { return ids[static_cast<std::size_t>(i * n + j)]; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int di = 0; di <= 1; ++di) {
        const int i2 = i + di, j2 = j + 1 - di;
        if (i2 >= n || j2 >= n) continue;
        JointDef def;
        def.type = JointKind::hinge;
        def.a = id(i2, j2), def.b = id(i, j);
        def.anchor = 0.5 * (w->store().get(def.a).position + w->store().get(def.b).position);
        def.axis = Vec3::UnitZ();
        if (is_static(w->store().get(def.a))) std::swap(def.a, def.b);
        w->add_constraint(std::make_unique<Joint>(def, w->store().get(def.a), &w->store().get(def.b)));
      }
  return w;
}

std::unique_ptr<World> resting_spheres(int n) {
  auto w = std::make_unique<World>();
  w->add_plane(make_plane(Vec3::UnitY(), 0.0, 0.0, default_friction));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      Body b = make_sphere_body(1.0, 0.4);
      b.position = Vec3(i, 0.4, j);
      w->add(b);
    }
  return w;
}

// Time per step after one second of settling; counters: joints (or contacts) and the time per
// constraint (µs).
void joint_grid_step(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  auto w = joint_grid(n);
  w->step(1.0 / 60.0, 60);
  for (auto _ : state) w->step(1.0 / 60.0);
  const double joints = static_cast<double>(w->constraint_count());
  state.counters["constraints"] = joints;
  state.counters["us_per_constraint"] =
      benchmark::Counter(joints, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void contact_step(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  auto w = resting_spheres(n);
  w->step(1.0 / 60.0, 60);
  for (auto _ : state) w->step(1.0 / 60.0);
  const double contacts = static_cast<double>(w->contacts().size());
  state.counters["constraints"] = contacts;
  state.counters["us_per_constraint"] =
      benchmark::Counter(contacts, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

BENCHMARK(joint_grid_step)->Arg(25)->Arg(50)->Arg(100)->Unit(benchmark::kMillisecond);
BENCHMARK(contact_step)->Arg(100)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rigidlab

BENCHMARK_MAIN();
