// The bodies of a world and their stable ids.
//
// Bodies live in one contiguous std::vector<Body>, in the order they were added (the step loops
// run over it, and the Lua side lists w:bodies() in that order). Removing a body keeps the
// order of the others, so their vector indices above it drop by one; everything that must
// keep pointing at a body (springs, drags, cached contacts, joints, the Lua body objects)
// holds its BodyId instead, and the world resolves ids to indices once per step.
//
// A BodyId is a slot and a generation, in the manner of Box2D v3's b2BodyId: the slot of a
// removed body is reused by a later one with the next generation, so an id kept past the
// removal of its body is recognised as stale (contains() is false) instead of silently
// naming the newcomer.
//
// The store is held by shared_ptr so handles to bodies (the Lua body objects) can keep it
// alive after the world is gone: such bodies stay readable, and store.world() is then nullptr.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/body.hpp"

namespace rigidlab {

class World;

struct BodyId {
  static constexpr std::uint32_t no_slot = 0xffffffffu;
  std::uint32_t slot = no_slot;
  std::uint32_t generation = 0;

  bool valid() const { return slot != no_slot; }
  friend bool operator==(BodyId x, BodyId y) {
    return x.slot == y.slot && x.generation == y.generation;
  }
  friend bool operator!=(BodyId x, BodyId y) { return !(x == y); }
  // An order for sorting (by slot, then generation); the invalid id comes last.
  friend bool operator<(BodyId x, BodyId y) {
    return x.slot != y.slot ? x.slot < y.slot : x.generation < y.generation;
  }
};

// An index that names no body (a spring's anchor end, a joint's world side, once resolved).
inline constexpr std::size_t no_body = static_cast<std::size_t>(-1);

// The id that names no body (a spring's world anchor, a contact's plane side).
inline constexpr BodyId no_body_id{};

class BodyStore {
 public:
  using Id = BodyId;

  Id insert(const Body& b);
  // Removes the body (which must be contained) and returns it; the others keep their ids.
  Body erase(Id id);
  bool contains(Id id) const {
    return id.slot < slots_.size() && slots_[id.slot].generation == id.generation &&
           slots_[id.slot].index != npos;
  }
  // The body of a contained id, and its index in bodies().
  Body& get(Id id) { return bodies_[slots_[id.slot].index]; }
  const Body& get(Id id) const { return bodies_[slots_[id.slot].index]; }
  std::size_t index_of(Id id) const { return slots_[id.slot].index; }
  Id id_at(std::size_t index) const { return ids_[index]; }
  std::size_t size() const { return bodies_.size(); }
  std::vector<Body>& bodies() { return bodies_; }
  const std::vector<Body>& bodies() const { return bodies_; }
  const std::vector<Id>& ids() const { return ids_; }  // by index

  // The world this store belongs to: nullptr for a store made for a lone body, and after the
  // world has been destroyed.
  World* world() const { return world_; }
  // True during World::step: only forces may then be applied to the bodies (see World::step).
  bool stepping() const { return stepping_; }

 private:
  friend class World;
  static constexpr std::uint32_t npos = 0xffffffffu;
  struct Slot {
    std::uint32_t index = npos;   // in bodies_; npos when free
    std::uint32_t generation = 0;
  };
  std::vector<Body> bodies_;
  std::vector<Id> ids_;        // by index
  std::vector<Slot> slots_;    // by id slot
  std::vector<std::uint32_t> free_slots_;
  World* world_ = nullptr;
  bool stepping_ = false;
};

}  // namespace rigidlab
