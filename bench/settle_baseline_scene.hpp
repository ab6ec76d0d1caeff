// fill_heap's scene (tests/engine/world_stacks.hpp) handed to the baseline of
// bench/settle_baseline.hpp: the spheres and the bin are read from a World that fill_heap
// filled, so both solvers start from the same bodies (same jitter, masses, inertias, friction),
// and the step settings are the world's (gravity, 60 Hz, its default iterations, speculative
// distance, Baumgarte fraction and slop).
#pragma once

#include <vector>

#include "bench/settle_baseline.hpp"
#include "engine/world.hpp"
#include "tests/engine/world_stacks.hpp"

namespace baseline {

inline SphereHeap heap_from_world(const rigidlab::World& w, double dt) {
  std::vector<Sphere> spheres;
  for (const rigidlab::Body& b : w.bodies()) {
    Sphere s;
    s.position = b.position;
    s.velocity = b.velocity;
    s.angular_velocity = b.angular_velocity;
    s.orientation = b.orientation;
    s.radius = b.shape.radius;
    s.inverse_mass = b.inverse_mass;
    s.inverse_inertia = b.inverse_inertia(0, 0);  // a solid sphere's: a multiple of 1
    s.friction = b.friction;
    spheres.push_back(s);
  }
  std::vector<Wall> walls;
  for (const rigidlab::Plane& p : w.planes()) walls.push_back(Wall{p.normal, p.offset, p.friction});
  const rigidlab::ContactSettings& c = w.contact_settings();
  Settings settings;
  settings.dt = dt;
  settings.gravity = w.gravity();
  settings.iterations = c.iterations;
  settings.speculative_distance = c.speculative_distance;
  settings.baumgarte = c.baumgarte;
  settings.linear_slop = c.linear_slop;
  return SphereHeap(std::move(spheres), std::move(walls), settings);
}

// The baseline's heap of n spheres, as fill_heap(w, n, 0) would drop them.
inline SphereHeap settling_heap(int n, double dt) {
  rigidlab::World w;
  rigidlab::fill_heap(w, n, 0.0);
  return heap_from_world(w, dt);
}

}  // namespace baseline
