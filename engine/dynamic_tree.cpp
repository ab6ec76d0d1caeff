// The dynamic AABB tree: insertion by the surface area heuristic, rotations on the way up, a
// median-split rebuild when the height passes its limit. See engine/dynamic_tree.hpp.
#include "engine/dynamic_tree.hpp"

#include <limits>

namespace rigidlab {

int DynamicTree::height_limit(std::int32_t leaves) {
  int log2_ceiling = 0;
  while (log2_ceiling < 31 && (std::int64_t{1} << log2_ceiling) < leaves) ++log2_ceiling;
  return 2 * log2_ceiling + 6;
}

std::int32_t DynamicTree::allocate_node() {
  if (free_list_ == null_node) {
    nodes_.push_back(Node{});
    return static_cast<std::int32_t>(nodes_.size() - 1);
  }
  const std::int32_t node = free_list_;
  free_list_ = nodes_[node].parent;
  nodes_[node] = Node{};
  return node;
}

void DynamicTree::free_node(std::int32_t node) {
  nodes_[node].parent = free_list_;
  nodes_[node].height = -1;
  free_list_ = node;
}

void DynamicTree::reserve(std::int32_t leaves) {
  if (leaves <= 0) return;
  nodes_.reserve(2 * static_cast<std::size_t>(leaves) - 1);
  rebuild_leaves_.reserve(static_cast<std::size_t>(leaves));
}

void DynamicTree::clear() {
  nodes_.clear();
  root_ = free_list_ = null_node;
  leaf_count_ = 0;
}

std::int32_t DynamicTree::insert(const Aabb& box, std::int32_t payload) {
  // An insertion takes at most two nodes (the leaf and its new parent), and a rebuild one more
  // slot of scratch: growing both first means that if that fails nothing has changed, and
  // that nothing after it allocates.
  if (nodes_.size() + 2 > nodes_.capacity()) nodes_.reserve(2 * nodes_.capacity() + 2);
  const auto leaves = static_cast<std::size_t>(leaf_count_) + 1;
  if (rebuild_leaves_.capacity() < leaves) rebuild_leaves_.reserve(2 * leaves);
  const std::int32_t leaf = allocate_node();
  Node& node = nodes_[leaf];
  node.box = box;
  node.child[1] = payload;
  ++leaf_count_;
  insert_leaf(leaf);
  if (height() > height_limit(leaf_count_)) rebuild();
  return leaf;
}

void DynamicTree::remove(std::int32_t leaf) {
  remove_leaf(leaf);
  free_node(leaf);
  --leaf_count_;
}

// A moved leaf is re-inserted near where it was (Bullet's btDbvt::update starts its insertion a
// few levels above the old place, too): from the lowest ancestor of its old place whose box
// holds the new box, where the ancestors above do not grow, so the surface area heuristic
// restricted to that subtree is exact. Short paths that are in cache, where an insertion from
// the root would walk the whole height. The ancestors are refitted and rotated only as far up
// as anything changes.
void DynamicTree::move(std::int32_t leaf, const Aabb& box) {
  if (leaf == root_) {
    nodes_[leaf].box = box;
    return;
  }
  const std::int32_t parent = nodes_[leaf].parent;
  const std::int32_t sibling =
      nodes_[parent].child[0] == leaf ? nodes_[parent].child[1] : nodes_[parent].child[0];
  remove_leaf(leaf);
  nodes_[leaf].box = box;
  std::int32_t start = sibling;
  if (nodes_[start].parent != null_node) start = nodes_[start].parent;
  while (start != root_ && !nodes_[start].box.contains(box)) start = nodes_[start].parent;
  attach(leaf, find_best_sibling(start, box), false);
  if (height() > height_limit(leaf_count_)) rebuild();
}

// The sibling for a new leaf D that adds the least surface area to the tree (Box2D v3,
// b2FindBestSibling). Making node S the sibling of D costs area(S ∪ D), the new parent, plus what
// every ancestor of S grows by taking in D (the "inherited" cost). Below an internal node S no
// sibling can cost less than inherited + area(S ∪ D) − area(S) + area(D) (S grows, and the new
// parent is at least as large as D), so the descent follows the child with the smaller lower
// bound and stops when neither child's bound beats the best cost found: one greedy path.
std::int32_t DynamicTree::find_best_sibling(std::int32_t top, const Aabb& box) const {
  const Vec3 centre = box.lower + box.upper;
  const double area_d = box.half_area();
  std::int32_t index = top;
  double area_base = nodes_[index].box.half_area();
  double direct = nodes_[index].box.merged(box).half_area();
  double inherited = 0.0;
  std::int32_t best = index;
  double best_cost = direct;
  constexpr double infinity = std::numeric_limits<double>::infinity();
  while (!is_leaf(index)) {
    const Node& node = nodes_[index];
    if (direct + inherited < best_cost) best = index, best_cost = direct + inherited;
    inherited += direct - area_base;  // what this node grows by, seen by its descendants
    double lower_bound[2], child_direct[2], child_area[2];
    bool leaf[2];
    for (int k = 0; k < 2; ++k) {
      const std::int32_t child = node.child[k];
      const Aabb& child_box = nodes_[child].box;
      child_direct[k] = child_box.merged(box).half_area();
      leaf[k] = is_leaf(child);
      child_area[k] = child_box.half_area();
      if (leaf[k]) {
        lower_bound[k] = infinity;
        if (child_direct[k] + inherited < best_cost)
          best = child, best_cost = child_direct[k] + inherited;
      } else {
        lower_bound[k] = inherited + child_direct[k] + std::min(area_d - child_area[k], 0.0);
      }
    }
    if (leaf[0] && leaf[1]) break;
    if (best_cost <= lower_bound[0] && best_cost <= lower_bound[1]) break;
    if (lower_bound[0] == lower_bound[1] && !leaf[0]) {
      // No choice by area (both children contain D, say): take the nearer centre.
      for (int k = 0; k < 2; ++k) {
        const Aabb& child_box = nodes_[node.child[k]].box;
        lower_bound[k] = (child_box.lower + child_box.upper - centre).squaredNorm();
      }
    }
    const int k = lower_bound[0] < lower_bound[1] && !leaf[0] ? 0 : 1;
    index = node.child[k];
    area_base = child_area[k];
    direct = child_direct[k];
  }
  return best;
}

void DynamicTree::insert_leaf(std::int32_t leaf) {
  if (root_ == null_node) {
    root_ = leaf;
    nodes_[leaf].parent = null_node;
    return;
  }
  attach(leaf, find_best_sibling(root_, nodes_[leaf].box), true);
}

// Makes a new parent for `sibling` and `leaf` in sibling's place, then refits the ancestors and
// offers each a rotation (Box2D v3, b2InsertLeaf): all the way to the root, or, when not
// `to_root`, up to the first one whose box and height stay the same.
void DynamicTree::attach(std::int32_t leaf, std::int32_t sibling, bool to_root) {
  const std::int32_t parent = allocate_node();  // may move nodes_: no references held across
  const std::int32_t old_parent = nodes_[sibling].parent;
  nodes_[parent].parent = old_parent;
  nodes_[parent].child[0] = sibling;
  nodes_[parent].child[1] = leaf;
  if (old_parent == null_node) {
    root_ = parent;
  } else {
    Node& above = nodes_[old_parent];
    above.child[above.child[0] == sibling ? 0 : 1] = parent;
  }
  nodes_[sibling].parent = parent;
  nodes_[leaf].parent = parent;
  refit(parent);
  for (std::int32_t index = old_parent; index != null_node; index = nodes_[index].parent) {
    const Node before = nodes_[index];
    refit(index);
    rotate(index);
    if (!to_root && same_box_and_height(before, nodes_[index])) break;
  }
}

void DynamicTree::remove_leaf(std::int32_t leaf) {
  if (leaf == root_) {
    root_ = null_node;
    return;
  }
  const std::int32_t parent = nodes_[leaf].parent;
  const std::int32_t grandparent = nodes_[parent].parent;
  const std::int32_t sibling =
      nodes_[parent].child[0] == leaf ? nodes_[parent].child[1] : nodes_[parent].child[0];
  nodes_[sibling].parent = grandparent;
  if (grandparent == null_node) {
    root_ = sibling;
  } else {
    Node& above = nodes_[grandparent];
    above.child[above.child[0] == parent ? 0 : 1] = sibling;
  }
  free_node(parent);
  nodes_[leaf].parent = null_node;
  // Refit the ancestors; above the first one that keeps its box and height nothing changes.
  for (std::int32_t index = grandparent; index != null_node; index = nodes_[index].parent) {
    const Node before = nodes_[index];
    refit(index);
    if (same_box_and_height(before, nodes_[index])) break;
  }
}

void DynamicTree::refit(std::int32_t index) {
  Node& node = nodes_[index];
  const Node& a = nodes_[node.child[0]];
  const Node& b = nodes_[node.child[1]];
  node.box = a.box.merged(b.box);
  node.height = 1 + std::max(a.height, b.height);
}

// A rotation at node A = (B, C) (Box2D v3, b2RotateNodes): swap B with a child F or G of C, or C
// with a child D or E of B, whichever shrinks the node that changes (C becomes (B, G), (F, B);
// B becomes (C, E), (D, C)) the most; none when no swap shrinks it. A's own box is the same
// afterwards (the same leaves lie below it).
void DynamicTree::rotate(std::int32_t index) {
  const Node& node = nodes_[index];
  if (node.height < 2) return;
  int best_down = -1, best_up = 0;
  double best_delta = 0.0;
  for (int down = 0; down < 2; ++down) {
    const Node& stay = nodes_[node.child[down]];      // the child that would go down
    const Node& other = nodes_[node.child[1 - down]];  // the child whose child comes up
    if (other.height == 0) continue;
    const double base = other.box.half_area();
    for (int up = 0; up < 2; ++up) {
      const Aabb& kept = nodes_[other.child[1 - up]].box;
      const double delta = stay.box.merged(kept).half_area() - base;
      if (delta < best_delta) best_delta = delta, best_down = down, best_up = up;
    }
  }
  if (best_down >= 0) swap_with_grandchild(index, best_down, best_up);
}

void DynamicTree::swap_with_grandchild(std::int32_t index, int slot_down, int slot_up) {
  const std::int32_t down = nodes_[index].child[slot_down];
  const std::int32_t other = nodes_[index].child[1 - slot_down];
  const std::int32_t up = nodes_[other].child[slot_up];
  nodes_[index].child[slot_down] = up;
  nodes_[up].parent = index;
  nodes_[other].child[slot_up] = down;
  nodes_[down].parent = other;
  refit(other);
  refit(index);
}

void DynamicTree::rebuild() {
  if (root_ == null_node) return;
  rebuild_leaves_.clear();
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const auto index = static_cast<std::int32_t>(i);
    if (nodes_[i].height == 0) rebuild_leaves_.push_back(index);
    else if (nodes_[i].height > 0) free_node(index);
  }
  root_ = build(rebuild_leaves_.data(), static_cast<std::int32_t>(rebuild_leaves_.size()));
  nodes_[root_].parent = null_node;
}

