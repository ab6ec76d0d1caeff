// A dynamic bounding volume hierarchy of axis-aligned boxes: a binary tree whose leaves hold the
// boxes and whose internal nodes hold the union of their children's boxes, changed one leaf at a
// time. The broad phase (engine/broad_phase.hpp) keeps one per proxy kind; tools may use one
// directly.
//
// What it follows (each scheme named where it is written, in dynamic_tree.cpp):
// - Insertion picks the sibling that adds the least surface area to the tree (the surface area
//   heuristic, SAH: Goldsmith and Salmon, "Automatic Creation of Object Hierarchies for Ray
//   Tracing", IEEE CG&A 7(5), 1987), found by Box2D v3's branch-and-bound descent
//   (dynamic_tree.c, b2FindBestSibling; E. Catto, "Dynamic Bounding Volume Hierarchies", GDC
//   2019), with surface area in place of Box2D's 2-D perimeter.
// - On the way back up every ancestor is refitted and offered a rotation: swapping one child with
//   a grandchild on the other side when that shrinks the other child's surface area (Box2D v3,
//   b2RotateNodes; Kopta et al., "Fast, Effective BVH Updates for Animated Scenes", I3D 2012).
// - Rotations keep the tree good for queries but do not bound its height. When the height passes
//   2⌈log₂ n⌉ + 6 the whole tree is rebuilt top down by median splits along the longest axis of
//   the leaves' centres (height ⌈log₂ n⌉), so the height is always O(log n) whatever the order
//   of insertions (sorted input is the classic worst case of incremental insertion).
//
// Leaf ids are stable: they stay the same through moves, rotations and rebuilds, until the leaf
// is removed, and a removed id is reused by a later insertion. Nothing allocates once the node
// pool has grown to the largest number of leaves held (reserve() grows it up front).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/math.hpp"

namespace rigidlab {

// An axis-aligned box (m, world): the points p with lower ≤ p ≤ upper componentwise. Boxes given
// to the tree and the broad phase are finite with lower ≤ upper (a point is a box).
struct Aabb {
  Vec3 lower = Vec3::Zero();
  Vec3 upper = Vec3::Zero();

  // Closed boxes: touching faces overlap.
  bool overlaps(const Aabb& b) const {
    return lower.x() <= b.upper.x() && b.lower.x() <= upper.x() && lower.y() <= b.upper.y() &&
           b.lower.y() <= upper.y() && lower.z() <= b.upper.z() && b.lower.z() <= upper.z();
  }
  bool contains(const Aabb& b) const {
    return lower.x() <= b.lower.x() && lower.y() <= b.lower.y() && lower.z() <= b.lower.z() &&
           b.upper.x() <= upper.x() && b.upper.y() <= upper.y() && b.upper.z() <= upper.z();
  }
  Aabb merged(const Aabb& b) const { return {lower.cwiseMin(b.lower), upper.cwiseMax(b.upper)}; }
  // Half the surface area (m²), the SAH cost of a node: xy + yz + zx of the extents.
  double half_area() const {
    const Vec3 e = upper - lower;
    return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
  }
  // Finite, with lower ≤ upper on every axis (false for any NaN).
  bool valid() const {
    return lower.allFinite() && upper.allFinite() && lower.x() <= upper.x() &&
           lower.y() <= upper.y() && lower.z() <= upper.z();
  }
};

class DynamicTree {
 public:
  static constexpr std::int32_t null_node = -1;

  // Adds a leaf with box (valid) carrying payload (any value; the broad phase stores its proxy
  // id); returns its leaf id.
  std::int32_t insert(const Aabb& box, std::int32_t payload);
  // Removes a leaf; its id may be reused by the next insert.
  void remove(std::int32_t leaf);
  // Gives a leaf a new box (re-inserts it where it now fits best); the leaf id stays.
  void move(std::int32_t leaf, const Aabb& box);

  const Aabb& box(std::int32_t leaf) const { return nodes_[leaf].box; }
  std::int32_t payload(std::int32_t leaf) const { return nodes_[leaf].child[1]; }
  std::int32_t leaf_count() const { return leaf_count_; }
  // Edges on the longest root-to-leaf path: 0 for one leaf (and for none).
  int height() const { return root_ == null_node ? 0 : nodes_[root_].height; }
  // The height above which insert() rebuilds: 2⌈log₂ n⌉ + 6 for n leaves.
  static int height_limit(std::int32_t leaves);
  // Sum of the internal nodes' surface areas over the root's (Box2D's b2DynamicTree_GetAreaRatio):
  // the expected number of internal nodes a small query visits, a measure of the tree's quality.
  double area_ratio() const;

  // Rebuilds the tree top down by median splits (height ⌈log₂ n⌉); leaf ids stay.
  void rebuild();
  // Grows the node pool for `leaves` leaves, so that holding that many allocates nothing.
  void reserve(std::int32_t leaves);
  // Removes every leaf; the memory is kept for reuse.
  void clear();
  // Empty when every invariant holds (links both ways, each internal box the union of its
  // children's, heights, leaf count, free list), else the first one broken.
  std::string check() const;

  // Calls visit(leaf) for every leaf whose box overlaps `box`; visit returns false to stop.
  template <class Visit>
  void query(const Aabb& box, Visit&& visit) const;
  // The same for every leaf but `leaf` itself, searched outward from it: the subtrees that hang
  // off its path to the root, nearest first. Right after `leaf` was inserted or moved that path
  // and its siblings are in cache, where a search from the root would fetch nodes afresh.
  template <class Visit>
  void query_around(std::int32_t leaf, const Aabb& box, Visit&& visit) const;
  // Casts the segment origin + t·direction, 0 ≤ t ≤ max_t, through the leaves' boxes: calls
  // visit(leaf, t_enter) for each leaf whose box the segment enters (t_enter ≥ 0 where it
  // enters it, 0 when the origin is inside). As Box2D's b2RayCastCallbackFcn, visit returns the
  // new max_t: 0 stops the cast, a negative value leaves max_t as it was (the leaf is ignored),
  // and any other value clips the segment to it (return t_hit to look for the closest hit,
  // max_t to see them all). Boxes are visited depth first, not nearest first.
  template <class Visit>
  void ray_cast(const Vec3& origin, const Vec3& direction, double max_t, Visit&& visit) const;

