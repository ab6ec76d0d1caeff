// Tests for engine/dynamic_tree.cpp and engine/broad_phase.cpp against brute force:
//   - tree queries equal the O(n) scan of the boxes, ray casts agree with points sampled along
//     the segment, through random insertions, moves and removals;
//   - the tree's height stays O(log n) (≤ 2⌈log₂ n⌉ + 6) even for sorted insertions, the
//     classic worst case, and a rebuild gives ⌈log₂ n⌉;
//   - the broad phase's pair set equals the O(n²) set of overlapping fat boxes (and holds every
//     overlap of tight boxes) over hundreds of steps of movement, insertion and removal, with
//     added() and removed() the differences between steps; fat boxes follow the documented
//     formula;
//   - the pair order depends on the keys alone (not on creation order or proxy ids);
//   - bad input throws and changes nothing.
// No allocation per step is counted in broad_phase_allocations.cpp (its own executable: it
// replaces operator new).
#include "engine/broad_phase.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

namespace rigidlab {
namespace {

using KeyPair = std::pair<std::uint64_t, std::uint64_t>;

// Independent of Aabb's own predicates: interval overlap axis by axis.
bool boxes_overlap(const Aabb& a, const Aabb& b) {
  for (int i = 0; i < 3; ++i)
    if (a.upper[i] < b.lower[i] || b.upper[i] < a.lower[i]) return false;
  return true;
}

bool point_inside(const Vec3& p, const Aabb& b, double tolerance) {
  for (int i = 0; i < 3; ++i)
    if (p[i] < b.lower[i] - tolerance || p[i] > b.upper[i] + tolerance) return false;
  return true;
}

Aabb box_around(const Vec3& centre, const Vec3& half) { return {centre - half, centre + half}; }

int log2_ceiling(int n) {
  int k = 0;
  while ((1 << k) < n) ++k;
  return k;
}

// ---- Aabb ---------------------------------------------------------------------------------

TEST(Aabb, Predicates) {
  const Aabb unit{Vec3(0, 0, 0), Vec3(1, 2, 3)};
  EXPECT_DOUBLE_EQ(unit.half_area(), 1 * 2 + 2 * 3 + 3 * 1);
  EXPECT_TRUE(unit.overlaps(Aabb{Vec3(1, 2, 3), Vec3(4, 4, 4)}));  // a shared corner
  EXPECT_FALSE(unit.overlaps(Aabb{Vec3(1.5, 0, 0), Vec3(4, 4, 4)}));
  EXPECT_TRUE(unit.contains(unit));
  EXPECT_FALSE(unit.contains(Aabb{Vec3(0, 0, 0), Vec3(1, 2, 3.5)}));
  EXPECT_TRUE(unit.valid());
  EXPECT_FALSE((Aabb{Vec3(0, 0, 0), Vec3(-1, 1, 1)}.valid()));
  EXPECT_FALSE((Aabb{Vec3(0, 0, 0), Vec3(NAN, 1, 1)}.valid()));
  EXPECT_FALSE((Aabb{Vec3(-INFINITY, 0, 0), Vec3(1, 1, 1)}.valid()));
}

// ---- DynamicTree --------------------------------------------------------------------------

struct TreeScene {
  std::mt19937 rng{7};
  std::uniform_real_distribution<double> u{0.0, 1.0};
  DynamicTree tree;
  std::vector<std::int32_t> leaves;
  std::vector<Aabb> boxes;  // by payload = index into boxes