// The subtree over leaves[0 .. count): split at the median of the centres along the axis where
// they spread most (ties by leaf id, so the split is the same on every platform).
std::int32_t DynamicTree::build(std::int32_t* leaves, std::int32_t count) {
  if (count == 1) return leaves[0];
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (std::int32_t i = 0; i < count; ++i) {
    const Vec3 centre = nodes_[leaves[i]].box.lower + nodes_[leaves[i]].box.upper;
    low = low.cwiseMin(centre);
    high = high.cwiseMax(centre);
  }
  int axis = 0;
  (high - low).maxCoeff(&axis);
  const std::int32_t half = count / 2;
  std::nth_element(leaves, leaves + half, leaves + count, [&](std::int32_t a, std::int32_t b) {
    const double ca = nodes_[a].box.lower[axis] + nodes_[a].box.upper[axis];
    const double cb = nodes_[b].box.lower[axis] + nodes_[b].box.upper[axis];
    return ca < cb || (ca == cb && a < b);
  });
  const std::int32_t left = build(leaves, half);
  const std::int32_t right = build(leaves + half, count - half);
  const std::int32_t node = allocate_node();
  nodes_[node].child[0] = left;
  nodes_[node].child[1] = right;
  nodes_[left].parent = node;
  nodes_[right].parent = node;
  refit(node);
  return node;
}

