// The exact, linear-time solve of the joints' equality rows over joint trees: D. Baraff,
// "Linear-Time Dynamics using Lagrange Multipliers", SIGGRAPH 1996.
//
// Why. Gauss-Seidel (engine/solver.cpp) solves each joint's block of equality rows exactly, but
// passes a load along a chain one joint per sweep: a 10-link chain hanging from the world keeps
// a residual of 0.03 m/s after 10 sweeps. On a tree of bodies and joints the whole system can
// be solved exactly in O(rows).
//
// The system. A joint j has s_j equality rows with Jacobian J_j (engine/constraint_row.hpp) on
// its two bodies; W is the inverse mass matrix, M = W⁻¹ (per body, 6 x 6: m⁻¹ E and I⁻¹). A
// sweep asks for the impulses Δλ that bring every row to its target at once:
//   J (v + W Jᵀ Δλ) + b + Γ (λ + Δλ) = 0,   i.e.   (K + Γ) Δλ = −(J v + b + Γ λ),   K = J W Jᵀ,
// with b the row's bias (m/s) and Γ its softness (0 for the rigid velocity rows). Baraff writes
// it as the sparse symmetric system (his eq. 7, with −Γ in the place of his −C)
//   [ M   Jᵀ ] [ x ]   [  0  ]
//   [ J  −Γ  ] [ y ] = [ rhs ],   rhs = −(J v + b + Γ λ),   x = Δv = W Jᵀ Δλ,  y = −Δλ,
// whose graph has one node per dynamic body (6 x 6 block M_i) and one per joint (s_j x s_j
// block −Γ_j), and an edge J_ji between a joint and each dynamic body it holds. The world and
// static bodies have infinite mass: they are not nodes, so a joint to the world has one
// neighbour. When that graph is acyclic, block LDLᵀ with every node eliminated before its
// parent (leaves first) makes no fill-in: eliminating a node only changes its parent's block,
//   D_n = H_nn − Σ_{children c} H_nc D_c⁻¹ H_cn,
// and the solve is a pass up the tree (w_n = rhs_n − Σ_c H_nc D_c⁻¹ w_c) and a pass down
// (x_n = D_n⁻¹ (w_n − H_n,parent x_parent)). Baraff's factor() and solve().
// Here a body's block is kept as its inverse, D⁻¹ = (M + P)⁻¹ = (E + W P)⁻¹ W (P the sum of its
// children's J_cᵀ E_c⁻¹ J_c): that needs W only, so a body whose inverse inertia is singular (a
// locked rotation) is still a node. A joint's block is −E_j, E_j = Γ_j + J_jc D_c⁻¹ J_jcᵀ for its
// child body c: a joint must not be a leaf (a rigid leaf's block −Γ_j = 0 cannot be
// eliminated), so a tree held by the world is rooted at its joint to the world, and a second
// joint between the tree and the world closes a loop through the world (a garland held at both
// ends) and stays with Gauss-Seidel. E_j is positive definite unless the joint's rows ask
// nothing of its child side, which factor() reports; the solver then sweeps by Gauss-Seidel.
//
// Soft rows in matrix form. Box2D v3's soft row (E. Catto, "Solver2D" notes, soft step;
// b2MakeSoft in Box2D v3's solver.c) updates the accumulated impulse by
//   Δλ = −m (s_m J v + b') − s_i λ,   m = 1/K,  s_m = a2/(1 + a2),  s_i = 1/(1 + a2),
// with a2 = hω(2ζ + hω) and b' = s_m β C its bias (engine/constraint_row.hpp make_soft).
// Write v' = v + W Jᵀ Δλ (so J v' = J v + K Δλ) and λ' = λ + Δλ; since 1 − s_m = s_i,
//   K Δλ = −s_m (J v' − K Δλ) − b' − s_i K λ  ⇒  s_i K λ' = −s_m (J v' + β C)
//   ⇒  J v' + β C + c K λ' = 0,   c = s_i/s_m = 1/a2   (Softness::compliance).
// That is the soft constraint above with b = β C and Γ = c K: Catto's softness is per unit
// effective mass, so for a block of rows solved together (a joint) Γ_j = c K_jj, the joint's
// own diagonal block of K (both bodies). Solved for one block it gives back the block update of
// engine/solver.cpp (Δλ = −K_jj⁻¹ (s_m J v + b') − s_i λ); solved for the tree it is the exact
// solution of all the soft rows at once. Rigid rows are c = 0.
//
// Use (engine/solver.cpp, soft_step only). At prepare the solver offers each joint's equality
// block in turn; blocks that would close a loop are refused and stay in the Gauss-Seidel
// sweeps, as do limits, springs, motors and contacts. The forest is ordered once per substep
// and factored once for the rigid velocity rows (c = 0) and once for soft_step's soft position
// rows; each sweep then solves all the forest's rows in one pass. Storage grows with the
// largest forest seen and is reused: no allocation per step once warm.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "engine/constraint_row.hpp"

