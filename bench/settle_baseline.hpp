// A hand-written baseline for issue 13's settling heap (bench/contacts_bench.cpp settle/N): a
// minimal sphere-heap solver in plain C++/Eigen, no engine code, so that the engine's cost per
// contact-step can be judged against what this machine does for the same scene and about the
// same memory traffic (settle_baseline/N, same window, same restore).
//
// One step of dt, semi-implicit Euler with sequential impulses (E. Catto, "Iterative Dynamics
// with Temporal Coherence", GDC 2005; Box2D v2.4 b2ContactSolver):
//   1. v += g dt into the solver bodies {v, 1/m, ω, 1/I} (one cache line each; body n is the
//      world: zero inverse mass, so wall contacts need no branch);
//   2. a uniform grid over the spheres' bounding box (cell = largest diameter + speculative
//      distance), rebuilt by a counting sort; each sphere i looks for j > i in its 27 cells;
//   3. one point per sphere pair or sphere-wall pair whose gap is at most the speculative
//      distance; rows: normal (≥ 0) and two tangents clamped to the disk |λ_t| ≤ μ λ_n, with
//      μ = √(μ_a μ_b) (Box2D's mixing rule);
//   4. warm start from the last step's impulses of the same pair (key a·2³² + b, walls after the
//      spheres; both lists sorted by key, so matching is one merge walk); the friction impulse
//      is remembered as a world vector and projected on the new tangents;
//   5. `iterations` sweeps, friction then normal per contact; the normal row drives
//      v_n ≥ −s/dt while the gap s > 0 (speculative: it may close the gap, no more) and
//      v_n ≥ β/dt · (−s − slop) while overlapping (Baumgarte feedback);
//   6. x += v dt, q += ½ dt (0, ω) q normalised; the impulses are remembered for step 4.
// No allocation per step once the buffers have grown to the heap's size.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace baseline {

using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;

struct Sphere {
  Vec3 position = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();
  Quat orientation = Quat::Identity();
  double radius = 0.1;
  double inverse_mass = 10.0;
  double inverse_inertia = 1.0 / (0.4 * 0.1 * 0.1 * 0.1);  // a solid sphere's: isotropic
  double friction = 0.5;
};

// The half-space n·x ≥ offset is free; its surface is a wall of the bin.
struct Wall {
  Vec3 normal = Vec3::UnitY();
  double offset = 0.0;
  double friction = 0.5;
};

struct Settings {
  double dt = 1.0 / 60.0;
  Vec3 gravity = Vec3(0.0, -9.81, 0.0);
  int iterations = 10;
  double speculative_distance = 0.02;  // m
  double baumgarte = 0.2;              // fraction of the overlap removed per step
  double linear_slop = 0.005;          // m of overlap left alone
};

// One contact of the last step, for warm starting the next.
struct Remembered {
  std::uint64_t key;
  double normal_impulse;
  Vec3 friction_impulse;  // N s, world
};

// What save/restore copy: the bodies and the warm-start cache.
struct State {
  std::vector<Sphere> spheres;
  std::vector<Remembered> cache;
};

class SphereHeap {
 public:
  SphereHeap(std::vector<Sphere> spheres, std::vector<Wall> walls, const Settings& settings);

  void step();
  const std::vector<Sphere>& spheres() const { return spheres_; }
  // Contact points of the last step, speculative ones (gap ≤ speculative_distance) included.
  std::size_t contact_count() const { return contacts_.size(); }
  // m: the deepest overlap among the last step's contacts, as found at the step's start.
  double max_overlap() const;
  void save(State& to) const;
  void restore(const State& from);

 private:
  struct alignas(64) SolverBody {
    Vec3 velocity;
    double inverse_mass;
    Vec3 angular_velocity;
    double inverse_inertia;
  };
  struct Contact {
    std::uint64_t key;
    std::uint32_t a, b;  // solver bodies; b = spheres_.size() for a wall
    Vec3 normal;         // from b toward a
    Vec3 tangent1, tangent2;
    Vec3 arm_a, arm_b;   // contact point − body centre
    double normal_mass, tangent_mass1, tangent_mass2;  // 1 / (J M⁻¹ Jᵀ) of each row
    double target;       // m/s: the least normal velocity the row allows
    double gap;          // m: s, negative when overlapping
    double friction;
    double normal_impulse, tangent_impulse1, tangent_impulse2;
  };

  void build_grid();
  void find_contacts();
  void add_contact(std::uint32_t a, std::uint32_t b, std::uint64_t key, const Vec3& normal,
                   double gap, double friction);
  void prepare_and_warm_start();
  void solve_sweep();
  void integrate_and_remember();

  std::vector<Sphere> spheres_;
  std::vector<Wall> walls_;
  Settings settings_;
  double cell_ = 0.0;  // m: the grid's cell edge
  std::vector<SolverBody> bodies_;  // spheres_.size() + 1 (the world)
  // The grid: cells x fastest, each sphere's cell, the spheres by cell (counting sort).
  Vec3 lower_ = Vec3::Zero();
  int dims_[3] = {1, 1, 1};
  std::vector<std::uint32_t> cell_start_, cell_cursor_, cell_of_, by_cell_;
  std::vector<std::uint32_t> neighbours_;  // one sphere's candidates, sorted
  std::vector<Contact> contacts_;
  std::vector<Remembered> cache_;
};

}  // namespace baseline
