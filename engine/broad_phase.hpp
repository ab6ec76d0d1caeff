// The broad phase: which pairs of shapes may touch in this step, found in time linear in the
// number of bodies (issue 13, item 5), for the narrow phase to test exactly.
//
// How to use it (the world's step, or a tool):
//   BroadPhase bp;                                   // or BroadPhase(settings)
//   ProxyId p = bp.create_proxy(box, key, kind, d);  // when a body (or shape) is added
//   bp.move_proxy(p, box, d);                        // every step, for every body that can move
//   bp.destroy_proxy(p);                             // when it is removed
//   bp.update_pairs();                               // once per step, after the moves
//   for (const BroadPhasePair& pair : bp.pairs()) narrow_phase(pair.key_a, pair.key_b);
// - `box` is the body's tight box for the step: its bounding box over the whole step, grown by
//   whatever contact distance the caller uses (speculative distance) and by how far it can move
//   in the step (the sweep: the box at the start united with the box at the end, or the start
//   box grown by the speed bound times Δt). The broad phase adds its own margin on top.
// - `d` is the displacement of the step (m, world, velocity · Δt): the fat box is stretched
//   along it by settings.displacement_multiplier, so a body moving steadily leaves its fat box
//   less often (Box2D v2.4's b2_aabbMultiplier). Zero when unknown.
// - `key` is the caller's name for the proxy, unique among live proxies: the body's stable id
//   (slot and generation) packed as std::uint64_t(slot) << 32 | generation, so that keys sort
//   by slot, then generation; or body and shape. Pairs are reported with their keys and sorted by them, so the order
//   depends only on the keys, never on the history of the tree: the world's determinism hash
//   may depend on it.
// - `kind`: moving proxies pair with every other proxy, fixed ones (static bodies, and kinematic
//   ones that are moved by hand) only with moving ones. They live in two trees (as Box2D's
//   trees per body type), so a world with much static geometry keeps the moving tree small.
//
// What it keeps (Box2D v3's broad_phase.c, with the fattened boxes of Box2D v2.4 and of
// Bullet's btDbvtBroadphase):
// - Each proxy has a fat box: the tight box grown by the margin on every side (settings.margin,
//   at most settings.margin_fraction of the box's longest side, so that small bodies in a heap
//   do not each pair with every body a whole margin away) and stretched along d. move_proxy
//   changes nothing while the tight box stays inside the fat box (the common case: a resting or
//   slow body), so the tree is untouched. When the tight box leaves it, or when the fat box has
//   grown far larger than needed (a fast body that stopped: larger than the tight box grown by
//   4 margins and 4 stretches on every side, as b2DynamicTree::MoveProxy of Box2D v2.4), the
//   proxy gets a new fat box, is re-inserted near its old place in its tree, and looks for new
//   partners there and then (while that part of the tree is in cache).
// - The pair set is persistent: after update_pairs(), pairs() is the set of pairs whose fat
//   boxes overlap (both of them moving, or one moving and one fixed), and so holds every pair
//   whose tight boxes overlap. update_pairs() brings it up to date from the proxies created or
//   re-inserted since the last call alone (Box2D's move buffer): their new partners join, and the
//   pairs that involve one of them or a destroyed proxy leave when their fat boxes no longer
//   overlap. added() and removed() say what changed (for contact begin and end events).
// - Cost per step: O(n) cheap containment tests, O(m log n) for the m proxies re-inserted (in
//   practice the local re-insertion is nearly O(m)), O(P) for the P pairs; no heap allocation
//   once the buffers have grown (reserve() grows them up front).
// - The trees hold fat boxes; query() and ray_cast() filter by the tight boxes, so a tool sees
//   the boxes as last given.
//
// Why trees and not a uniform grid (bench/broad_phase_bench.cpp measures both, with today's
// sweep and prune, on the same boxes): the trees with persistent pairs cost less than a grid
// rebuilt every step at 1k, 10k and 100k scattered bodies and in a settling heap, touch only
// the bodies that left their fat boxes, and need no cell size: bodies of any size mix (a static
// ground box, a heap of pebbles) where a grid's cell suits one size only.
//
// Bad input (a box that is not finite or has lower > upper, a non-finite displacement, an id
// that is not a live proxy) throws std::invalid_argument and changes nothing.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/dynamic_tree.hpp"

