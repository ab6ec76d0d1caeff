// Which bodies of a world may touch in a step: the bodies with a shape kept as proxies of the
// broad phase (engine/broad_phase.hpp, a dynamic AABB tree with fattened boxes and persistent
// pairs) under their stable ids, brought up to date once per substep, and the candidate pairs
// it reports, for the narrow phase (engine/contact_finder.cpp) to test exactly.
//
// - Each proxy's key is the body's BodyId (slot, then generation): the pairs come sorted by
//   the ids of their bodies, so the order in which contacts are found (and solved) depends only
//   on the ids, never on where the bodies are or on the tree's history: a world stepped from a
//   saved state repeats itself bit for bit, and the determinism hash holds run to run.
// - The tight box of a body for the step: its shape's bounding box at its pose (a box's by its
//   rotated extents, a sphere's centre ± r), grown on every side by how far its points can move
//   in the step (sweep = (|u| + |ω| R) h, R the bounding radius, u and ω the velocities the
//   integrator's velocity stage gave the positions; capped, so absurd speeds stay finite) and by
//   half the speculative distance. Two bodies whose points can come within the speculative
//   distance in the step have overlapping tight boxes, so every pair the narrow phase would find
//   is reported (the pair set is a superset: the narrow phase decides).
// - A box that turns fast (its turning alone would carry its rotated box out of the fat box's
//   margin within 4 steps) is bounded instead by its sphere: the centre ± (R + sweep + half the
//   speculative distance), which holds the rotated box and which turning does not change. A
//   spinning box then keeps its fat box until it has moved, where its rotated box would leave
//   the fat box every few steps and be re-inserted into the tree (at 100k scattered boxes that
//   re-insertion, cache misses on the tree's nodes, was the largest cost that grew with n).
//   The pairs found by the narrow phase are the same (the boxes only grow), so is the order.
// - Static bodies (inverse mass 0, also those moved by hand) are fixed proxies: they pair only
//   with moving bodies, never with each other.
// - A body that left the world (or lost its shape, or changed between static and moving) loses
//   its proxy at the next update: each update marks the slots it saw and drops the others, in
//   one pass over the slots. Nothing is allocated once the buffers have grown.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/body.hpp"
#include "engine/body_store.hpp"
#include "engine/broad_phase.hpp"
#include "engine/constraint_row.hpp"

namespace rigidlab {

// A candidate pair of bodies, by their indices in the world's body vector: a's id < b's id.
struct BodyPair {
  std::size_t a, b;
};

class ContactPairs {
 public:
  // Brings the proxies up to date with the bodies (slot i of `solver` holds body i's velocities
  // for the step of length h) and finds the candidate pairs.
  void update(const std::vector<Body>& bodies, const std::vector<BodyId>& ids,
              const SolverBody* solver, double h, double speculative_distance);
  // Pairs of bodies that never collide (joined by a joint that says so), by their proxy keys
  // (key_of), each as (smaller, larger), sorted: update skips them in one merge with the broad
  // phase's sorted pairs. Set again only when the joints change.
  std::vector<std::pair<std::uint64_t, std::uint64_t>>& excluded() { return excluded_; }
  // Sorted by (id of a, id of b); each pair once, never two static bodies.
  const std::vector<BodyPair>& pairs() const { return pairs_; }
  // Of body i in the last update (0 for a body without a shape): its bounding radius and how
  // far its points can move in the step (m).
  double radius(std::size_t i) const { return reach_[i].radius; }
  double sweep(std::size_t i) const { return reach_[i].sweep; }
  const BroadPhase& broad_phase() const { return broad_phase_; }

  // The key of a body's proxy: its slot, then its generation.
  static std::uint64_t key_of(BodyId id) {
    return std::uint64_t{id.slot} << 32 | std::uint64_t{id.generation};
  }

 private:
  struct SlotProxy {
    ProxyId proxy = null_proxy;
    std::uint32_t generation = 0;
    std::uint32_t index = 0;  // of the body in the last update
    std::uint64_t seen = 0;   // the last update that saw it
    ProxyKind kind = ProxyKind::moving;
    bool turning = false;     // its box is its bounding sphere's (see update)
  };
  struct Reach {
    double radius = 0.0, sweep = 0.0;
  };
  // How many steps a box's turning must keep its rotated box inside the fat box's margin.
  static constexpr double turning_steps = 4.0;
  SlotProxy& slot_of(BodyId id);
  void sync_body(SlotProxy& s, std::size_t i, BodyId id, const Aabb& box,
                 const Vec3& displacement, ProxyKind kind);
  void drop_unseen();

  BroadPhase broad_phase_;
  std::vector<SlotProxy> slots_;  // by BodyId slot
  std::vector<Reach> reach_;  // by body index
  std::vector<BodyPair> pairs_;
  std::uint64_t update_count_ = 0;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> excluded_;
};

}  // namespace rigidlab
