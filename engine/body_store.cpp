#include "engine/body_store.hpp"

namespace rigidlab {

BodyStore::Id BodyStore::insert(const Body& b) {
  std::uint32_t slot;
  if (!free_slots_.empty()) {
    slot = free_slots_.back();
    free_slots_.pop_back();
  } else {
    slot = static_cast<std::uint32_t>(slots_.size());
    slots_.push_back(Slot{});
  }
  bodies_.push_back(b);
  slots_[slot].index = static_cast<std::uint32_t>(bodies_.size() - 1);
  const Id id{slot, slots_[slot].generation};
  ids_.push_back(id);
  return id;
}

Body BodyStore::erase(Id id) {
  const std::size_t index = slots_[id.slot].index;
  Body b = bodies_[index];
  bodies_.erase(bodies_.begin() + static_cast<std::ptrdiff_t>(index));
  ids_.erase(ids_.begin() + static_cast<std::ptrdiff_t>(index));
  for (std::size_t i = index; i < ids_.size(); ++i)
    slots_[ids_[i].slot].index = static_cast<std::uint32_t>(i);
  slots_[id.slot].index = npos;
  ++slots_[id.slot].generation;  // an id kept past the removal is now stale
  free_slots_.push_back(id.slot);
  return b;
}

}  // namespace rigidlab
