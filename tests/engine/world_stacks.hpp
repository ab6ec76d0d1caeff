// Issue 13's stacking scenes, shared by tests/engine/world_contacts_test.cpp (the targets as
// tests) and bench/contacts_bench.cpp (their cost): unit boxes face on face on the floor y = 0.
#pragma once

#include "engine/world.hpp"

namespace rigidlab {

// Rows of base, base − 1, ... unit boxes (a pyramid, centred on x = 0) or `base` boxes on each
// other, on a floor plane of the default friction; returns the id of the top box.
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

}  // namespace rigidlab