namespace rigidlab {

using ProxyId = std::int32_t;
constexpr ProxyId null_proxy = -1;

enum class ProxyKind : std::uint8_t { moving, fixed };

// Two proxies whose fat boxes overlap: key_a < key_b (the caller's keys), with their proxy ids.
struct BroadPhasePair {
  std::uint64_t key_a = 0, key_b = 0;
  ProxyId proxy_a = null_proxy, proxy_b = null_proxy;
};
inline bool operator<(const BroadPhasePair& p, const BroadPhasePair& q) {
  return p.key_a < q.key_a || (p.key_a == q.key_a && p.key_b < q.key_b);
}
inline bool operator==(const BroadPhasePair& p, const BroadPhasePair& q) {
  return p.key_a == q.key_a && p.key_b == q.key_b;
}

struct BroadPhaseSettings {
  double margin = 0.1;           // m, added on every side of the tight box (Box2D: 0.1 m) ...
  double margin_fraction = 0.1;  // ... but at most this fraction of the box's longest side
  double displacement_multiplier = 4.0;  // how many steps of displacement the fat box looks
                                         // ahead (Box2D v2.4's b2_aabbMultiplier: 4)
};

class BroadPhase {
 public:
  // std::invalid_argument unless every setting is finite and ≥ 0.
  explicit BroadPhase(const BroadPhaseSettings& settings = {});

  const BroadPhaseSettings& settings() const { return settings_; }

  ProxyId create_proxy(const Aabb& box, std::uint64_t key, ProxyKind kind = ProxyKind::moving,
                       const Vec3& displacement = Vec3::Zero());
  // True when the proxy got a new fat box (and will be looked at by the next update_pairs).
  bool move_proxy(ProxyId id, const Aabb& box, const Vec3& displacement = Vec3::Zero());
  // The proxy leaves the trees at once (queries no longer see it) and its pairs at the next
  // update_pairs; its id is reused only after that.
  void destroy_proxy(ProxyId id);
  // Brings pairs(), added() and removed() up to date with the creations, moves and destructions
  // since the last call.
  void update_pairs();

  // Sorted by (key_a, key_b); each pair once.
  const std::vector<BroadPhasePair>& pairs() const { return pairs_; }
  const std::vector<BroadPhasePair>& added() const { return added_; }      // sorted
  const std::vector<BroadPhasePair>& removed() const { return removed_; }  // sorted

  // Calls visit(id, key) for every live proxy whose tight box (as last given) overlaps box;
  // visit returns false to stop. Fixed proxies first, then moving ones.
  template <class Visit>
  void query(const Aabb& box, Visit&& visit) const;
  // Casts the segment origin + t·direction, 0 ≤ t ≤ max_t, through the live proxies' tight
  // boxes: calls visit(id, key, t_enter), whose result clips the segment as in
  // DynamicTree::ray_cast (0 stops, < 0 ignores the proxy, else the new max_t).
  template <class Visit>
  void ray_cast(const Vec3& origin, const Vec3& direction, double max_t, Visit&& visit) const;

  bool contains(ProxyId id) const {
    return id >= 0 && static_cast<std::size_t>(id) < proxies_.size() && proxies_[id].live();
  }
  // Of a live proxy (unchecked: see contains()).
  const Aabb& box(ProxyId id) const { return proxies_[id].box; }
  const Aabb& fat_box(ProxyId id) const { return tree(proxies_[id].kind).box(proxies_[id].leaf); }
  std::uint64_t key(ProxyId id) const { return proxies_[id].key; }
  ProxyKind kind(ProxyId id) const { return proxies_[id].kind; }

