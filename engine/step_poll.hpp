// A stop check for the long loops of a step: World::step counts the work it does (bodies
// integrated, contact points solved) and calls the embedding program's callback about every
// `interval` units, well under a millisecond of work, so a step of any size can be stopped
// (Ctrl-C, a time limit) between two substeps or two sweeps of the contact solver. The
// callback stops the step by throwing; World::step then undoes it (engine/world.hpp).
#pragma once

#include <cstddef>
#include <functional>

namespace rigidlab {

class StepPoll {
 public:
  // Units of work between two calls: a body integrated or a contact point solved is one unit,
  // tens of nanoseconds each.
  static constexpr std::size_t interval = 4096;

  StepPoll() = default;
  explicit StepPoll(const std::function<void()>& callback) : callback_(&callback) {
    if (!*callback_) callback_ = nullptr;
  }

  // Counts `work` units; calls the callback (which may throw) when `interval` have passed.
  void tick(std::size_t work) {
    if (callback_ == nullptr) return;
    since_call_ += work;
    if (since_call_ < interval) return;
    since_call_ = 0;
    (*callback_)();
  }

 private:
  const std::function<void()>* callback_ = nullptr;
  std::size_t since_call_ = 0;
};

}  // namespace rigidlab