namespace rigidlab {

class JointTree {
 public:
  static constexpr int max_rows = 6;  // rows of one joint's block
  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  using Vector6 = Eigen::Matrix<double, 6, 1>;

  // The numbers of one factorisation (of K + c blockdiag(K_jj)), per node.
  struct Factor {
    double compliance = 0.0;
    bool valid = false;  // false: some joint block was singular; sweep by Gauss-Seidel
    std::vector<Matrix6> body_inverse;   // D_i⁻¹ of each body node
    std::vector<Matrix6> joint_inverse;  // E_j⁻¹ (top-left s_j x s_j) of each joint node
  };

  // Starts a new forest over `slots` solver bodies (slot indices as the solver's).
  void clear(std::size_t slots);
  // Offers a joint's block of `size` equality rows (1 to max_rows) between slots a and b: taken
  // (true) unless neither body is dynamic (inverse mass 0) or the joint would close a loop,
  // among dynamic bodies or through the world (a second joint between a tree and the world).
  // The taken joints' rows are numbered in the order offered.
  bool offer(std::uint32_t a, std::uint32_t b, const Jacobian* rows, int size,
             const SolverBody* bodies);
  // Drops every tree that a refused joint would have closed a loop in (after the last offer,
  // before order): those trees are then swept by Gauss-Seidel as a whole.
  void drop_looped();
  // Whether the joint of the k-th offer (counting every call) is in the forest.
  bool taken(std::size_t k) const { return k < taken_.size() && taken_[k] != 0; }
  // Orders the forest leaves-first (after the last offer).
  void order();
  // Factors K + Γ, Γ_j = compliance · K_jj, for the bodies' present inverse mass properties.
  void factor(const SolverBody* bodies, double compliance, Factor& f) const;
  // Solves for every row at once: the impulses Δλ with
  //   J v' + bias + Γ (λ + Δλ) = 0,   v' = v + W Jᵀ Δλ,
  // adds Δλ to `impulse` and W Jᵀ Δλ to the velocities of `set` (bodies or push velocities, same
  // inverse masses as factored). bias and impulse are by tree row. Returns the largest
  // |J v + bias| before the update.
  double solve(const Factor& f, SolverBody* set, const double* bias, double* impulse);

  std::size_t joint_count() const { return joints_.size(); }
  std::size_t row_count() const { return jacobians_.size(); }
  std::size_t body_count() const { return body_nodes_.size(); }

 private:
  struct JointNode {
    std::uint32_t a, b;        // solver slots
    std::int32_t node_a = -1;  // body nodes of a and b (−1: not dynamic)
    std::int32_t node_b = -1;
    std::uint32_t first = 0;   // first tree row
    std::uint8_t size = 0;
    std::uint32_t offer = 0;   // its offer's number
    bool parent_is_a = true;   // which side is the parent (a body node, or the world)
    std::int32_t parent() const { return parent_is_a ? node_a : node_b; }
    std::int32_t child() const { return parent_is_a ? node_b : node_a; }
  };
  struct BodyNode {
    std::uint32_t slot;
    std::int32_t parent = -1;  // parent joint node (−1: root)
  };
  struct Order {                // an entry of the elimination order
    std::uint32_t index;
    bool joint;
  };
  std::int32_t node_of(std::uint32_t slot, const SolverBody* bodies);
  std::uint32_t find(std::uint32_t slot);
  void reach(std::size_t next);
  // The s x 6 block J_j,side (side a: [−linear, −angular_a], b: [linear, angular_b]).
  void block(const JointNode& j, bool side_a, Eigen::Matrix<double, max_rows, 6>& out) const;
  Vector6 transpose_times(const JointNode& j, bool side_a, const double* y) const;
  void times(const JointNode& j, bool side_a, const Vector6& x, double* out) const;

  std::vector<JointNode> joints_;
  std::vector<BodyNode> body_nodes_;
  std::vector<Jacobian> jacobians_;  // by tree row
  std::vector<std::int32_t> slot_node_;     // body node of each slot, −1 if none
  std::vector<std::uint32_t> union_find_;   // by slot
  std::vector<std::uint8_t> grounded_;      // by union-find root: the tree has a world joint
  std::vector<std::uint8_t> looped_;        // by union-find root: a joint was refused in it
  std::vector<std::uint32_t> refused_;      // a dynamic slot of each joint refused for a loop
  std::vector<std::uint8_t> taken_;         // by offer
  std::vector<Jacobian> kept_rows_;         // drop_looped's scratch
  std::vector<std::uint32_t> adjacency_start_, adjacency_, cursor_;  // joints of each body node
  std::vector<Order> order_;  // root first; eliminated from the back
  // solve scratch, by node
  std::vector<Vector6> body_w_, body_x_;
  std::vector<double> joint_w_, joint_x_;  // by tree row
};

}  // namespace rigidlab
