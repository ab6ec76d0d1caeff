// Is the baseline of bench/settle_baseline.hpp a sane solver of the settle/N heap? Steps the
// engine's World and the baseline from the same fill_heap state and prints, for each, at 1.5 s
// (the end of settle/N's window) and at 10 s: the fastest sphere, the mean speed, the contact
// points per body (speculative ones included, as settle/N counts them), the deepest overlap
// between two spheres or a sphere and a wall (measured from the positions, the same way for
// both), the highest sphere top, and how many centres left the bin.
//   build/bench/settle_baseline_check [N ...]   (default: 256 1024 4096)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bench/settle_baseline_scene.hpp"

namespace {

using rigidlab::Vec3;

struct Sphere {
  Vec3 position, velocity;
  double radius;
};
struct Report {
  double max_speed = 0.0, mean_speed = 0.0, deepest = 0.0, top = 0.0;
  int outside = 0;
};

// Brute force over all pairs: independent of either solver's broad phase.
Report report(const std::vector<Sphere>& s, const std::vector<rigidlab::Plane>& planes) {
  Report r;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double speed = s[i].velocity.norm();
    r.max_speed = std::max(r.max_speed, speed);
    r.mean_speed += speed / static_cast<double>(s.size());
    r.top = std::max(r.top, s[i].position.y() + s[i].radius);
    bool inside = true;
    for (const rigidlab::Plane& p : planes) {
      const double gap = p.normal.dot(s[i].position) - p.offset - s[i].radius;
      r.deepest = std::max(r.deepest, -gap);
      inside = inside && p.normal.dot(s[i].position) >= p.offset;
    }
    r.outside += inside ? 0 : 1;
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      const double gap = (s[i].position - s[j].position).norm() - s[i].radius - s[j].radius;
      r.deepest = std::max(r.deepest, -gap);
    }
  }
  return r;
}

void print(const char* who, int n, double seconds, double contacts_per_body, double ms_per_step,
           const Report& r) {
  std::printf("%-8s %6d %5.1f %10.4f %10.4f %9.2f %10.2f %8.3f %8d %9.2f\n", who, n, seconds,
              r.max_speed, r.mean_speed, contacts_per_body, 1e3 * r.deepest, r.top, r.outside,
              ms_per_step);
}

void check(int n) {
  constexpr double dt = 1.0 / 60.0;
  rigidlab::World w;
  rigidlab::fill_heap(w, n, 0.0);
  baseline::SphereHeap heap = baseline::heap_from_world(w, dt);
  std::vector<Sphere> spheres(n);
  int steps = 0;
  double engine_ms = 0.0, baseline_ms = 0.0;
  for (const int until : {90, 600}) {
    const int count = until - steps;
    auto t0 = std::chrono::steady_clock::now();
    w.step(dt, count);
    auto t1 = std::chrono::steady_clock::now();
    for (int k = 0; k < count; ++k) heap.step();
    auto t2 = std::chrono::steady_clock::now();
    engine_ms = std::chrono::duration<double, std::milli>(t1 - t0).count() / count;
    baseline_ms = std::chrono::duration<double, std::milli>(t2 - t1).count() / count;
    steps = until;
    for (int i = 0; i < n; ++i) {
      const rigidlab::Body& b = w.bodies()[i];
      spheres[i] = Sphere{b.position, b.velocity, b.shape.radius};
    }
    print("engine", n, steps * dt, static_cast<double>(w.contacts().size()) / n, engine_ms,
          report(spheres, w.planes()));
    for (int i = 0; i < n; ++i) {
      const baseline::Sphere& s = heap.spheres()[i];
      spheres[i] = Sphere{s.position, s.velocity, s.radius};
    }
    print("baseline", n, steps * dt, static_cast<double>(heap.contact_count()) / n, baseline_ms,
          report(spheres, w.planes()));
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::printf("%-8s %6s %5s %10s %10s %9s %10s %8s %8s %9s\n", "solver", "N", "t s",
              "max |v|", "mean |v|", "cont/body", "overlap mm", "top m", "outside",
              "ms/step");
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i) sizes.push_back(std::atoi(argv[i]));
  if (sizes.empty()) sizes = {256, 1024, 4096};
  for (const int n : sizes) check(n);
}
