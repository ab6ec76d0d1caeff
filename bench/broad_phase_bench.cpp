// Broad phase speed (issue 13, item 5 and its target), the engine's BroadPhase (dynamic AABB
// trees, fat boxes, persistent pairs) side by side with two hand-written baselines run on the
// same boxes in the same process:
//   sap   the sweep and prune the contact finder ran before the world used this broad phase
//         (issue 13 item 5): every step the proxies are rebuilt, sorted along x
//         and swept, here with the y and z intervals tested instead of bounding spheres;
//   grid  a uniform grid rebuilt every step: each box into the hashed cells it covers (counting
//         sort by cell), each pair tested once in the cell of the corner of its overlap.
// Scenes:
//   scattered/N  N shaped boxes (0.5 to 1.5 m sides) far apart (5 m lattice), each moving at
//                up to 1 m/s about its site and spinning at up to 3 rad/s, 60 Hz: broad phase
//                only (no pair), cost per body-step at 1k, 10k, 100k (goal: flat within 1.5×
//                of the 1k figure, ≤ 1.3 µs at 100k; Bullet's 1.2 µs is the anchor);
//                motion/N is the caller's share (moving the boxes, their step boxes) that every
//                side pays too.
//   pile         1,024 spheres (r = 0.1 m) settling in a 2 m bin under the engine's World, 4 s
//                recorded once; each step hands every sphere's step box to the broad phase:
//                cost per step with thousands of persistent pairs.
// bench/run prints the ratios:  build/bench/broad_phase_bench --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "engine/broad_phase.hpp"
#include "engine/world.hpp"

namespace {

using namespace rigidlab;

constexpr double dt = 1.0 / 60.0;
constexpr double half_speculative = 0.01;  // m: half the contact solver's speculative distance

// ---- the scattered scene: what a world step would hand to any broad phase -----------------

struct ShapedBox {
  Vec3 site, centre, half, velocity, axis;
  double angle, spin;
};

struct Scattered {
  std::vector<ShapedBox> bodies;
  std::vector<Aabb> boxes;           // this step's box of each body
  std::vector<Vec3> displacements;   // m, this step's

  explicit Scattered(int n) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int side = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(n))));
    for (int i = 0; i < n; ++i) {
      ShapedBox b;
      b.site = 5.0 * Vec3(i % side, (i / side) % side, i / (side * side));
      b.centre = b.site + 0.5 * Vec3(u(rng), u(rng), u(rng));
      b.half = Vec3(0.5 + 0.25 * u(rng), 0.5 + 0.25 * u(rng), 0.5 + 0.25 * u(rng));
      b.velocity = Vec3(u(rng), u(rng), u(rng));
      b.axis = Vec3(u(rng), u(rng), 1.0).normalized();
      b.angle = 3.0 * u(rng);
      b.spin = 3.0 * u(rng);
      bodies.push_back(b);
    }
    boxes.resize(n);
    displacements.resize(n);
    advance();
  }
  // One step of motion (back and forth within 1 m of the site), then the step box: the box of
  // the rotated shape grown by the sweep along the displacement, by what the spin can move its
  // corners and by half the speculative distance (as the contact solver's proxies).
  void advance() {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      ShapedBox& b = bodies[i];
      for (int k = 0; k < 3; ++k)
        if (std::abs(b.centre[k] - b.site[k]) > 1.0 && (b.centre[k] - b.site[k]) * b.velocity[k] > 0)
          b.velocity[k] = -b.velocity[k];
      const Vec3 d = dt * b.velocity;
      b.centre += d;
      b.angle += dt * b.spin;
      const Mat3 r = Eigen::AngleAxisd(b.angle, b.axis).toRotationMatrix();
      const Vec3 extent = r.cwiseAbs() * b.half +
                          Vec3::Constant(std::abs(b.spin) * dt * b.half.norm() + half_speculative);
      Aabb box{b.centre - extent, b.centre + extent};
      for (int k = 0; k < 3; ++k)  // united with the box at the start of the step
        (d[k] < 0.0 ? box.upper[k] : box.lower[k]) -= d[k];
      boxes[i] = box;
      displacements[i] = d;
    }
  }
};

// ---- baseline 1: today's sweep and prune, rebuilt every step ------------------------------

struct SweepAndPrune {
  struct Proxy {
    double min_x, max_x;
    std::size_t index;
  };
  std::vector<Proxy> proxies;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;

