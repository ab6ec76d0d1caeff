#include "engine/joint_tree.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numeric>

namespace rigidlab {

namespace {
using Square = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, JointTree::max_rows,
                             JointTree::max_rows>;
using RowBlock = Eigen::Matrix<double, JointTree::max_rows, 6>;
// A joint's rows as a vector: sized at run time, at most max_rows (no heap).
using RowsMap = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 1, 0, JointTree::max_rows, 1>>;

// W of a solver body, 6 x 6: m⁻¹ E and I⁻¹ (world frame).
JointTree::Matrix6 inverse_mass_matrix(const SolverBody& b) {
  JointTree::Matrix6 w = JointTree::Matrix6::Zero();
  w.topLeftCorner<3, 3>().diagonal().setConstant(b.inverse_mass);
  w.bottomRightCorner<3, 3>() = b.inverse_inertia;
  return w;
}
}  // namespace

// ---- building the forest -----------------------------------------------------------------------

void JointTree::clear(std::size_t slots) {
  joints_.clear();
  body_nodes_.clear();
  jacobians_.clear();
  slot_node_.assign(slots, -1);
  union_find_.resize(slots);
  std::iota(union_find_.begin(), union_find_.end(), 0u);
  grounded_.assign(slots, 0);
  refused_.clear();
  taken_.clear();
}

std::uint32_t JointTree::find(std::uint32_t slot) {
  while (union_find_[slot] != slot) {
    union_find_[slot] = union_find_[union_find_[slot]];  // path halving
    slot = union_find_[slot];
  }
  return slot;
}

std::int32_t JointTree::node_of(std::uint32_t slot, const SolverBody* bodies) {
  if (!(bodies[slot].inverse_mass > 0.0)) return -1;  // the world, static and kinematic bodies
  if (slot_node_[slot] < 0) {
    slot_node_[slot] = static_cast<std::int32_t>(body_nodes_.size());
    body_nodes_.push_back({slot, -1});
  }
  return slot_node_[slot];
}

bool JointTree::offer(std::uint32_t a, std::uint32_t b, const Jacobian* rows, int size,
                      const SolverBody* bodies) {
  taken_.push_back(0);
  if (size < 1 || size > max_rows || a == b) return false;
  const bool dynamic_a = bodies[a].inverse_mass > 0.0, dynamic_b = bodies[b].inverse_mass > 0.0;
  if (!dynamic_a && !dynamic_b) return false;
  if (dynamic_a && dynamic_b) {  // joins two trees, or closes a loop
    const std::uint32_t ra = find(a), rb = find(b);
    if (ra == rb || (grounded_[ra] && grounded_[rb])) {
      refused_.push_back(a);
      return false;
    }
    union_find_[ra] = rb;
    grounded_[rb] = grounded_[ra] || grounded_[rb];
  } else {  // to the world: a tree holds to the world by one joint at most
    const std::uint32_t slot = dynamic_a ? a : b;
    const std::uint32_t r = find(slot);
    if (grounded_[r]) {
      refused_.push_back(slot);
      return false;
    }
    grounded_[r] = 1;
  }
  JointNode j{a, b, node_of(a, bodies), node_of(b, bodies),
              static_cast<std::uint32_t>(jacobians_.size()), static_cast<std::uint8_t>(size),
              static_cast<std::uint32_t>(taken_.size() - 1), true};
  joints_.push_back(j);
  jacobians_.insert(jacobians_.end(), rows, rows + size);
  taken_.back() = 1;
  return true;
}

void JointTree::drop_looped() {
  if (refused_.empty()) return;
  looped_.assign(union_find_.size(), 0);
  for (std::uint32_t slot : refused_) looped_[find(slot)] = 1;
  // Keep the joints of the other trees, their rows and body nodes renumbered in order.
  std::fill(slot_node_.begin(), slot_node_.end(), -1);
  body_nodes_.clear();
  kept_rows_.clear();
  std::size_t kept = 0;
  for (JointNode j : joints_) {
    const std::uint32_t slot = j.node_a >= 0 ? j.a : j.b;
    if (looped_[find(slot)]) {
      taken_[j.offer] = 0;
      continue;
    }
    kept_rows_.insert(kept_rows_.end(), jacobians_.begin() + j.first,
                      jacobians_.begin() + j.first + j.size);
    j.first = static_cast<std::uint32_t>(kept_rows_.size() - j.size);
    for (auto [side, node] : {std::pair{j.a, &j.node_a}, std::pair{j.b, &j.node_b}}) {
      if (*node < 0) continue;
      if (slot_node_[side] < 0) {
        slot_node_[side] = static_cast<std::int32_t>(body_nodes_.size());
        body_nodes_.push_back({side, -1});
      }
      *node = slot_node_[side];
    }
    joints_[kept++] = j;
  }
  joints_.resize(kept);
  jacobians_.swap(kept_rows_);
}

// Breadth first from a root body of each tree: the order is root first, every node after its
// parent; eliminating from the back is leaves first.
void JointTree::order() {
  const std::size_t nb = body_nodes_.size();
  adjacency_start_.assign(nb + 1, 0);
  for (const JointNode& j : joints_) {
    if (j.node_a >= 0) ++adjacency_start_[static_cast<std::size_t>(j.node_a) + 1];
    if (j.node_b >= 0) ++adjacency_start_[static_cast<std::size_t>(j.node_b) + 1];
  }
  for (std::size_t i = 0; i < nb; ++i) adjacency_start_[i + 1] += adjacency_start_[i];
  adjacency_.resize(adjacency_start_[nb]);
  cursor_.assign(adjacency_start_.begin(), adjacency_start_.end() - 1);
  for (std::uint32_t k = 0; k < joints_.size(); ++k)
    for (std::int32_t n : {joints_[k].node_a, joints_[k].node_b})
      if (n >= 0) adjacency_[cursor_[static_cast<std::size_t>(n)]++] = k;

  order_.clear();
  for (BodyNode& n : body_nodes_) n.parent = -2;  // −2: not reached yet
  // A tree held by a joint to the world is rooted at that joint (the joint must come after its
  // one body: a leaf joint has the zero block −Γ, singular for rigid rows); the others at a body.
  for (std::uint32_t k = 0; k < joints_.size(); ++k) {
    JointNode& j = joints_[k];
    if (j.node_a >= 0 && j.node_b >= 0) continue;
    j.parent_is_a = j.node_a < 0;  // the parent is the world
    order_.push_back({k, true});
    reach(order_.size() - 1);
  }
  for (std::uint32_t root = 0; root < nb; ++root) {
    if (body_nodes_[root].parent != -2) continue;
    body_nodes_[root].parent = -1;
    order_.push_back({root, false});
    reach(order_.size() - 1);
  }
  body_w_.resize(nb);
  body_x_.resize(nb);
  joint_w_.resize(jacobians_.size());
  joint_x_.resize(jacobians_.size());
}

// Appends the nodes below order_[next] breadth first.
void JointTree::reach(std::size_t next) {
  for (; next < order_.size(); ++next) {
    const Order o = order_[next];
    if (!o.joint) {
      for (std::uint32_t e = adjacency_start_[o.index]; e < adjacency_start_[o.index + 1]; ++e) {
        const std::uint32_t k = adjacency_[e];
        if (static_cast<std::int32_t>(k) == body_nodes_[o.index].parent) continue;
        joints_[k].parent_is_a = joints_[k].node_a == static_cast<std::int32_t>(o.index);
        order_.push_back({k, true});
      }
    } else {
      const JointNode& j = joints_[o.index];
      const std::int32_t child = j.child();
      if (child < 0) continue;
      body_nodes_[static_cast<std::size_t>(child)].parent = static_cast<std::int32_t>(o.index);
      order_.push_back({static_cast<std::uint32_t>(child), false});
    }
  }
}

// ---- the blocks J_j,i ------------------------------------------------------------------------------

void JointTree::block(const JointNode& j, bool side_a, RowBlock& out) const {
  const double sign = side_a ? -1.0 : 1.0;
  for (int r = 0; r < j.size; ++r) {
    const Jacobian& jac = jacobians_[j.first + static_cast<std::uint32_t>(r)];
    out.block<1, 3>(r, 0) = sign * jac.linear.transpose();
    out.block<1, 3>(r, 3) = sign * (side_a ? jac.angular_a : jac.angular_b).transpose();
  }
}

JointTree::Vector6 JointTree::transpose_times(const JointNode& j, bool side_a,
                                              const double* y) const {
  Vec3 linear = Vec3::Zero(), angular = Vec3::Zero();
  for (int r = 0; r < j.size; ++r) {
    const Jacobian& jac = jacobians_[j.first + static_cast<std::uint32_t>(r)];
    linear += y[r] * jac.linear;
    angular += y[r] * (side_a ? jac.angular_a : jac.angular_b);
  }
  Vector6 out;
  out << linear, angular;
  return side_a ? Vector6(-out) : out;
}

void JointTree::times(const JointNode& j, bool side_a, const Vector6& x, double* out) const {
  const Vec3 linear = x.head<3>(), angular = x.tail<3>();
  for (int r = 0; r < j.size; ++r) {
    const Jacobian& jac = jacobians_[j.first + static_cast<std::uint32_t>(r)];
    const double value = jac.linear.dot(linear) + (side_a ? jac.angular_a : jac.angular_b).dot(angular);
    out[r] = side_a ? -value : value;
  }
}

// ---- factor and solve -----------------------------------------------------------------------------

void JointTree::factor(const SolverBody* bodies, double compliance, Factor& f) const {
  f.compliance = compliance;
  f.valid = true;
  f.body_inverse.resize(body_nodes_.size());
  f.joint_inverse.resize(joints_.size());
  RowBlock jc;
  for (std::size_t i = order_.size(); i-- > 0;) {
    const Order o = order_[i];
    if (o.joint) {  // E_j = Γ_j + J_jc D_c⁻¹ J_jcᵀ
      const JointNode& j = joints_[o.index];
      const int s = j.size;
      Square e = Square::Zero(s, s);
      double scale = 0.0;  // the largest diagonal entry of K_jj
      for (int r = 0; r < s; ++r)
        for (int c = 0; c < s; ++c) {
          const double k = coupling(jacobians_[j.first + r], jacobians_[j.first + c],
                                    bodies[j.a], bodies[j.b]);
          e(r, c) = compliance * k;
          if (r == c) scale = std::max(scale, k);
        }
      const std::int32_t child = j.child();
      if (child >= 0) {
        block(j, !j.parent_is_a, jc);
        const auto js = jc.topRows(s);
        e += js * f.body_inverse[static_cast<std::size_t>(child)] * js.transpose();
      }
      const Eigen::LLT<Square> llt(e);
      const double smallest =
          llt.info() == Eigen::Success ? llt.matrixLLT().diagonal().cwiseAbs().minCoeff() : 0.0;
      if (!(smallest * smallest > 1e-12 * scale)) {
        f.valid = false;
        return;
      }
      Matrix6& inverse = f.joint_inverse[o.index];
      inverse.setZero();
      inverse.topLeftCorner(s, s) = llt.solve(Square::Identity(s, s));
      continue;
    }
    // A body: D⁻¹ = (M + P)⁻¹ = (E + W P)⁻¹ W, P = Σ_children J_kᵀ E_k⁻¹ J_k.
    const BodyNode& n = body_nodes_[o.index];
    Matrix6 p = Matrix6::Zero();
    for (std::uint32_t e = adjacency_start_[o.index]; e < adjacency_start_[o.index + 1]; ++e) {
      const std::uint32_t k = adjacency_[e];
      if (static_cast<std::int32_t>(k) == n.parent) continue;
      const JointNode& j = joints_[k];
      block(j, j.parent_is_a, jc);
      const int s = j.size;
      const auto js = jc.topRows(s);
      p += js.transpose() * f.joint_inverse[k].topLeftCorner(s, s) * js;
    }
    const Matrix6 w = inverse_mass_matrix(bodies[n.slot]);
    const Matrix6 d = (Matrix6::Identity() + w * p).partialPivLu().solve(w);
    f.body_inverse[o.index] = 0.5 * (d + d.transpose());
  }
}

double JointTree::solve(const Factor& f, SolverBody* set, const double* bias, double* impulse) {
  double largest = 0.0;
  // rhs = −(J v + bias + Γ λ), Γ_j = c K_jj
  for (const JointNode& j : joints_) {
    const SolverBody& a = set[j.a];
    const SolverBody& b = set[j.b];
    Vec3 linear = Vec3::Zero(), angular_a = Vec3::Zero(), angular_b = Vec3::Zero();
    if (f.compliance != 0.0)  // Jᵀ λ, for K_jj λ = J W Jᵀ λ
      for (int r = 0; r < j.size; ++r) {
        const Jacobian& jac = jacobians_[j.first + r];
        const double l = impulse[j.first + r];
        linear += l * jac.linear, angular_a += l * jac.angular_a, angular_b += l * jac.angular_b;
      }
    const Vec3 wa = a.inverse_inertia * angular_a, wb = b.inverse_inertia * angular_b;
    for (int r = 0; r < j.size; ++r) {
      const Jacobian& jac = jacobians_[j.first + r];
      const double v = jac.linear.dot(b.velocity - a.velocity) +
                       jac.angular_b.dot(b.angular_velocity) - jac.angular_a.dot(a.angular_velocity);
      const double error = v + bias[j.first + r];
      largest = std::max(largest, std::abs(error));
      const double soft = (a.inverse_mass + b.inverse_mass) * jac.linear.dot(linear) +
                          jac.angular_a.dot(wa) + jac.angular_b.dot(wb);
      joint_w_[j.first + r] = -(error + f.compliance * soft);
    }
  }
  for (Vector6& w : body_w_) w.setZero();
  // Up the tree (leaves first): z_n = D_n⁻¹ w_n, w_parent −= H_parent,n z_n.
  for (std::size_t i = order_.size(); i-- > 0;) {
    const Order o = order_[i];
    if (o.joint) {
      const JointNode& j = joints_[o.index];
      RowsMap w(&joint_w_[j.first], j.size), z(&joint_x_[j.first], j.size);
      z.noalias() = -f.joint_inverse[o.index].topLeftCorner(j.size, j.size) * w;
      const std::int32_t parent = j.parent();
      if (parent >= 0)
        body_w_[static_cast<std::size_t>(parent)] -= transpose_times(j, j.parent_is_a, z.data());
    } else {
      body_x_[o.index] = f.body_inverse[o.index] * body_w_[o.index];
      const std::int32_t q = body_nodes_[o.index].parent;
      if (q < 0) continue;
      const JointNode& j = joints_[static_cast<std::size_t>(q)];
      double jz[max_rows];
      times(j, !j.parent_is_a, body_x_[o.index], jz);
      for (int r = 0; r < j.size; ++r) joint_w_[j.first + r] -= jz[r];
    }
  }
  // Down the tree (root first): x_n = z_n − D_n⁻¹ H_n,parent x_parent.
  for (const Order o : order_) {
    if (o.joint) {
      const JointNode& j = joints_[o.index];
      if (j.parent() < 0) continue;
      double jx[max_rows];
      times(j, j.parent_is_a, body_x_[static_cast<std::size_t>(j.parent())], jx);
      RowsMap x(&joint_x_[j.first], j.size);
      x.noalias() += f.joint_inverse[o.index].topLeftCorner(j.size, j.size) * RowsMap(jx, j.size);
    } else {
      const std::int32_t q = body_nodes_[o.index].parent;
      if (q < 0) continue;
      const JointNode& j = joints_[static_cast<std::size_t>(q)];
      body_x_[o.index] -=
          f.body_inverse[o.index] * transpose_times(j, !j.parent_is_a, &joint_x_[j.first]);
    }
  }
  // Δλ = −y; the bodies' velocity changes are x = W Jᵀ Δλ.
  for (std::size_t r = 0; r < jacobians_.size(); ++r) impulse[r] -= joint_x_[r];
  for (std::size_t n = 0; n < body_nodes_.size(); ++n) {
    SolverBody& b = set[body_nodes_[n].slot];
    b.velocity += body_x_[n].head<3>();
    b.angular_velocity += body_x_[n].tail<3>();
  }
  return largest;
}

}  // namespace rigidlab