  std::int32_t proxy_count() const { return moving_.leaf_count() + fixed_.leaf_count(); }
  const DynamicTree& tree(ProxyKind kind) const {
    return kind == ProxyKind::moving ? moving_ : fixed_;
  }
  // Rebuilds both trees by median splits (after loading a scene, say); pairs do not change.
  void rebuild();
  // Grows every buffer for this many proxies and pairs, so reaching them allocates nothing.
  void reserve(std::int32_t proxies, std::size_t pairs);
  // Destroys every proxy and forgets every pair at once (a world emptied); ids start again from
  // 0, and the memory is kept for reuse.
  void clear();
  // Empty when the trees and the pair set are consistent (every live proxy's tight box inside
  // its fat box, pairs sorted, unique and overlapping, no pair of two fixed proxies), else what
  // is wrong. Linear in the pairs; for tests.
  std::string check() const;

 private:
  struct Proxy {
    Aabb box;                           // tight box, as last given
    std::uint64_t key = 0;
    std::int32_t leaf = DynamicTree::null_node;  // in tree(kind); null_node once destroyed
    ProxyKind kind = ProxyKind::moving;
    bool moved = false;      // in move_buffer_
    bool destroyed = false;  // waiting for update_pairs to drop its pairs and free its id
    bool fresh = false;      // created since the last update_pairs: in no pair yet
    bool live() const { return leaf != DynamicTree::null_node; }
  };

  DynamicTree& tree_for(ProxyKind kind) { return kind == ProxyKind::moving ? moving_ : fixed_; }
  double margin_of(const Aabb& box) const;
  Aabb fatten(const Aabb& box, const Vec3& displacement) const;
  bool fat_enough(const Aabb& fat, const Aabb& box, const Vec3& displacement) const;
  void buffer_move(ProxyId id);
  void check_proxy(ProxyId id, const char* function) const;
  void find_new_pairs(ProxyId id);
  const Aabb& paired_box(ProxyId id) const {
    return proxies_[id].moved ? paired_boxes_[id] : fat_box(id);
  }
  bool has_pair(const BroadPhasePair& pair) const;
  void drop_stale_pairs();
  void sift_candidates();

  BroadPhaseSettings settings_;
  DynamicTree moving_, fixed_;
  std::vector<Proxy> proxies_;
  std::vector<ProxyId> free_ids_;        // reused last in, first out
  std::vector<ProxyId> move_buffer_;     // created or re-fattened since the last update
  std::vector<ProxyId> pending_free_;    // destroyed since the last update
  std::vector<BroadPhasePair> pairs_, added_, removed_, merged_;
  std::vector<BroadPhasePair> candidates_;  // found by create and move since the last update
  // By proxy id, of a proxy that moved since the last update_pairs: its fat box at that update
  // (paired_box). pairs_ is exactly the set of pairs whose fat boxes overlapped then (not both
  // fixed), so whether a pair is in it is whether those boxes overlap (has_pair): no search
  // of the pair set, whose cache misses grew with the heap (42 k pairs, 1.35 MB, at 4,096
  // settling spheres), as Box2D v2.4's move buffer decides which pairs are new.
  std::vector<Aabb> paired_boxes_;
};

template <class Visit>
void BroadPhase::query(const Aabb& box, Visit&& visit) const {
  bool go_on = true;
  for (const DynamicTree* t : {&fixed_, &moving_}) {
    t->query(box, [&](std::int32_t leaf) {
      const ProxyId id = t->payload(leaf);
      if (proxies_[id].box.overlaps(box)) go_on = visit(id, proxies_[id].key);
      return go_on;
    });
    if (!go_on) return;
  }
}

template <class Visit>
void BroadPhase::ray_cast(const Vec3& origin, const Vec3& direction, double max_t,
                          Visit&& visit) const {
  for (const DynamicTree* t : {&fixed_, &moving_}) {
    bool stopped = false;
    t->ray_cast(origin, direction, max_t, [&](std::int32_t leaf, double) {
      const ProxyId id = t->payload(leaf);
      const double t_enter = tree_detail::segment_enters(proxies_[id].box, origin, direction, max_t);
      if (t_enter < 0.0) return -1.0;
      const double clip = visit(id, proxies_[id].key, t_enter);
      if (clip == 0.0) stopped = true;
      else if (clip > 0.0) max_t = std::min(max_t, clip);
      return clip;
    });
    if (stopped) return;
  }
}

}  // namespace rigidlab
