// Contacts in the world (issue 13's targets), each scene stepped by the engine's World as a
// user's script steps it, 60 Hz, default settings unless named:
//   free/N        N boxes without shapes (integration alone): the baseline of scattered/N;
//   scattered/N   the same N boxes with their shapes, far apart (5 m lattice, drifting at up to
//                 0.3 m/s and spinning at up to 3 rad/s, no gravity): the broad phase's share is
//                 scattered − free, per body-step at 1k, 10k, 100k (goal: flat within 1.5× of
//                 the 1k figure, the whole step ≤ 1.3 µs per body at 100k);
//   settle/N      N spheres (r = 0.1 m) dropped as a jittered lattice, 4 layers, into a bin of
//                 five planes whose floor grows with N (256, 1,024, 4,096), timed from 0.5 s to
//                 1.5 s while they settle: ms per step and mean contacts per body (goal: per
//                 body-step flat after accounting for the contacts per body);
//   settle_baseline/N  the settle/N heap stepped by a hand-written sequential-impulse solver
//                 (bench/settle_baseline.hpp: grid, one point per pair, warm start, friction
//                 disk, the world's iterations), timed the same way: the per-contact cost the
//                 machine gives for the same scene, to judge settle/N's growth with N against;
//   bouncy/N      the same heap with restitution e = 0.5 (spheres and bin): impacts above the
//                 1 m/s threshold bounce, and the restitution stage solves them to convergence
//                 (goal: no more than a few times settle/N);
//   pyramid/S     210 unit boxes (base 20), solver S, timed after 10 s standing; the top box's
//                 displacement after those 10 s is reported too (goal: ≤ 1.0 ms per step,
//                 < 5 mm);
//   column/S      10 unit boxes on each other, likewise (and a column of 20's top after 10 s);
//   stack/S       5 unit boxes: how far the top sank after 10 s.
// bench/run prints the table of issue 13 from these:  build/bench/contacts_bench
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "bench/settle_baseline_scene.hpp"
#include "engine/world.hpp"
#include "tests/engine/world_stacks.hpp"

namespace {

using namespace rigidlab;

constexpr double dt = 1.0 / 60.0;

// Every benchmark sets the same counters (the CSV bench/run reads needs them in every row).
void set_counters(benchmark::State& state, double moved_mm, double contacts_per_body) {
  state.counters["moved_mm"] = moved_mm;
  state.counters["contacts_per_body"] = contacts_per_body;
}

// ---- scattered boxes, with and without shapes -----------------------------------------------

std::unique_ptr<World> scattered_world(int n, bool shaped) {
  auto w = std::make_unique<World>();
  w->set_gravity(Vec3::Zero());
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int side = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(n))));
  for (int i = 0; i < n; ++i) {
    Body b = make_box_body(1.0, Vec3(1.0 + 0.5 * u(rng), 1.0 + 0.5 * u(rng), 1.0 + 0.5 * u(rng)));
    b.position = 5.0 * Vec3(i % side, (i / side) % side, i / (side * side)) +
                 0.5 * Vec3(u(rng), u(rng), u(rng));
    b.orientation = quat_from_axis_angle(Vec3(u(rng), u(rng), 1.0), 3 * u(rng));
    b.velocity = 0.3 * Vec3(u(rng), u(rng), u(rng));
    b.angular_velocity = 3.0 * Vec3(u(rng), u(rng), u(rng));
    if (!shaped) b.shape = Shape{};
    w->add(b);
  }
  return w;
}

void run_scattered(benchmark::State& state, bool shaped) {
  const int n = static_cast<int>(state.range(0));
  std::unique_ptr<World> w = scattered_world(n, shaped);
  w->step(dt, 3);  // the buffers grow
  for (auto _ : state) {
    w->step(dt);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n);
  set_counters(state, 0.0, static_cast<double>(w->contacts().size()) / n);
}
void free_boxes(benchmark::State& state) { run_scattered(state, false); }
void scattered(benchmark::State& state) { run_scattered(state, true); }

// ---- spheres settling in a bin ------------------------------------------------------------------