 private:
  // 64 bytes. A free node links the free list through `parent`; a leaf has child[0] ==
  // null_node and its payload in child[1].
  struct Node {
    Aabb box;
    std::int32_t parent = null_node;
    std::int32_t child[2] = {null_node, null_node};
    std::int32_t height = 0;  // 0 for a leaf, 1 + the higher child's otherwise, −1 when free
  };
  // Depth-first traversals keep at most height + 1 nodes pending, and the height never passes
  // height_limit(2³¹) = 68.
  static constexpr int stack_size = 128;

  bool is_leaf(std::int32_t node) const { return nodes_[node].child[0] == null_node; }
  std::int32_t allocate_node();
  void free_node(std::int32_t node);
  std::int32_t find_best_sibling(std::int32_t top, const Aabb& box) const;
  template <class Enter, class Leaf>
  bool descend(std::int32_t top, Enter&& enter, Leaf&& leaf) const;
  void insert_leaf(std::int32_t leaf);
  void remove_leaf(std::int32_t leaf);
  void attach(std::int32_t leaf, std::int32_t sibling, bool to_root);
  void refit(std::int32_t node);
  static bool same_box_and_height(const Node& a, const Node& b) {
    return a.height == b.height && a.box.lower == b.box.lower && a.box.upper == b.box.upper;
  }
  void rotate(std::int32_t node);
  void swap_with_grandchild(std::int32_t node, int slot_down, int slot_up);
  std::int32_t build(std::int32_t* leaves, std::int32_t count);
  std::string check_subtree(std::int32_t node, std::int32_t parent, std::int32_t& leaves) const;

  std::vector<Node> nodes_;
  std::int32_t root_ = null_node;
  std::int32_t free_list_ = null_node;
  std::int32_t leaf_count_ = 0;
  std::vector<std::int32_t> rebuild_leaves_;  // scratch of rebuild(), kept to reuse its memory
};

// Depth first below `top`: enters the nodes whose box passes `enter`, and calls leaf(index) for
// each leaf that passes, right after its own test; false (and no more calls) once leaf does.
template <class Enter, class Leaf>
bool DynamicTree::descend(std::int32_t top, Enter&& enter, Leaf&& leaf) const {
  std::int32_t stack[stack_size];
  int count = 0;
  stack[count++] = top;
  while (count > 0) {
    const std::int32_t index = stack[--count];
    const Node& node = nodes_[index];
    if (!enter(node.box)) continue;
    if (node.child[0] == null_node) {
      if (!leaf(index)) return false;
    } else {
      stack[count++] = node.child[0];
      stack[count++] = node.child[1];
    }
  }
  return true;
}

template <class Visit>
void DynamicTree::query(const Aabb& box, Visit&& visit) const {
  if (root_ == null_node) return;
  descend(root_, [&](const Aabb& b) { return b.overlaps(box); }, visit);
}

template <class Visit>
void DynamicTree::query_around(std::int32_t leaf, const Aabb& box, Visit&& visit) const {
  std::int32_t child = leaf;
  for (std::int32_t node = nodes_[leaf].parent; node != null_node;
       child = node, node = nodes_[node].parent) {
    const std::int32_t sibling =
        nodes_[node].child[0] == child ? nodes_[node].child[1] : nodes_[node].child[0];
    if (!descend(sibling, [&](const Aabb& b) { return b.overlaps(box); }, visit)) return;
  }
}

namespace tree_detail {
// Where the segment origin + t·direction enters box, for t in [0, max_t]; −1 when it misses.
// The slab test (Kay and Kajiya, "Ray Tracing Complex Scenes", SIGGRAPH 1986), with an axis
// the segment runs parallel to (direction 0) tested on the origin alone.
inline double segment_enters(const Aabb& box, const Vec3& origin, const Vec3& direction,
                             double max_t) {
  double t_in = 0.0, t_out = max_t;
  for (int i = 0; i < 3; ++i) {
    if (direction[i] == 0.0) {
      if (origin[i] < box.lower[i] || origin[i] > box.upper[i]) return -1.0;
      continue;
    }
    const double inverse = 1.0 / direction[i];
    double t1 = (box.lower[i] - origin[i]) * inverse, t2 = (box.upper[i] - origin[i]) * inverse;
    if (t1 > t2) std::swap(t1, t2);
    t_in = std::max(t_in, t1);
    t_out = std::min(t_out, t2);
    if (!(t_in <= t_out)) return -1.0;
  }
  return t_in;
}
}  // namespace tree_detail

template <class Visit>
void DynamicTree::ray_cast(const Vec3& origin, const Vec3& direction, double max_t,
                           Visit&& visit) const {
  if (root_ == null_node || !(max_t >= 0.0)) return;
  double t = 0.0;  // where the segment enters the box tested last
  auto enter = [&](const Aabb& b) {
    t = tree_detail::segment_enters(b, origin, direction, max_t);
    return t >= 0.0;
  };
  descend(root_, enter, [&](std::int32_t leaf) {
    const double clip = visit(leaf, t);
    if (clip > 0.0) max_t = std::min(max_t, clip);
    return clip != 0.0;
  });
}

}  // namespace rigidlab