  Aabb random_box(double extent) {
    const Vec3 c(extent * u(rng), extent * u(rng), extent * u(rng));
    return box_around(c, Vec3(0.05 + u(rng), 0.05 + u(rng), 0.05 + u(rng)));
  }
  void insert(double extent) {
    boxes.push_back(random_box(extent));
    leaves.push_back(tree.insert(boxes.back(), static_cast<std::int32_t>(boxes.size() - 1)));
  }
};

TEST(DynamicTree, QueryEqualsScanThroughInsertMoveRemove) {
  TreeScene s;
  for (int i = 0; i < 400; ++i) s.insert(30.0);
  std::vector<bool> alive(s.boxes.size(), true);
  std::size_t neighbours = 0;
  for (int round = 0; round < 60; ++round) {
    for (std::size_t k = 0; k < s.boxes.size(); ++k) {
      if (!alive[k]) continue;
      const double r = s.u(s.rng);
      if (r < 0.02) {
        s.tree.remove(s.leaves[k]);
        alive[k] = false;
      } else if (r < 0.3) {
        s.boxes[k] = s.random_box(30.0);
        s.tree.move(s.leaves[k], s.boxes[k]);
      }
    }
    for (int i = 0; i < 8; ++i) {
      s.insert(30.0);
      alive.push_back(true);
    }
    ASSERT_EQ(s.tree.check(), "") << "round " << round;
    for (int q = 0; q < 20; ++q) {
      const Aabb query = s.random_box(30.0);
      std::set<std::int32_t> found, expected;
      s.tree.query(query, [&](std::int32_t leaf) {
        EXPECT_EQ(s.tree.box(leaf).lower, s.boxes[s.tree.payload(leaf)].lower);
        found.insert(s.tree.payload(leaf));
        return true;
      });
      for (std::size_t k = 0; k < s.boxes.size(); ++k)
        if (alive[k] && boxes_overlap(s.boxes[k], query)) expected.insert(static_cast<int>(k));
      ASSERT_EQ(found, expected) << "round " << round << ", query " << q;
    }
    // Searching outward from a leaf finds the same leaves as the whole tree, but that one.
    for (std::size_t k = 0; k < s.boxes.size(); k += 37) {
      if (!alive[k]) continue;
      const Aabb around{s.boxes[k].lower.array() - 2.0, s.boxes[k].upper.array() + 2.0};
      std::set<std::int32_t> found, expected;
      s.tree.query_around(s.leaves[k], around, [&](std::int32_t leaf) {
        found.insert(s.tree.payload(leaf));
        return true;
      });
      for (std::size_t j = 0; j < s.boxes.size(); ++j)
        if (alive[j] && j != k && boxes_overlap(s.boxes[j], around)) expected.insert(static_cast<int>(j));
      ASSERT_EQ(found, expected) << "round " << round << ", around " << k;
      neighbours += found.size();
    }
  }
  EXPECT_GT(neighbours, 1000u);
}

TEST(DynamicTree, QueryStopsWhenAsked) {
  TreeScene s;
  for (int i = 0; i < 100; ++i) s.insert(1.0);  // all overlapping
  int visits = 0;
  s.tree.query(Aabb{Vec3::Zero(), Vec3::Constant(2.0)}, [&](std::int32_t) { return ++visits < 3; });
  EXPECT_EQ(visits, 3);
}

// Sorted insertion along a line grows an incrementally built tree into a list unless something
// keeps it balanced; the limit is 2⌈log₂ n⌉ + 6, and a rebuild gives ⌈log₂ n⌉.
TEST(DynamicTree, HeightStaysLogarithmicForSortedInsertion) {
  DynamicTree tree;
  const int n = 20000;
  std::vector<std::int32_t> leaves;
  for (int i = 0; i < n; ++i) {
    leaves.push_back(tree.insert(box_around(Vec3(i, 0, 0), Vec3::Constant(0.4)), i));
    ASSERT_LE(tree.height(), 2 * log2_ceiling(i + 1) + 6) << "after " << i + 1 << " leaves";
  }
  ASSERT_EQ(tree.check(), "");
  // Moving every leaf to the other end, one by one, is sorted insertion again.
  for (int i = 0; i < n; ++i) {
    tree.move(leaves[i], box_around(Vec3(n + i, 0, 0), Vec3::Constant(0.4)));
    ASSERT_LE(tree.height(), 2 * log2_ceiling(n) + 6);
  }
  ASSERT_EQ(tree.check(), "");
  tree.rebuild();
  EXPECT_EQ(tree.height(), log2_ceiling(n));
  EXPECT_EQ(tree.check(), "");
  EXPECT_EQ(tree.leaf_count(), n);
  for (int i = 0; i < n; ++i) EXPECT_EQ(tree.payload(leaves[i]), i);  // leaf ids stay
}

// Random scenes: insertion by the surface area heuristic with rotations stays close to the
// balanced height without any rebuild, and its boxes overlap little: the area ratio (internal
// nodes' surface over the root's) of a random scene stays near that of the median-split rebuild.
TEST(DynamicTree, RandomInsertionIsBalancedAndTight) {
  TreeScene s;
  const int n = 4096;
  for (int i = 0; i < n; ++i) s.insert(100.0);
  EXPECT_LE(s.tree.height(), 2 * log2_ceiling(n));
  const double incremental = s.tree.area_ratio();
  s.tree.rebuild();
  const double rebuilt = s.tree.area_ratio();
  EXPECT_LT(incremental, 1.5 * rebuilt) << incremental << " against " << rebuilt;
}

TEST(DynamicTree, EmptyAndSingleLeaf) {
  DynamicTree tree;
  EXPECT_EQ(tree.height(), 0);
  int visits = 0;
  tree.query(Aabb{}, [&](std::int32_t) { return ++visits, true; });
  tree.ray_cast(Vec3::Zero(), Vec3(1, 0, 0), 1.0, [&](std::int32_t, double) { return ++visits, 1.0; });
  EXPECT_EQ(visits, 0);
  const std::int32_t leaf = tree.insert(Aabb{}, 5);
  EXPECT_EQ(tree.height(), 0);
  EXPECT_EQ(tree.check(), "");
  tree.remove(leaf);
  EXPECT_EQ(tree.leaf_count(), 0);
  EXPECT_EQ(tree.check(), "");
  tree.rebuild();
  EXPECT_EQ(tree.insert(Aabb{}, 6), leaf);  // the removed id is reused
}

// Ray casts: a box the segment passes through (seen at points sampled along it) is reported,
// and the reported entry point lies on the box; with clipping, the closest entry is found.
TEST(DynamicTree, RayCastAgreesWithSampledSegment) {
  TreeScene s;
  for (int i = 0; i < 300; ++i) s.insert(20.0);
  for (int r = 0; r < 50; ++r) {
    const Vec3 origin(20 * s.u(s.rng), 20 * s.u(s.rng), 20 * s.u(s.rng));
    Vec3 direction(s.u(s.rng) - 0.5, s.u(s.rng) - 0.5, s.u(s.rng) - 0.5);
    if (r % 5 == 0) direction.y() = direction.z() = 0.0;  // parallel to two slabs
    const double max_t = 10.0 / direction.norm();
    std::set<std::int32_t> found;
    s.tree.ray_cast(origin, direction, max_t, [&](std::int32_t leaf, double t) {
      const Aabb& b = s.boxes[s.tree.payload(leaf)];
      EXPECT_TRUE(t >= 0.0 && t <= max_t);
      EXPECT_TRUE(point_inside(origin + t * direction, b, 1e-9));
      if (t > 0.0) EXPECT_FALSE(point_inside(origin + (t - 1e-6) * direction, b, 0.0));
      found.insert(s.tree.payload(leaf));
      return max_t;  // see them all
    });
    double closest_sampled = INFINITY;
    for (std::size_t k = 0; k < s.boxes.size(); ++k) {
      for (int j = 0; j <= 2000; ++j) {
        const double t = max_t * j / 2000.0;
        if (point_inside(origin + t * direction, s.boxes[k], 0.0)) {
          EXPECT_TRUE(found.count(static_cast<std::int32_t>(k))) << "ray " << r << " box " << k;
          closest_sampled = std::min(closest_sampled, t);
          break;
        }
      }
    }
    double closest = INFINITY;
    s.tree.ray_cast(origin, direction, max_t, [&](std::int32_t, double t) {
      closest = std::min(closest, t);
      return t;  // clip: only nearer boxes from now on
    });
    if (std::isfinite(closest_sampled)) {
      EXPECT_LE(closest, closest_sampled);
      EXPECT_GT(closest, closest_sampled - max_t / 2000.0 - 1e-12);
    }
  }
}

// ---- BroadPhase ---------------------------------------------------------------------------

// A scene of boxes moving about, some fixed, with bodies added and removed; the broad phase
// is fed as a world would feed it: each body's box for the step (start box united with end
// box) and its displacement.
struct Scene {
  struct Thing {
    Vec3 position, half, velocity;
    std::uint64_t key;
    ProxyKind kind;
    ProxyId proxy;
    Aabb box;
  };
  std::mt19937 rng;
  std::uniform_real_distribution<double> u{-1.0, 1.0};
  double extent, dt = 1.0 / 60.0;
  BroadPhase bp;
  std::vector<Thing> things;
  std::uint64_t next_key = 1000;

