// The joints' blocks of equality rows (a hinge's 3 point rows and 2 angular rows, a ball's 3
// point rows, ...) as the Gauss-Seidel sweeps of engine/solver.cpp read them: only what a sweep
// needs, packed in sweep order.
//
// Why. A sweep is memory bound: a block's update is ~100 flops against everything it reads.
// Kept as the solver's general rows (engine/constraint_row.hpp ConstraintRow: Jacobian, I⁻¹ Jᵀ
// of both sides, effective mass, bounds; plus the solver's per-row state) and a 6 x 6 padded
// K⁻¹, a hinge took ~1.45 kB, and Box2D v3's joint_grid at 100 x 100 (19,800 hinges, 29 MB
// per pass) streamed from memory where the 50 x 50 grid (7 MB) stayed in the cache: 1.75 times
// the cost per joint (bench/joint_bench.cpp). Here a hinge takes ~0.4 kB:
//   - the Jacobian in the form the joint wrote it in, recognised exactly at prepare: the three
//     point rows along the world axes (engine/constraint_row.hpp point_jacobian(e_k, r_a, r_b))
//     as r_a and r_b (6 numbers for 27), an angular row (linear 0, angular_a = angular_b = k) as
//     k (3 for 9), any other row as its 9 numbers;
//   - I⁻¹ Jᵀ is not kept: the block's angular impulses are summed and multiplied by each body's
//     I⁻¹ once (2 products of 3 x 3 per update, instead of 2 cached vectors per row);
//   - K⁻¹ (symmetric) as its lower triangle;
//   - the biases and impulses (velocity and push) in arrays of their own, by block row.
// The update itself is the solver's block update (engine/solver.cpp, sweep_group): with
// K_ij = J_i W J_jᵀ,  Δλ = −K⁻¹ (mass_scale J v + bias) − impulse_scale λ  (Box2D v3's soft
// form; rigid: mass_scale 1, impulse_scale 0), then Δv = W Jᵀ Δλ.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/constraint_row.hpp"

namespace rigidlab {

class JointBlocks {
 public:
  static constexpr int max_size = 6;
  static constexpr std::uint32_t none = 0xffffffffu;

  void clear();
  // A block of `size` (2 to max_size) equality rows between solver slots a and b: its K⁻¹ at the
  // bodies' present inverse masses; `bias` the velocity bias of each row (engine/solver.cpp),
  // `push_bias` that of the soft position row, `soft` the softness of the push rows. Returns
  // its index, or none when K cannot be inverted (some row asks nothing of either body, or two
  // rows ask nearly the same): the rows are then solved one by one. The impulses start at 0.
  std::uint32_t add(std::uint32_t a, std::uint32_t b, const Jacobian* rows, int size,
                    const SolverBody& body_a, const SolverBody& body_b, const double* bias,
                    const double* push_bias, const Softness& soft);
  // One update of block k on the body velocities (push false: rigid, the velocity biases) or on
  // the push velocities (push true: the soft position rows). Returns the largest |J v + bias|
  // before the update.
  double solve(std::uint32_t k, SolverBody* set, bool push);

  std::size_t size() const { return heads_.size(); }
  // The velocity and push impulses of row i of block k.
  double& impulse(std::uint32_t k, int i) { return impulse_[heads_[k].row + i]; }
  double& push_impulse(std::uint32_t k, int i) { return push_impulse_[heads_[k].row + i]; }

 private:
  struct Head {
    std::uint32_t a, b;   // solver slots
    std::uint32_t data;   // first number in data_: mass_scale, impulse_scale, Jacobians, K⁻¹
    std::uint32_t row;    // first block row (bias_, impulse_, ...)
    std::uint8_t size;
    std::uint8_t point;   // rows 0 to 2 are point rows along x, y, z (data: r_a, r_b)
    std::uint8_t angular; // bit i: row i (past the point rows) is angular (data: k)
  };
  template <int size>
  double solve_sized(const Head& h, SolverBody* set, bool push);

  std::vector<Head> heads_;
  std::vector<double> data_;
  std::vector<double> bias_, push_bias_, impulse_, push_impulse_;
};

}  // namespace rigidlab
