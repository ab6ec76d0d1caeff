// Issue 13's stacking and settling scenes, shared by the engine tests (the targets as tests)
// and bench/contacts_bench.cpp (their cost).
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "engine/world.hpp"

namespace rigidlab {

// Unit boxes face on face on the floor y = 0: rows of base, base − 1, ... boxes (a pyramid,
// centred on x = 0) or `base` boxes on each other, on a floor plane of the default friction;
// returns the id of the top box.
inline BodyId build_stack(World& w, int base, bool pyramid) {
  w.add_plane(make_plane(Vec3(0, 1, 0), 0.0, 0.0, default_friction));
  BodyId top;
  for (int row = 0; row < base; ++row) {
    const int count = pyramid ? base - row : 1;
    for (int k = 0; k < count; ++k) {
      Body box = make_box_body(1.0, Vec3(1, 1, 1));
      box.position = Vec3(k - 0.5 * (count - 1), 0.5 + row, 0);
      top = w.add(box);
    }
  }
  return top;
}

// The pyramid of build_stack with what should not matter changed (tests/engine/
// pyramid_creep_test.cpp): the order its boxes are added in (which orders the contacts and so
// the solve: `added` in rows from the bottom, reversed, or shuffled by `seed`) and each box's
// position moved by up to `jitter` (m) along each axis. Returns the id of the top box.
enum class AddOrder { bottom_up, top_down, shuffled };
inline BodyId build_pyramid(World& w, int base, AddOrder added, double jitter,
                            unsigned seed = 7) {
  w.add_plane(make_plane(Vec3(0, 1, 0), 0.0, 0.0, default_friction));
  struct Slot {
    int row, k;
  };
  std::vector<Slot> slots;
  for (int row = 0; row < base; ++row)
    for (int k = 0; k < base - row; ++k) slots.push_back({row, k});
  std::mt19937 rng(seed);
  if (added == AddOrder::top_down) std::reverse(slots.begin(), slots.end());
  if (added == AddOrder::shuffled) std::shuffle(slots.begin(), slots.end(), rng);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  BodyId top;
  for (const Slot& s : slots) {
    Body box = make_box_body(1.0, Vec3(1, 1, 1));
    box.position = Vec3(s.k - 0.5 * (base - s.row - 1), 0.5 + s.row, 0) +
                   jitter * Vec3(u(rng), u(rng), u(rng));
    const BodyId id = w.add(box);
    if (s.row == base - 1) top = id;
  }
  return top;
}

// The settling heap (bench settle/N, tests/engine/restitution_budget_test.cpp): n spheres of
// r = 0.1 m, 0.1 kg, friction 0.5 and restitution e, in 4 jittered layers dropped into a bin
// of five planes of the same e.
inline void fill_heap(World& w, int n, double e) {
  const int side = static_cast<int>(std::lround(std::sqrt(n / 4.0)));  // 4 layers
  const double width = 0.25 * side;
  w.add_plane(make_plane(Vec3(0, 1, 0), 0.0, e, 0.5));
  w.add_plane(make_plane(Vec3(1, 0, 0), 0.0, e, 0.5));
  w.add_plane(make_plane(Vec3(-1, 0, 0), -width, e, 0.5));
  w.add_plane(make_plane(Vec3(0, 0, 1), 0.0, e, 0.5));
  w.add_plane(make_plane(Vec3(0, 0, -1), -width, e, 0.5));
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < n; ++i) {
    Body b = make_sphere_body(0.1, 0.1);
    b.position = Vec3(0.125 + 0.25 * (i % side), 0.2 + 0.25 * (i / (side * side)),
                      0.125 + 0.25 * ((i / side) % side)) +
                 0.02 * Vec3(u(rng), u(rng), u(rng));
    b.friction = 0.5;
    b.restitution = e;
    w.add(b);
  }
}

}  // namespace rigidlab