  Scene(unsigned seed, double extent, BroadPhaseSettings settings = {})
      : rng(seed), extent(extent), bp(settings) {}

  Aabb step_box(const Thing& t) const {
    const Aabb start = box_around(t.position, t.half);
    const Aabb end = box_around(t.position + dt * t.velocity, t.half);
    return {start.lower.cwiseMin(end.lower), start.upper.cwiseMax(end.upper)};
  }
  void add(ProxyKind kind, std::uint64_t key) {
    Thing t;
    t.position = Vec3(extent * u(rng), extent * u(rng), extent * u(rng));
    t.half = Vec3(0.3 + 0.25 * u(rng), 0.3 + 0.25 * u(rng), 0.3 + 0.25 * u(rng));
    t.velocity = kind == ProxyKind::fixed ? Vec3::Zero() : Vec3(3 * u(rng), 3 * u(rng), 3 * u(rng));
    t.key = key;
    t.kind = kind;
    t.box = step_box(t);
    t.proxy = bp.create_proxy(t.box, t.key, kind, dt * t.velocity);
    things.push_back(t);
  }
  void add_random() { add(u(rng) < -0.8 ? ProxyKind::fixed : ProxyKind::moving, next_key++); }
  void remove(std::size_t i) {
    bp.destroy_proxy(things[i].proxy);
    things.erase(things.begin() + static_cast<long>(i));
  }
  // Moves every moving thing; now and then one turns, stops, jumps (teleports) or is replaced.
  void step() {
    for (Thing& t : things) {
      if (t.kind == ProxyKind::fixed) continue;
      t.position += dt * t.velocity;
      const double r = u(rng);
      if (r > 0.97) t.velocity = Vec3(3 * u(rng), 3 * u(rng), 3 * u(rng));
      else if (r < -0.99) t.velocity.setZero();
      else if (r < -0.985) t.position = Vec3(extent * u(rng), extent * u(rng), extent * u(rng));
      for (int i = 0; i < 3; ++i)  // stay in the region
        if (std::abs(t.position[i]) > extent && t.position[i] * t.velocity[i] > 0)
          t.velocity[i] = -t.velocity[i];
      t.box = step_box(t);
      bp.move_proxy(t.proxy, t.box, dt * t.velocity);
    }
  }

