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
  const Vec3 limit = Vec3::Constant(max_coordinate);
  return {(b.position - extent).cwiseMax(-limit).cwiseMin(limit),
          (b.position + extent).cwiseMax(-limit).cwiseMin(limit)};
}

}  // namespace

void ContactPairs::update(const std::vector<Body>& bodies, const std::vector<BodyId>& ids,
                          const SolverBody* solver, double h, double speculative_distance) {
  ++update_count_;
  radius_.assign(bodies.size(), 0.0);
  sweep_.assign(bodies.size(), 0.0);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    if (b.shape.kind == ShapeKind::none) continue;
    radius_[i] = bounding_radius(b.shape);
    const double speed = solver[i].velocity.norm() + solver[i].angular_velocity.norm() * radius_[i];
    // Capped so that absurd speeds (1e300 m/s) cannot make the boxes overflow to infinity.
    sweep_[i] = std::min(speed * h, contact_detail::max_sweep);
    Vec3 displacement = h * solver[i].velocity;
    if (!displacement.allFinite() || displacement.norm() > contact_detail::max_sweep)
      displacement.setZero();
    const ProxyKind kind = is_static(b) ? ProxyKind::fixed : ProxyKind::moving;
    sync_body(i, ids[i], tight_box(b, sweep_[i] + 0.5 * speculative_distance), displacement,
              kind);
  }
  drop_unseen();
  broad_phase_.update_pairs();
  pairs_.clear();
  for (const BroadPhasePair& p : broad_phase_.pairs()) {
    const SlotProxy& a = slots_[p.key_a >> 32];
    const SlotProxy& b = slots_[p.key_b >> 32];
    pairs_.push_back({a.index, b.index});
  }
}

// The body's proxy: moved when it has one of the same generation and kind, else (a new body,
// or a slot reused by another) made anew.
void ContactPairs::sync_body(std::size_t i, BodyId id, const Aabb& box, const Vec3& displacement,
                             ProxyKind kind) {
  if (id.slot >= slots_.size()) slots_.resize(id.slot + 1);
  SlotProxy& s = slots_[id.slot];
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