double DynamicTree::area_ratio() const {
  if (root_ == null_node) return 0.0;
  const double root_area = nodes_[root_].box.half_area();
  double total = 0.0;
  for (std::size_t i = 0; i < nodes_.size(); ++i)
    if (nodes_[i].height > 0 && static_cast<std::int32_t>(i) != root_)
      total += nodes_[i].box.half_area();
  return root_area > 0.0 ? total / root_area : 0.0;
}

std::string DynamicTree::check_subtree(std::int32_t index, std::int32_t parent,
                                       std::int32_t& leaves) const {
  const std::string at = "node " + std::to_string(index);
  if (index < 0 || static_cast<std::size_t>(index) >= nodes_.size()) return at + " out of range";
  const Node& node = nodes_[index];
  if (node.parent != parent) return at + ": parent link broken";
  if (node.height < 0) return at + ": free node in the tree";
  if (node.child[0] == null_node) {
    ++leaves;
    return node.height == 0 ? "" : at + ": leaf with height " + std::to_string(node.height);
  }
  for (int k = 0; k < 2; ++k) {
    const std::string problem = check_subtree(node.child[k], index, leaves);
    if (!problem.empty()) return problem;
  }
  const Node& a = nodes_[node.child[0]];
  const Node& b = nodes_[node.child[1]];
  if (node.height != 1 + std::max(a.height, b.height)) return at + ": wrong height";
  const Aabb u = a.box.merged(b.box);
  if (u.lower != node.box.lower || u.upper != node.box.upper)
    return at + ": box is not the union of its children's";
  return "";
}

std::string DynamicTree::check() const {
  std::int32_t leaves = 0;
  if (root_ != null_node) {
    const std::string problem = check_subtree(root_, null_node, leaves);
    if (!problem.empty()) return problem;
  }
  if (leaves != leaf_count_)
    return std::to_string(leaves) + " leaves reachable, " + std::to_string(leaf_count_) + " held";
  std::size_t free_count = 0;
  for (std::int32_t i = free_list_; i != null_node; i = nodes_[i].parent) {
    if (nodes_[i].height != -1) return "node " + std::to_string(i) + " on the free list in use";
    if (++free_count > nodes_.size()) return "the free list loops";
  }
  const std::size_t used = leaf_count_ == 0 ? 0 : 2 * static_cast<std::size_t>(leaf_count_) - 1;
  if (used + free_count != nodes_.size()) return "nodes lost: neither in the tree nor free";
  return "";
}

}  // namespace rigidlab
