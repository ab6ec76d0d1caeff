// One memory budget for --max-memory: what Lua allocates (through the state's allocator) and
// what the engine and the bindings allocate in C++ (through operator new: a world's bodies,
// planes and contacts) count against the same limit. Without the C++ part, a script under
// `--max-memory 16` could fill 400 MB with planes, and 2000 overlapping spheres 1.6 GB of
// contacts in one w:step.
//
// This file replaces the global operator new and delete of the rigidlab executable (only of
// the executable: the libraries and their tests keep the standard ones) with counting ones.
// Every allocation is counted; one is refused only on a thread that charges a budget
// (ChargeHeap, set around the calls into a user's code), and only when it would take the
// budget past its limit: operator new then throws std::bad_alloc, which the bindings turn into
// Lua's "not enough memory" error, and the engine undoes what it was doing (World::step
// undoes the step). Elsewhere (the CLI's own work between calls, other threads) nothing is
// refused, so a std::bad_alloc is never thrown where no one catches it.
//
// Not counted: Eigen's dynamic-size matrices, which allocate with malloc (the only ones today
// are ode.step's state vectors, smaller than the Lua tables they are read from).
#pragma once

#include <cstddef>

namespace rigidlab::cli {

// Bytes held now through operator new, by every thread (malloc's usable sizes).
std::size_t heap_bytes();

// The bytes of one Lua state and the C++ heap's growth since the budget was made, against one
// limit.
class MemoryBudget {
 public:
  explicit MemoryBudget(std::size_t limit_bytes);  // 0: no limit
  std::size_t limit() const { return limit_; }

  // Lua's allocator asks before growing a block from `old_bytes` to `new_bytes`, and reports
  // what it did.
  bool lua_may_grow(std::size_t old_bytes, std::size_t new_bytes) const;
  void lua_changed(std::size_t old_bytes, std::size_t new_bytes) {
    lua_bytes_ = lua_bytes_ - old_bytes + new_bytes;
  }
  void set_lua_bytes(std::size_t bytes) { lua_bytes_ = bytes; }
  // operator new asks before keeping a block: false when the budget would pass its limit.
  bool heap_may_hold(std::size_t heap_now) const;
  // C++ bytes allocated since the budget was made (0 if fewer are held now).
  std::size_t heap_growth() const;
  std::size_t used() const { return lua_bytes_ + heap_growth(); }

  // Whether an allocation was refused, and forgetting it (a new run).
  bool refused() const { return refused_; }
  void set_refused(bool refused) { refused_ = refused; }

 private:
  std::size_t limit_;
  std::size_t heap_baseline_;
  std::size_t lua_bytes_ = 0;
  bool refused_ = false;
};

// While alive, operator new on this thread charges `budget` (nullptr: none) and refuses what
// would pass its limit. Nests: the previous budget is charged again afterwards.
class ChargeHeap {
 public:
  explicit ChargeHeap(MemoryBudget* budget);
  ~ChargeHeap();
  ChargeHeap(const ChargeHeap&) = delete;
  ChargeHeap& operator=(const ChargeHeap&) = delete;

 private:
  MemoryBudget* previous_;
};

}  // namespace rigidlab::cli
