// The history of a live view: a ring of the most recent saved states with a cursor, for
// stepping back (rewind) and forward again. The slots are allocated once, when the history is
// made (each a copy of a prototype state, so a state of the same size is later copied into a
// slot without allocating); saving a state then reuses the oldest slot.
//
// Like an editor's undo list: states after the cursor are the future seen before a rewind.
// The view steps forward from the cursor and either finds the step's result equal to the next
// saved state (advance) or records it as a new present, which drops that future (record).
// Generic over the state (the world's engine::WorldState, an articulation's), no engine here.
#pragma once

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace rigidlab::present {

template <class State>
class History {
 public:
  // `capacity` >= 1 slots, each a copy of `prototype` (throws std::bad_alloc from the copies).
  History(std::size_t capacity, const State& prototype) {
    if (capacity == 0) throw std::invalid_argument("a history needs at least one slot");
    slots_.assign(capacity, prototype);
  }

  std::size_t capacity() const { return slots_.size(); }
  std::size_t size() const { return size_; }  // states held, <= capacity
  // Of the current state among those held, 0 = the oldest; size() - 1 when at the newest.
  std::size_t position() const { return cursor_; }
  bool empty() const { return size_ == 0; }
  bool at_newest() const { return size_ == 0 || cursor_ + 1 == size_; }
  bool at_oldest() const { return cursor_ == 0; }

  // The slot for a new current state after the cursor: the states after the cursor are
  // dropped, and the oldest when the ring is full. The caller saves the state into it.
  State& record() {
    if (size_ > 0) {
      size_ = cursor_ + 1;
      if (size_ == slots_.size()) {
        first_ = (first_ + 1) % slots_.size();
        --size_;
      }
    }
    ++size_;
    cursor_ = size_ - 1;
    return slot(cursor_);
  }

  // Keeps at most `capacity` (>= 1) slots, freeing the others: the newest states stay, and the
  // cursor on its state (or on the oldest kept, if its own is dropped). For a state that has
  // grown (more contacts): the ring's memory stays bounded. Moves the states kept.
  void shrink(std::size_t capacity) {
    if (capacity == 0) throw std::invalid_argument("a history needs at least one slot");
    if (capacity >= slots_.size()) return;
    const std::size_t kept = std::min(size_, capacity), dropped = size_ - kept;
    std::vector<State> slots;
    slots.reserve(capacity);
    for (std::size_t k = dropped; k < size_; ++k) slots.push_back(std::move(slot(k)));
    // The spare slots (any content: a state is copied into them before it is read).
    while (slots.size() < capacity) slots.push_back(std::move(slots_[slots.size() % slots_.size()]));
    slots_ = std::move(slots);
    first_ = 0;
    size_ = kept;
    cursor_ = cursor_ >= dropped ? cursor_ - dropped : 0;
  }

  // Forgets every state (the slots stay allocated).
  void clear() { size_ = cursor_ = first_ = 0; }

  // The k-th state held, oldest first (k < size()).
  const State& at(std::size_t k) const { return slots_[(first_ + k) % slots_.size()]; }
  const State& current() const { return at(cursor_); }
  // The state after the current one, or nullptr at the newest.
  const State* next() const { return at_newest() ? nullptr : &at(cursor_ + 1); }

  // Moves the cursor one state back / forward; false (and no move) at either end.
  bool back() {
    if (size_ == 0 || cursor_ == 0) return false;
    --cursor_;
    return true;
  }
  bool forward() {
    if (at_newest()) return false;
    ++cursor_;
    return true;
  }

 private:
  State& slot(std::size_t k) { return slots_[(first_ + k) % slots_.size()]; }

  std::vector<State> slots_;
  std::size_t first_ = 0, size_ = 0, cursor_ = 0;
};

}  // namespace rigidlab::present