  void find(const std::vector<Aabb>& boxes) {
    proxies.clear();
    for (std::size_t i = 0; i < boxes.size(); ++i)
      proxies.push_back({boxes[i].lower.x(), boxes[i].upper.x(), i});
    std::sort(proxies.begin(), proxies.end(), [](const Proxy& p, const Proxy& q) {
      return p.min_x < q.min_x || (p.min_x == q.min_x && p.index < q.index);
    });
    pairs.clear();
    for (std::size_t i = 0; i < proxies.size(); ++i) {
      const Aabb& a = boxes[proxies[i].index];
      for (std::size_t j = i + 1; j < proxies.size() && proxies[j].min_x <= proxies[i].max_x; ++j) {
        const Aabb& b = boxes[proxies[j].index];
        if (a.lower.y() <= b.upper.y() && b.lower.y() <= a.upper.y() && a.lower.z() <= b.upper.z() &&
            b.lower.z() <= a.upper.z())
          pairs.push_back({static_cast<std::uint32_t>(std::min(proxies[i].index, proxies[j].index)),
                           static_cast<std::uint32_t>(std::max(proxies[i].index, proxies[j].index))});
      }
    }
  }
};

// ---- baseline 2: a hashed uniform grid, rebuilt every step --------------------------------

struct UniformGrid {
  struct Entry {
    std::int64_t x, y, z;
    std::uint32_t body;
  };
  double cell;
  std::vector<Entry> entries, sorted;
  std::vector<std::uint32_t> start;  // counting sort by bucket
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;

  explicit UniformGrid(double cell_size) : cell(cell_size) {}

  std::int64_t coordinate(double x) const { return static_cast<std::int64_t>(std::floor(x / cell)); }
  static std::uint32_t hash(std::int64_t x, std::int64_t y, std::int64_t z) {
    return static_cast<std::uint32_t>(x * 73856093 ^ y * 19349663 ^ z * 83492791);
  }

  void find(const std::vector<Aabb>& boxes) {
    entries.clear();
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      const Aabb& b = boxes[i];
      for (std::int64_t x = coordinate(b.lower.x()); x <= coordinate(b.upper.x()); ++x)
        for (std::int64_t y = coordinate(b.lower.y()); y <= coordinate(b.upper.y()); ++y)
          for (std::int64_t z = coordinate(b.lower.z()); z <= coordinate(b.upper.z()); ++z)
            entries.push_back({x, y, z, static_cast<std::uint32_t>(i)});
    }
    std::uint32_t buckets = 1;
    while (buckets < 2 * entries.size()) buckets *= 2;
    start.assign(buckets + 1, 0);
    for (const Entry& e : entries) ++start[(hash(e.x, e.y, e.z) & (buckets - 1)) + 1];
    for (std::uint32_t k = 0; k < buckets; ++k) start[k + 1] += start[k];
    sorted.resize(entries.size());
    for (const Entry& e : entries) sorted[start[hash(e.x, e.y, e.z) & (buckets - 1)]++] = e;
    // start[k] is now the end of bucket k, the beginning of bucket k + 1.
    pairs.clear();
    std::uint32_t begin = 0;
    for (std::uint32_t k = 0; k < buckets; ++k) {
      const std::uint32_t end = start[k];
      for (std::uint32_t i = begin; i < end; ++i)
        for (std::uint32_t j = i + 1; j < end; ++j) test(boxes, sorted[i], sorted[j]);
      begin = end;
    }
  }
  // Same cell (not just the same bucket), boxes overlap, and this cell holds the lower corner
  // of their overlap: each pair once.
  void test(const std::vector<Aabb>& boxes, const Entry& p, const Entry& q) {
    if (p.x != q.x || p.y != q.y || p.z != q.z) return;
    const Aabb& a = boxes[p.body];
    const Aabb& b = boxes[q.body];
    if (!a.overlaps(b)) return;
    const Vec3 corner = a.lower.cwiseMax(b.lower);
    if (coordinate(corner.x()) != p.x || coordinate(corner.y()) != p.y ||
        coordinate(corner.z()) != p.z)
      return;
    pairs.push_back({std::min(p.body, q.body), std::max(p.body, q.body)});
  }
};

// ---- the scattered benchmarks -------------------------------------------------------------

// Every benchmark sets the same counters (the CSV that bench/run reads needs them in every
// row): pairs per step, and for the tree its height and the share of proxies re-inserted.
void set_counters(benchmark::State& state, std::size_t pairs, double height = 0.0,
                  double refattened = 0.0) {
  state.counters["pairs"] = static_cast<double>(pairs) / static_cast<double>(state.iterations());
  state.counters["height"] = height;
  state.counters["refattened"] = refattened;
}

void scattered_tree(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Scattered scene(n);
  BroadPhase bp;
  std::vector<ProxyId> ids;
  for (int i = 0; i < n; ++i)
    ids.push_back(bp.create_proxy(scene.boxes[i], static_cast<std::uint64_t>(i),
                                  ProxyKind::moving, scene.displacements[i]));
  bp.update_pairs();
  std::size_t pairs = 0, refattened = 0;
  for (auto _ : state) {
    scene.advance();
    for (int i = 0; i < n; ++i)
      refattened += bp.move_proxy(ids[i], scene.boxes[i], scene.displacements[i]);
    bp.update_pairs();
    pairs += bp.pairs().size();
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n);
  set_counters(state, pairs, bp.tree(ProxyKind::moving).height(),
               static_cast<double>(refattened) / static_cast<double>(state.iterations()) / n);
}

