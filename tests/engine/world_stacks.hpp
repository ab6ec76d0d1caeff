// Issue 13's stacking and settling scenes, shared by the engine tests (the targets as tests)
// and bench/contacts_bench.cpp (their cost).
#pragma once

#include <cmath>
#include <random>

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