  std::set<KeyPair> reported() const {
    std::set<KeyPair> s;
    for (const BroadPhasePair& p : bp.pairs()) s.insert({p.key_a, p.key_b});
    return s;
  }
  // Brute force over every two things: their fat boxes overlap (or, with tight, their boxes).
  std::set<KeyPair> brute_force(bool tight) const {
    std::set<KeyPair> s;
    for (std::size_t i = 0; i < things.size(); ++i)
      for (std::size_t j = i + 1; j < things.size(); ++j) {
        const Thing& a = things[i];
        const Thing& b = things[j];
        if (a.kind == ProxyKind::fixed && b.kind == ProxyKind::fixed) continue;
        const bool overlap = tight ? boxes_overlap(a.box, b.box)
                                   : boxes_overlap(bp.fat_box(a.proxy), bp.fat_box(b.proxy));
        if (overlap) s.insert({std::min(a.key, b.key), std::max(a.key, b.key)});
      }
    return s;
  }
  // What the broad phase must hold for each thing: its box, a fat box around it no larger than
  // the documented bound (4 margins and 4 stretches on every side).
  void expect_fat_boxes() const {
    const BroadPhaseSettings& s = bp.settings();
    for (const Thing& t : things) {
      const Aabb& fat = bp.fat_box(t.proxy);
      ASSERT_EQ(bp.box(t.proxy).lower, t.box.lower);
      ASSERT_TRUE(point_inside(t.box.lower, fat, 0.0) && point_inside(t.box.upper, fat, 0.0));
      const Vec3 reach =
          4 * (Vec3::Constant(s.margin) + s.displacement_multiplier * dt * t.velocity.cwiseAbs());
      ASSERT_TRUE(point_inside(fat.lower, t.box, reach.maxCoeff() + 1e-12));
      ASSERT_TRUE(point_inside(fat.upper, t.box, reach.maxCoeff() + 1e-12));
    }
  }
};

std::set<KeyPair> difference(const std::set<KeyPair>& a, const std::set<KeyPair>& b) {
  std::set<KeyPair> d;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::inserter(d, d.begin()));
  return d;
}

std::set<KeyPair> as_set(const std::vector<BroadPhasePair>& pairs) {
  std::set<KeyPair> s;
  for (const BroadPhasePair& p : pairs) s.insert({p.key_a, p.key_b});
  return s;
}

TEST(BroadPhase, PairsEqualBruteForceOverManySteps) {
  // A dense region (about 3 neighbours per box) so that pairs come and go all the time.
  Scene scene(3, 4.5);
  for (int i = 0; i < 300; ++i) scene.add_random();
  scene.bp.update_pairs();
  std::set<KeyPair> previous = scene.reported();
  std::size_t most_pairs = 0, total_added = 0, total_removed = 0;
  for (int step = 0; step < 300; ++step) {
    scene.step();
    if (step % 3 == 0) {  // removals and insertions between the moves
      for (int k = 0; k < 4; ++k)
        scene.remove(static_cast<std::size_t>(scene.rng() % scene.things.size()));
      for (int k = 0; k < 4; ++k) scene.add_random();
    }
    scene.bp.update_pairs();
    ASSERT_EQ(scene.bp.check(), "") << "step " << step;
    const std::set<KeyPair> now = scene.reported();
    ASSERT_EQ(now.size(), scene.bp.pairs().size()) << "a pair reported twice";
    ASSERT_EQ(now, scene.brute_force(false)) << "step " << step;
    const std::set<KeyPair> tight = scene.brute_force(true);
    ASSERT_TRUE(std::includes(now.begin(), now.end(), tight.begin(), tight.end()));
    ASSERT_EQ(as_set(scene.bp.added()), difference(now, previous)) << "step " << step;
    ASSERT_EQ(as_set(scene.bp.removed()), difference(previous, now)) << "step " << step;
    ASSERT_TRUE(std::is_sorted(scene.bp.added().begin(), scene.bp.added().end()));
    ASSERT_TRUE(std::is_sorted(scene.bp.removed().begin(), scene.bp.removed().end()));
    scene.expect_fat_boxes();
    most_pairs = std::max(most_pairs, now.size());
    total_added += scene.bp.added().size();
    total_removed += scene.bp.removed().size();
    previous = now;
  }
  // The scene really exercises the pair set: many pairs, many changes.
  EXPECT_GT(most_pairs, 200u) << total_added << " added, " << total_removed << " removed";
  EXPECT_GT(total_added, 1000u);
  EXPECT_GT(total_removed, 1000u);
}

// Without margin or stretch, the fat boxes are the tight boxes: the pair set is then exactly the
// set of overlapping step boxes, and every move re-inserts.
TEST(BroadPhase, ZeroMarginGivesExactlyTheTightOverlaps) {
  Scene scene(11, 6.0, BroadPhaseSettings{0.0, 0.0, 0.0});
  for (int i = 0; i < 150; ++i) scene.add_random();
  for (int step = 0; step < 100; ++step) {
    scene.step();
    scene.bp.update_pairs();
    ASSERT_EQ(scene.reported(), scene.brute_force(true)) << "step " << step;
  }
}

// The fat box of a new proxy: margin on every side (at most a fraction of the longest side),
// stretched along multiplier × displacement.
TEST(BroadPhase, FatBoxFormula) {
  BroadPhase small;  // defaults: margin 0.1 m, at most 0.1 of the longest side
  const ProxyId s = small.create_proxy(Aabb{Vec3::Zero(), Vec3(0.2, 0.1, 0.1)}, 1);
  EXPECT_TRUE(small.fat_box(s).lower.isApprox(Vec3::Constant(-0.02), 1e-15));
  EXPECT_TRUE(small.fat_box(s).upper.isApprox(Vec3(0.22, 0.12, 0.12), 1e-15));
  BroadPhase bp(BroadPhaseSettings{0.1, 1.0, 4.0});
  const Aabb box{Vec3(0, 0, 0), Vec3(1, 1, 1)};
  const ProxyId p = bp.create_proxy(box, 1, ProxyKind::moving, Vec3(0.01, -0.02, 0));
  EXPECT_TRUE(bp.fat_box(p).lower.isApprox(Vec3(-0.1, -0.1 - 0.08, -0.1), 1e-15));
  EXPECT_TRUE(bp.fat_box(p).upper.isApprox(Vec3(1.1 + 0.04, 1.1, 1.1), 1e-15));
  // Inside the fat box nothing changes; leaving it re-fattens around the new box.
  EXPECT_FALSE(bp.move_proxy(p, Aabb{Vec3(0.03, -0.15, 0), Vec3(1.03, 0.85, 1)}, Vec3(0.01, -0.02, 0)));
  EXPECT_TRUE(bp.move_proxy(p, Aabb{Vec3(0.2, 0, 0), Vec3(1.2, 1, 1)}, Vec3::Zero()));
  EXPECT_TRUE(bp.fat_box(p).lower.isApprox(Vec3(0.1, -0.1, -0.1), 1e-15));
  EXPECT_TRUE(bp.fat_box(p).upper.isApprox(Vec3(1.3, 1.1, 1.1), 1e-15));
  // A fast body that stops: its stretched box is shrunk although the tight box is inside it.
  EXPECT_TRUE(bp.move_proxy(p, Aabb{Vec3(2.2, 0, 0), Vec3(3.2, 1, 1)}, Vec3(1, 0, 0)));
  EXPECT_DOUBLE_EQ(bp.fat_box(p).upper.x(), 3.2 + 0.1 + 4.0);
  EXPECT_TRUE(bp.move_proxy(p, Aabb{Vec3(2.2, 0, 0), Vec3(3.2, 1, 1)}, Vec3::Zero()));
  EXPECT_DOUBLE_EQ(bp.fat_box(p).upper.x(), 3.2 + 0.1);
}

// Fixed proxies pair with moving ones only, including a fixed proxy created (or moved by hand)
// over moving ones that are at rest and never leave their fat boxes.
TEST(BroadPhase, FixedProxiesPairOnlyWithMovingOnes) {
  BroadPhase bp;
  const Aabb unit{Vec3::Zero(), Vec3::Ones()};
  bp.create_proxy(unit, 1, ProxyKind::fixed);
  bp.create_proxy(unit, 2, ProxyKind::fixed);
  const ProxyId resting = bp.create_proxy(unit, 3, ProxyKind::moving);
  bp.update_pairs();
  EXPECT_EQ(as_set(bp.pairs()), (std::set<KeyPair>{{1, 3}, {2, 3}}));
  bp.move_proxy(resting, unit);  // at rest: no change
  const ProxyId late = bp.create_proxy(unit, 0, ProxyKind::fixed);
  bp.update_pairs();
  EXPECT_EQ(as_set(bp.pairs()), (std::set<KeyPair>{{0, 3}, {1, 3}, {2, 3}}));
  EXPECT_EQ(as_set(bp.added()), (std::set<KeyPair>{{0, 3}}));
  bp.move_proxy(late, Aabb{Vec3::Constant(5), Vec3::Constant(6)});  // moved by hand
  bp.update_pairs();
  EXPECT_EQ(as_set(bp.removed()), (std::set<KeyPair>{{0, 3}}));
  EXPECT_EQ(bp.check(), "");
}

// The order of the pairs is that of their keys, whatever the order of creation (and so the
// proxy ids and the shape of the trees): two broad phases fed the same bodies in opposite
// orders report the same list, step after step.
TEST(BroadPhase, PairOrderDependsOnKeysOnly) {
  Scene forward(5, 7.0), backward(5, 7.0);
  for (int i = 0; i < 200; ++i) forward.add_random();
  for (auto it = forward.things.rbegin(); it != forward.things.rend(); ++it) {
    Scene::Thing t = *it;
    t.proxy = backward.bp.create_proxy(t.box, t.key, t.kind, backward.dt * t.velocity);
    backward.things.push_back(t);
  }
  for (int step = 0; step < 50; ++step) {
    forward.step();
    // The same motions in the other order: replay forward's new boxes.
    for (std::size_t i = 0; i < forward.things.size(); ++i) {
      const Scene::Thing& f = forward.things[i];
      Scene::Thing& b = backward.things[forward.things.size() - 1 - i];
      b.box = f.box;
      b.velocity = f.velocity;
      if (f.kind == ProxyKind::moving) backward.bp.move_proxy(b.proxy, b.box, forward.dt * b.velocity);
    }
    forward.bp.update_pairs();
    backward.bp.update_pairs();
    const auto& fp = forward.bp.pairs();
    const auto& bp = backward.bp.pairs();
    ASSERT_EQ(fp.size(), bp.size()) << "step " << step;
    for (std::size_t k = 0; k < fp.size(); ++k) {
      ASSERT_EQ(fp[k].key_a, bp[k].key_a);
      ASSERT_EQ(fp[k].key_b, bp[k].key_b);
      ASSERT_LT(fp[k].key_a, fp[k].key_b);
    }
    ASSERT_GT(fp.size(), 0u);
  }
}

// A key given back and taken by a new proxy in the same step names a new pair: the old pair
// goes with the destroyed proxy, the new one is reported.
TEST(BroadPhase, KeyReusedInTheSameStep) {
  BroadPhase bp;
  const Aabb unit{Vec3::Zero(), Vec3::Ones()};
  const ProxyId old = bp.create_proxy(unit, 7);
  bp.create_proxy(unit, 8);
  bp.update_pairs();
  bp.destroy_proxy(old);
  const ProxyId renewed = bp.create_proxy(unit, 7);
  bp.update_pairs();
  ASSERT_EQ(bp.pairs().size(), 1u);
  EXPECT_EQ(bp.pairs()[0].proxy_a, renewed);
  EXPECT_EQ(bp.removed().size(), 1u);
  EXPECT_EQ(bp.added().size(), 1u);
  EXPECT_EQ(bp.check(), "");
}

// Whether a pair is new is decided from the fat boxes of the last update (has_pair): a proxy
// that moves away and back between two updates, or two proxies that both move, keep the pair
// they had (not added again), and a pair that comes apart and together again in one update
// is neither removed nor added. Independent reference: the pairs before and after.
TEST(BroadPhase, PairsKnownFromTheFatBoxesOfTheLastUpdate) {
  BroadPhase bp(BroadPhaseSettings{0.0, 0.0, 0.0});  // fat = tight: every move re-inserts
  const Aabb here = box_around(Vec3::Zero(), Vec3::Constant(0.5));
  const Aabb near = box_around(Vec3(0.8, 0, 0), Vec3::Constant(0.5));
  const Aabb far = box_around(Vec3(9, 0, 0), Vec3::Constant(0.5));
  const ProxyId a = bp.create_proxy(here, 1);
  const ProxyId b = bp.create_proxy(near, 2);
  bp.update_pairs();
  ASSERT_EQ(bp.pairs().size(), 1u);
  ASSERT_EQ(bp.added().size(), 1u);
  bp.move_proxy(a, far);   // apart ...
  bp.move_proxy(a, here);  // ... and back before the update
  bp.move_proxy(b, box_around(Vec3(0.7, 0, 0), Vec3::Constant(0.5)));  // both moved
  bp.update_pairs();
  EXPECT_EQ(bp.pairs().size(), 1u);
  EXPECT_TRUE(bp.added().empty());
  EXPECT_TRUE(bp.removed().empty());
  bp.move_proxy(a, far);
  bp.update_pairs();
  EXPECT_TRUE(bp.pairs().empty());
  EXPECT_EQ(bp.removed().size(), 1u);
  bp.move_proxy(b, far);  // b comes to a, which did not move: a new pair
  bp.update_pairs();
  ASSERT_EQ(bp.pairs().size(), 1u);
  EXPECT_EQ(bp.added().size(), 1u);
  EXPECT_EQ(bp.check(), "");
}

TEST(BroadPhase, QueryAndRayCastSeeTightBoxes) {
  Scene scene(9, 10.0);
  for (int i = 0; i < 200; ++i) scene.add_random();
  for (int q = 0; q < 30; ++q) {
    const Aabb query = box_around(Vec3(10 * scene.u(scene.rng), 10 * scene.u(scene.rng), 0),
                                  Vec3::Constant(1.5));
    std::set<std::uint64_t> found, expected;
    scene.bp.query(query, [&](ProxyId id, std::uint64_t key) {
      EXPECT_EQ(scene.bp.key(id), key);
      found.insert(key);
      return true;
    });
    for (const Scene::Thing& t : scene.things)
      if (boxes_overlap(t.box, query)) expected.insert(t.key);
    ASSERT_EQ(found, expected);
  }
  // The closest box along a ray aimed at one of them, against the nearest point sampled
  // along it that lies inside any box.
  const Vec3 origin(-15, 0.1, 0.2);
  const Vec3 direction = scene.things[17].position - origin;
  double closest = INFINITY;
  std::uint64_t closest_key = 0;
  scene.bp.ray_cast(origin, direction, 1.5, [&](ProxyId, std::uint64_t key, double t) {
    if (t < closest) closest = t, closest_key = key;
    return t;
  });
  double sampled = INFINITY;
  std::uint64_t sampled_key = 0;
  for (int j = 0; j <= 15000 && !std::isfinite(sampled); ++j)
    for (const Scene::Thing& t : scene.things)
      if (point_inside(origin + 1e-4 * j * direction, t.box, 0.0)) {
        sampled = 1e-4 * j, sampled_key = t.key;
        break;
      }
  ASSERT_TRUE(std::isfinite(sampled));
  EXPECT_EQ(closest_key, sampled_key);
  EXPECT_LE(closest, sampled);
  EXPECT_GT(closest, sampled - 1e-4);
}

// A large scene: after many steps of motion and churn both trees stay within 2⌈log₂ n⌉ + 6.
TEST(BroadPhase, TreeHeightStaysLogarithmic) {
  Scene scene(13, 60.0);
  const int n = 6000;
  for (int i = 0; i < n; ++i) scene.add_random();
  for (int step = 0; step < 60; ++step) {
    scene.step();
    for (int k = 0; k < 20; ++k) {
      scene.remove(static_cast<std::size_t>(scene.rng() % scene.things.size()));
      scene.add_random();
    }
    scene.bp.update_pairs();
    ASSERT_LE(scene.bp.tree(ProxyKind::moving).height(), 2 * log2_ceiling(n) + 6);
    ASSERT_LE(scene.bp.tree(ProxyKind::fixed).height(), 2 * log2_ceiling(n) + 6);
  }
  EXPECT_EQ(scene.bp.check(), "");
}

TEST(BroadPhase, ClearForgetsEverything) {
  Scene scene(17, 4.0);
  for (int i = 0; i < 100; ++i) scene.add_random();
  scene.bp.update_pairs();
  ASSERT_FALSE(scene.bp.pairs().empty());
  scene.bp.clear();
  EXPECT_EQ(scene.bp.proxy_count(), 0);
  EXPECT_TRUE(scene.bp.pairs().empty());
  EXPECT_FALSE(scene.bp.contains(0));
  scene.things.clear();
  for (int i = 0; i < 50; ++i) scene.add_random();
  EXPECT_EQ(scene.things.front().proxy, 0);
  scene.bp.update_pairs();
  EXPECT_EQ(scene.reported(), scene.brute_force(false));
  EXPECT_EQ(scene.bp.check(), "");
}

TEST(BroadPhase, BadInputThrowsAndChangesNothing) {
  EXPECT_THROW(BroadPhase(BroadPhaseSettings{-0.1, 0.1, 4.0}), std::invalid_argument);
  EXPECT_THROW(BroadPhase(BroadPhaseSettings{0.1, -1.0, 4.0}), std::invalid_argument);
  EXPECT_THROW(BroadPhase(BroadPhaseSettings{0.1, 0.1, NAN}), std::invalid_argument);
  BroadPhase bp;
  const Aabb unit{Vec3::Zero(), Vec3::Ones()};
  const ProxyId a = bp.create_proxy(unit, 1);
  const ProxyId b = bp.create_proxy(unit, 2);
  bp.update_pairs();
  const Aabb fat = bp.fat_box(a);
  const Aabb bad_boxes[] = {{Vec3(0, 0, 0), Vec3(-1, 1, 1)},
                            {Vec3(0, NAN, 0), Vec3(1, 1, 1)},
                            {Vec3(0, 0, 0), Vec3(1, 1, INFINITY)}};
  for (const Aabb& bad : bad_boxes) {
    EXPECT_THROW(bp.create_proxy(bad, 3), std::invalid_argument);
    EXPECT_THROW(bp.move_proxy(a, bad), std::invalid_argument);
  }
  EXPECT_THROW(bp.move_proxy(a, unit, Vec3(NAN, 0, 0)), std::invalid_argument);
  const Aabb away{Vec3::Constant(5), Vec3::Constant(6)};
  EXPECT_THROW(bp.move_proxy(a, away, Vec3(1e308, 0, 0)), std::invalid_argument);  // overflows
  EXPECT_THROW(bp.create_proxy(unit, 3, ProxyKind::moving, Vec3(0, INFINITY, 0)),
               std::invalid_argument);
  for (const ProxyId bad_id : {-1, 2, 1000}) {
    EXPECT_THROW(bp.move_proxy(bad_id, unit), std::invalid_argument);
    EXPECT_THROW(bp.destroy_proxy(bad_id), std::invalid_argument);
  }
  try {
    bp.move_proxy(a, bad_boxes[0]);
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "BroadPhase::move_proxy: the box must be finite with lower <= upper, got lower "
                 "(0, 0, 0), upper (-1, 1, 1)");
  }
  EXPECT_EQ(bp.proxy_count(), 2);
  EXPECT_EQ(bp.fat_box(a).lower, fat.lower);
  EXPECT_EQ(bp.box(a).upper, unit.upper);
  bp.update_pairs();
  EXPECT_EQ(as_set(bp.pairs()), (std::set<KeyPair>{{1, 2}}));
  bp.destroy_proxy(b);
  EXPECT_THROW(bp.destroy_proxy(b), std::invalid_argument);  // already gone
  EXPECT_THROW(bp.move_proxy(b, unit), std::invalid_argument);
  bp.update_pairs();
  EXPECT_TRUE(bp.pairs().empty());
  EXPECT_EQ(bp.check(), "");
}

}  // namespace
}  // namespace rigidlab