template <class Baseline>
void scattered_baseline(benchmark::State& state, Baseline baseline) {
  const int n = static_cast<int>(state.range(0));
  Scattered scene(n);
  std::size_t pairs = 0;
  for (auto _ : state) {
    scene.advance();
    baseline.find(scene.boxes);
    pairs += baseline.pairs.size();
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n);
  set_counters(state, pairs);
}

void scattered_sap(benchmark::State& state) { scattered_baseline(state, SweepAndPrune{}); }
void scattered_grid(benchmark::State& state) { scattered_baseline(state, UniformGrid(4.0)); }

void scattered_motion(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Scattered scene(n);
  for (auto _ : state) {
    scene.advance();
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n);
  set_counters(state, 0);
}

// ---- the settling pile --------------------------------------------------------------------

struct Pile {
  static constexpr int steps = 240;
  int count = 0;
  std::vector<Vec3> centres;  // [step][body], steps + 1 poses
  double radius = 0.1;

  Pile() {
    World world;
    const double e = 0.0, mu = 0.5;
    world.add_plane(make_plane(Vec3(0, 1, 0), 0.0, e, mu));
    world.add_plane(make_plane(Vec3(1, 0, 0), -1.0, e, mu));
    world.add_plane(make_plane(Vec3(-1, 0, 0), -1.0, e, mu));
    world.add_plane(make_plane(Vec3(0, 0, 1), -1.0, e, mu));
    world.add_plane(make_plane(Vec3(0, 0, -1), -1.0, e, mu));
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int layer = 0; layer < 16; ++layer)
      for (int i = 0; i < 8; ++i)
        for (int k = 0; k < 8; ++k) {
          Body b = make_sphere_body(1.0, radius);
          b.position = Vec3(-0.84 + 0.24 * i + 0.02 * u(rng), 0.2 + 0.24 * layer,
                            -0.84 + 0.24 * k + 0.02 * u(rng));
          b.velocity = Vec3(0.3 * u(rng), 0.0, 0.3 * u(rng));
          world.add(b);
        }
    count = static_cast<int>(world.bodies().size());
    record(world);
    for (int s = 0; s < steps; ++s) {
      world.step(dt);
      record(world);
    }
  }
  void record(const World& world) {
    for (const Body& b : world.bodies()) centres.push_back(b.position);
  }
  const Vec3& centre(int step, int body) const { return centres[step * count + body]; }
  // The step box of a body from its recorded poses at the start and the end of the step.
  void step_box(int step, int body, Aabb& box, Vec3& displacement) const {
    const Vec3& a = centre(step, body);
    const Vec3& b = centre(step + 1, body);
    const Vec3 r = Vec3::Constant(radius + half_speculative);
    box = {a.cwiseMin(b) - r, a.cwiseMax(b) + r};
    displacement = b - a;
  }
};

const Pile& pile() {
  static const Pile p;
  return p;
}

void pile_tree(benchmark::State& state) {
  const Pile& p = pile();
  BroadPhase bp;
  std::vector<ProxyId> ids;
  Aabb box;
  Vec3 d;
  for (int i = 0; i < p.count; ++i) {
    p.step_box(0, i, box, d);
    ids.push_back(bp.create_proxy(box, static_cast<std::uint64_t>(i), ProxyKind::moving, d));
  }
  int step = 0;
  std::size_t pairs = 0;
  for (auto _ : state) {
    for (int i = 0; i < p.count; ++i) {
      p.step_box(step, i, box, d);
      bp.move_proxy(ids[i], box, d);
    }
    bp.update_pairs();
    pairs += bp.pairs().size();
    step = (step + 1) % Pile::steps;
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * p.count);
  set_counters(state, pairs);
}

template <class Baseline>
void pile_baseline(benchmark::State& state, Baseline baseline) {
  const Pile& p = pile();
  std::vector<Aabb> boxes(p.count);
  Vec3 d;
  int step = 0;
  std::size_t pairs = 0;
  for (auto _ : state) {
    for (int i = 0; i < p.count; ++i) p.step_box(step, i, boxes[i], d);
    baseline.find(boxes);
    pairs += baseline.pairs.size();
    step = (step + 1) % Pile::steps;
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * p.count);
  set_counters(state, pairs);
}

void pile_sap(benchmark::State& state) { pile_baseline(state, SweepAndPrune{}); }
void pile_grid(benchmark::State& state) { pile_baseline(state, UniformGrid(0.25)); }

}  // namespace

BENCHMARK(scattered_tree)->Arg(1000)->Arg(10000)->Arg(100000);
BENCHMARK(scattered_sap)->Arg(1000)->Arg(10000)->Arg(100000);
BENCHMARK(scattered_grid)->Arg(1000)->Arg(10000)->Arg(100000);
BENCHMARK(scattered_motion)->Arg(1000)->Arg(10000)->Arg(100000);
BENCHMARK(pile_tree);
BENCHMARK(pile_sap);
BENCHMARK(pile_grid);

BENCHMARK_MAIN();
