// The world's bodies in the broad phase: see engine/contact_pairs.hpp.
#include "engine/contact_pairs.hpp"

#include <algorithm>

#include "engine/contact_helpers.hpp"
#include "engine/narrow_phase.hpp"

namespace rigidlab {

namespace {

// m: boxes are clamped to this range so that the tree's areas (products of extents, summed up
// the tree) stay finite for bodies absurdly far out; pairs there are then over-reported, never
// missed, and the narrow phase decides.
constexpr double max_coordinate = 1e100;

Aabb clamped(const Vec3& centre, const Vec3& extent) {
  const Vec3 limit = Vec3::Constant(max_coordinate);
  return {(centre - extent).cwiseMax(-limit).cwiseMin(limit),
          (centre + extent).cwiseMax(-limit).cwiseMin(limit)};
}

// The shape's bounding box at the body's pose (a box's: the centre ± |R| h, Ericson,
// "Real-Time Collision Detection" 4.2.6), grown by `grow` on every side.
Aabb tight_box(const Body& b, double grow) {
  Vec3 extent = Vec3::Zero();
  switch (b.shape.kind) {
    case ShapeKind::sphere:
      extent.setConstant(b.shape.radius);
      break;
    case ShapeKind::box:
      extent = b.orientation.toRotationMatrix().cwiseAbs() * b.shape.half_extents;
      break;
    case ShapeKind::none:
      break;
  }
  extent.array() += grow;
  return clamped(b.position, extent);
}

}  // namespace

void ContactPairs::update(const std::vector<Body>& bodies, const std::vector<BodyId>& ids,
                          const SolverBody* solver, double h, double speculative_distance) {
  ++update_count_;
  reach_.resize(bodies.size());
  const BroadPhaseSettings& settings = broad_phase_.settings();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    Reach& r = reach_[i];
    if (b.shape.kind == ShapeKind::none) {
      r = Reach{};
      continue;
    }
    r.radius = bounding_radius(b.shape);
    const double spin = solver[i].angular_velocity.norm() * r.radius;
    // Capped so that absurd speeds (1e300 m/s) cannot make the boxes overflow to infinity.
    r.sweep = std::min((solver[i].velocity.norm() + spin) * h, contact_detail::max_sweep);
    const double turn = spin * h;  // m, how far its points move by turning in the step
    Vec3 displacement = h * solver[i].velocity;
    if (!displacement.allFinite() || displacement.norm() > contact_detail::max_sweep)
      displacement.setZero();
    const ProxyKind kind = is_static(b) ? ProxyKind::fixed : ProxyKind::moving;
    const double grow = r.sweep + 0.5 * speculative_distance;
    // A box turning fast enough to carry its rotated box out of the fat box's margin within
    // turning_steps steps gets the box of its bounding sphere instead, which its turning does
    // not change (it holds the rotated box: each |R| h component is at most |h|). On and off
    // at a factor 2 apart, so a body near the limit does not switch (and move) step by step.
    SlotProxy& slot = slot_of(ids[i]);
    const double margin =
        std::min(settings.margin, settings.margin_fraction * 2.0 * r.radius);
    if (b.shape.kind != ShapeKind::box) slot.turning = false;
    else if (turning_steps * turn > margin) slot.turning = true;
    else if (2.0 * turning_steps * turn < margin) slot.turning = false;
    const Aabb box = slot.turning ? clamped(b.position, Vec3::Constant(r.radius + grow))
                                  : tight_box(b, grow);
    sync_body(slot, i, ids[i], box, displacement, kind);
  }
  drop_unseen();
  broad_phase_.update_pairs();
  pairs_.clear();
  auto skip = excluded_.begin();
  for (const BroadPhasePair& p : broad_phase_.pairs()) {
    const std::pair<std::uint64_t, std::uint64_t> keys{p.key_a, p.key_b};
    while (skip != excluded_.end() && *skip < keys) ++skip;
    if (skip != excluded_.end() && *skip == keys) continue;
    const SlotProxy& a = slots_[p.key_a >> 32];
    const SlotProxy& b = slots_[p.key_b >> 32];
    pairs_.push_back({a.index, b.index});
  }
}

ContactPairs::SlotProxy& ContactPairs::slot_of(BodyId id) {
  if (id.slot >= slots_.size()) slots_.resize(id.slot + 1);
  SlotProxy& s = slots_[id.slot];
  // A slot reused by another body starts afresh.
  if (s.generation != id.generation) s.turning = false;
  return s;
}

// The body's proxy: moved when it has one of the same generation and kind, else (a new body,
// or a slot reused by another) made anew.
void ContactPairs::sync_body(SlotProxy& s, std::size_t i, BodyId id, const Aabb& box,
                             const Vec3& displacement, ProxyKind kind) {
  if (s.proxy != null_proxy && (s.generation != id.generation || s.kind != kind)) {
    broad_phase_.destroy_proxy(s.proxy);
    s.proxy = null_proxy;
  }
  if (s.proxy == null_proxy)
    s.proxy = broad_phase_.create_proxy(box, key_of(id), kind, displacement);
  else
    broad_phase_.move_proxy(s.proxy, box, displacement);
  s.generation = id.generation;
  s.kind = kind;
  s.index = static_cast<std::uint32_t>(i);
  s.seen = update_count_;
}

void ContactPairs::drop_unseen() {
  for (SlotProxy& s : slots_) {
    if (s.proxy == null_proxy || s.seen == update_count_) continue;
    broad_phase_.destroy_proxy(s.proxy);
    s.proxy = null_proxy;
  }
}

}  // namespace rigidlab
