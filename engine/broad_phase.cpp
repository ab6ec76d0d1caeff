// The broad phase: fat boxes, the move buffer and the persistent, sorted pair set. See
// engine/broad_phase.hpp.
#include "engine/broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/format.hpp"

namespace rigidlab {

namespace {

std::string vector_text(const Vec3& v) {
  return "(" + format_number(v.x()) + ", " + format_number(v.y()) + ", " + format_number(v.z()) +
         ")";
}

void check_box(const Aabb& box, const char* function) {
  if (!box.valid())
    throw std::invalid_argument(std::string("BroadPhase::") + function +
                                ": the box must be finite with lower <= upper, got lower " +
                                vector_text(box.lower) + ", upper " + vector_text(box.upper));
}

void check_displacement(const Vec3& displacement, const char* function) {
  if (!displacement.allFinite())
    throw std::invalid_argument(std::string("BroadPhase::") + function +
                                ": the displacement must be finite, got " +
                                vector_text(displacement));
}

}  // namespace

BroadPhase::BroadPhase(const BroadPhaseSettings& settings) : settings_(settings) {
  if (!(std::isfinite(settings.margin) && settings.margin >= 0.0))
    throw std::invalid_argument("BroadPhase: margin must be finite and >= 0, got " +
                                format_number(settings.margin));
  if (!(std::isfinite(settings.margin_fraction) && settings.margin_fraction >= 0.0))
    throw std::invalid_argument("BroadPhase: margin_fraction must be finite and >= 0, got " +
                                format_number(settings.margin_fraction));
  if (!(std::isfinite(settings.displacement_multiplier) &&
        settings.displacement_multiplier >= 0.0))
    throw std::invalid_argument(
        "BroadPhase: displacement_multiplier must be finite and >= 0, got " +
        format_number(settings.displacement_multiplier));
}

// The margin of a tight box (m): settings.margin, but at most margin_fraction of its longest
// side, so that small bodies in a heap do not each pair with every body a whole margin away.
double BroadPhase::margin_of(const Aabb& box) const {
  return std::min(settings_.margin, settings_.margin_fraction * (box.upper - box.lower).maxCoeff());
}

// The tight box grown by the margin on every side and stretched along the displacement (Box2D
// v2.4, b2DynamicTree::MoveProxy: the fat box looks `multiplier` steps ahead).
Aabb BroadPhase::fatten(const Aabb& box, const Vec3& displacement) const {
  const Vec3 margin = Vec3::Constant(margin_of(box));
  Aabb fat{box.lower - margin, box.upper + margin};
  const Vec3 stretch = settings_.displacement_multiplier * displacement;
  for (int i = 0; i < 3; ++i) (stretch[i] < 0.0 ? fat.lower[i] : fat.upper[i]) += stretch[i];
  if (!fat.valid())
    throw std::invalid_argument("BroadPhase: the fat box of lower " + vector_text(box.lower) +
                                ", upper " + vector_text(box.upper) + ", displacement " +
                                vector_text(displacement) + " is not finite");
  return fat;
}

// The fat box still serves: it holds the tight box and is no larger than the tight box grown by
// 4 margins and 4 stretches on every side (a fast body that slowed down gets a smaller one).
bool BroadPhase::fat_enough(const Aabb& fat, const Aabb& box, const Vec3& displacement) const {
  if (!fat.contains(box)) return false;
  const Vec3 reach = 4.0 * (Vec3::Constant(margin_of(box)) +
                            settings_.displacement_multiplier * displacement.cwiseAbs());
  return Aabb{box.lower - reach, box.upper + reach}.contains(fat);
}

void BroadPhase::check_proxy(ProxyId id, const char* function) const {
  if (!contains(id))
    throw std::invalid_argument(std::string("BroadPhase::") + function + ": " +
                                std::to_string(id) + " is not a live proxy");
}

void BroadPhase::buffer_move(ProxyId id) {
  Proxy& p = proxies_[id];
  if (p.moved) return;
  if (!p.fresh) paired_boxes_[id] = fat_box(id);  // before its tree moves it
  p.moved = true;
  move_buffer_.push_back(id);  // never allocates: reserved for every proxy (create_proxy)
}

ProxyId BroadPhase::create_proxy(const Aabb& box, std::uint64_t key, ProxyKind kind,
                                 const Vec3& displacement) {
  check_box(box, "create_proxy");
  check_displacement(displacement, "create_proxy");
  const Aabb fat = fatten(box, displacement);
  if (free_ids_.empty()) {
    // Every id list holds each proxy at most once: room for all of them now means none of
    // their push_backs allocates later. The new slot goes on the free list, so that a failed
    // insertion below leaves it there.
    proxies_.emplace_back();
    paired_boxes_.emplace_back();
    const std::size_t room = proxies_.capacity();
    for (std::vector<ProxyId>* ids : {&free_ids_, &move_buffer_, &pending_free_})
      if (ids->capacity() < room) ids->reserve(room);
    free_ids_.push_back(static_cast<ProxyId>(proxies_.size() - 1));
  }
  const ProxyId id = free_ids_.back();
  const std::int32_t leaf = tree_for(kind).insert(fat, id);
  free_ids_.pop_back();
  Proxy& p = proxies_[id];
  p = Proxy{};
  p.box = box;
  p.key = key;
  p.kind = kind;
  p.leaf = leaf;
  p.fresh = true;
  buffer_move(id);
  find_new_pairs(id);
  return id;
}

bool BroadPhase::move_proxy(ProxyId id, const Aabb& box, const Vec3& displacement) {
  check_proxy(id, "move_proxy");
  check_box(box, "move_proxy");
  check_displacement(displacement, "move_proxy");
  Proxy& p = proxies_[id];
  if (fat_enough(fat_box(id), box, displacement)) {
    p.box = box;
    return false;
  }
  const Aabb fat = fatten(box, displacement);
  p.box = box;
  buffer_move(id);
  tree_for(p.kind).move(p.leaf, fat);
  find_new_pairs(id);
  return true;
}

void BroadPhase::destroy_proxy(ProxyId id) {
  check_proxy(id, "destroy_proxy");
  Proxy& p = proxies_[id];
  tree_for(p.kind).remove(p.leaf);
  p.leaf = DynamicTree::null_node;
  p.destroyed = true;
  pending_free_.push_back(id);
}

// Whether the pair was in pairs_ at the last update: both proxies were there (a key destroyed
// and given to a new proxy since names a new pair) and their fat boxes then overlapped (see
// paired_boxes_). Never two fixed proxies: find_new_pairs does not look for those.
bool BroadPhase::has_pair(const BroadPhasePair& pair) const {
  if (proxies_[pair.proxy_a].fresh || proxies_[pair.proxy_b].fresh) return false;
  return paired_box(pair.proxy_a).overlaps(paired_box(pair.proxy_b));
}

// The pairs of a proxy that has just been created or given a new fat box and that are not in the
// set: the proxies whose fat boxes overlap its new one. Searched at once, while the path of its
// leaf is in cache: its own tree outward from the leaf, the other tree from the root (a fixed
// proxy searches the moving tree only). Of two proxies that move in the same step, the later
// one to move sees the other's final fat box, so no pair is missed; what an earlier search
// found may have parted since, or be found twice: update_pairs keeps the candidates whose final
// fat boxes overlap, once each. (Box2D queries its move buffer in b2UpdateBroadPhasePairs
// instead, after all the moves, from the root.)
void BroadPhase::find_new_pairs(ProxyId id) {
  const Proxy& p = proxies_[id];
  const Aabb fat = fat_box(id);
  auto consider = [&](ProxyId other) {
    const Proxy& q = proxies_[other];
    const BroadPhasePair pair = p.key < q.key ? BroadPhasePair{p.key, q.key, id, other}
                                              : BroadPhasePair{q.key, p.key, other, id};
    if (!has_pair(pair)) candidates_.push_back(pair);
    return true;
  };
  auto in_moving = [&](std::int32_t leaf) { return consider(moving_.payload(leaf)); };
  if (p.kind == ProxyKind::moving) {
    moving_.query_around(p.leaf, fat, in_moving);
    fixed_.query(fat, [&](std::int32_t leaf) { return consider(fixed_.payload(leaf)); });
  } else {
    moving_.query(fat, in_moving);
  }
}

// Drops the pairs with a destroyed proxy, and those with a moved proxy whose fat boxes no longer
// overlap (the others' fat boxes have not changed, so they still overlap). Keeps the order.
void BroadPhase::drop_stale_pairs() {
  std::size_t kept = 0;
  for (const BroadPhasePair& pair : pairs_) {
    const Proxy& a = proxies_[pair.proxy_a];
    const Proxy& b = proxies_[pair.proxy_b];
    const bool stale = a.destroyed || b.destroyed ||
                       ((a.moved || b.moved) && !fat_box(pair.proxy_a).overlaps(fat_box(pair.proxy_b)));
    if (stale) removed_.push_back(pair);
    else pairs_[kept++] = pair;
  }
  pairs_.resize(kept);
}

// The candidates whose proxies are live and whose final fat boxes overlap, sorted, once each.
void BroadPhase::sift_candidates() {
  for (const BroadPhasePair& pair : candidates_) {
    if (proxies_[pair.proxy_a].destroyed || proxies_[pair.proxy_b].destroyed) continue;
    if (fat_box(pair.proxy_a).overlaps(fat_box(pair.proxy_b))) added_.push_back(pair);
  }
  candidates_.clear();
  std::sort(added_.begin(), added_.end());
  added_.erase(std::unique(added_.begin(), added_.end()), added_.end());
}

void BroadPhase::update_pairs() {
  added_.clear();
  removed_.clear();
  if (move_buffer_.empty() && pending_free_.empty()) return;
  drop_stale_pairs();
  sift_candidates();
  if (!added_.empty()) {
    merged_.resize(pairs_.size() + added_.size());
    std::merge(pairs_.begin(), pairs_.end(), added_.begin(), added_.end(), merged_.begin());
    pairs_.swap(merged_);
  }
  for (const ProxyId id : move_buffer_) proxies_[id].moved = proxies_[id].fresh = false;
  move_buffer_.clear();
  for (const ProxyId id : pending_free_) {
    proxies_[id] = Proxy{};
    free_ids_.push_back(id);
  }
  pending_free_.clear();
}

void BroadPhase::clear() {
  moving_.clear();
  fixed_.clear();
  proxies_.clear();
  paired_boxes_.clear();
  for (std::vector<ProxyId>* ids : {&free_ids_, &move_buffer_, &pending_free_}) ids->clear();
  for (std::vector<BroadPhasePair>* list : {&pairs_, &added_, &removed_, &merged_, &candidates_})
    list->clear();
}

void BroadPhase::rebuild() {
  moving_.rebuild();
  fixed_.rebuild();
}

void BroadPhase::reserve(std::int32_t proxies, std::size_t pairs) {
  if (proxies > 0) {
    const auto n = static_cast<std::size_t>(proxies);
    proxies_.reserve(n);
    paired_boxes_.reserve(n);
    for (std::vector<ProxyId>* ids : {&free_ids_, &move_buffer_, &pending_free_})
      ids->reserve(std::max(n, proxies_.capacity()));
    moving_.reserve(proxies);
    fixed_.reserve(proxies);
  }
  for (std::vector<BroadPhasePair>* list : {&pairs_, &added_, &removed_, &merged_, &candidates_})
    list->reserve(pairs);
}

std::string BroadPhase::check() const {
  for (const DynamicTree* t : {&moving_, &fixed_}) {
    const std::string problem = t->check();
    if (!problem.empty()) return problem;
  }
  for (std::size_t i = 0; i < proxies_.size(); ++i) {
    const auto id = static_cast<ProxyId>(i);
    if (!contains(id)) continue;
    if (tree(kind(id)).payload(proxies_[i].leaf) != id)
      return "proxy " + std::to_string(id) + " is not in its leaf";
    if (!fat_box(id).contains(box(id)))
      return "proxy " + std::to_string(id) + ": the tight box sticks out of the fat box";
  }
  for (std::size_t i = 0; i < pairs_.size(); ++i) {
    const BroadPhasePair& pair = pairs_[i];
    const std::string at = "pair " + std::to_string(i);
    if (i > 0 && !(pairs_[i - 1] < pair)) return at + ": out of order or repeated";
    if (!contains(pair.proxy_a) || !contains(pair.proxy_b)) return at + ": proxy not live";
    if (key(pair.proxy_a) != pair.key_a || key(pair.proxy_b) != pair.key_b ||
        !(pair.key_a < pair.key_b))
      return at + ": keys wrong";
    if (kind(pair.proxy_a) == ProxyKind::fixed && kind(pair.proxy_b) == ProxyKind::fixed)
      return at + ": two fixed proxies";
    if (!fat_box(pair.proxy_a).overlaps(fat_box(pair.proxy_b)))
      return at + ": fat boxes apart";
  }
  return "";
}

}  // namespace rigidlab