// Every size is timed over the same second of its settling (0.5 s to 1.5 s, restored from the
// state at 0.5 s after each 60 steps), so the heaps compared are in the same state: timed step
// by step from 0.5 s on, a small heap ran for 12 s (at rest, cheaper per contact) while a large
// one was still landing. `step` advances one step, `restore` goes back to 0.5 s (untimed),
// `contacts` counts the last step's points.
template <class Step, class Restore, class Contacts>
void time_window(benchmark::State& state, int n, Step step, Restore restore, Contacts contacts) {
  constexpr long window = 60;
  double total = 0.0;
  long k = 0;
  for (auto _ : state) {
    if (k > 0 && k % window == 0) {
      state.PauseTiming();
      restore();
      state.ResumeTiming();
    }
    step();
    benchmark::ClobberMemory();
    total += static_cast<double>(contacts());
    ++k;
  }
  state.SetItemsProcessed(state.iterations() * n);
  set_counters(state, 0.0, total / (static_cast<double>(k) * n));
}

void run_settle(benchmark::State& state, double restitution) {
  const int n = static_cast<int>(state.range(0));
  World w;
  fill_heap(w, n, restitution);
  w.step(dt, 30);  // half a second: they have landed on each other and are settling
  WorldState start;
  w.save_state(start);
  time_window(
      state, n, [&] { w.step(dt); }, [&] { w.restore_state(start); },
      [&] { return w.contacts().size(); });
}
void settle(benchmark::State& state) { run_settle(state, 0.0); }
void bouncy(benchmark::State& state) { run_settle(state, 0.5); }

// The same heap, window and restore, stepped by the baseline solver.
void settle_baseline(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  baseline::SphereHeap heap = baseline::settling_heap(n, dt);
  for (int k = 0; k < 30; ++k) heap.step();
  baseline::State start;
  heap.save(start);
  time_window(
      state, n, [&] { heap.step(); }, [&] { heap.restore(start); },
      [&] { return heap.contact_count(); });
}

// ---- stacks: pyramid, column, stack ---------------------------------------------------------------

// Stands the stack 10 s, reports how far its top moved (mm), then times its steps.
void run_stack(benchmark::State& state, int base, bool pyramid) {
  World w;
  w.set_solver(static_cast<SolverKind>(state.range(0)));
  const BodyId top = build_stack(w, base, pyramid);
  const Vec3 start = w.store().get(top).position;
  w.step(dt, 600);
  const double moved_mm = 1e3 * (w.store().get(top).position - start).norm();
  for (auto _ : state) {
    w.step(dt);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(w.bodies().size()));
  set_counters(state, moved_mm, static_cast<double>(w.contacts().size()) / w.bodies().size());
}
void pyramid(benchmark::State& state) { run_stack(state, 20, true); }
void column(benchmark::State& state) { run_stack(state, 10, false); }
void column20(benchmark::State& state) { run_stack(state, 20, false); }
void stack(benchmark::State& state) { run_stack(state, 5, false); }

}  // namespace

BENCHMARK(free_boxes)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(scattered)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
// Whole windows of 60 steps (see run_settle), so each size is timed over the same second.
BENCHMARK(settle)->Arg(256)->Iterations(600)->Unit(benchmark::kMillisecond);
BENCHMARK(settle)->Arg(1024)->Iterations(120)->Unit(benchmark::kMillisecond);
BENCHMARK(settle)->Arg(4096)->Iterations(60)->Unit(benchmark::kMillisecond);
BENCHMARK(settle_baseline)->Arg(256)->Iterations(600)->Unit(benchmark::kMillisecond);
BENCHMARK(settle_baseline)->Arg(1024)->Iterations(120)->Unit(benchmark::kMillisecond);
BENCHMARK(settle_baseline)->Arg(4096)->Iterations(60)->Unit(benchmark::kMillisecond);
BENCHMARK(bouncy)->Arg(1024)->Iterations(120)->Unit(benchmark::kMillisecond);
BENCHMARK(pyramid)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(column)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(column20)->Arg(0)->Arg(1)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(stack)->Arg(0)->Arg(1)->Iterations(1)->Unit(benchmark::kMillisecond);

// ---- a settled heap asleep (engine/islands.hpp) ----------------------------------------------------
//   asleep/N/S    the settle/N heap after 8 s (settled; with S = 1, world.sleeping on, so its
//                 islands have fallen asleep), timed: ms per step with sleeping off (S = 0) and
//                 on (S = 1), and the share of bodies asleep (%).
namespace {
void asleep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  World w;
  w.set_sleeping(state.range(1) != 0);
  fill_heap(w, n, 0.0);
  w.step(dt, 480);
  for (auto _ : state) {
    w.step(dt);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n);
  state.counters["asleep_percent"] = 100.0 * static_cast<double>(w.sleeping_count()) / n;
}
}  // namespace
BENCHMARK(asleep)->Args({1024, 0})->Args({1024, 1})->Iterations(120)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
