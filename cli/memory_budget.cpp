#include "cli/memory_budget.hpp"

#include <malloc.h>

#include <atomic>
#include <cstdlib>
#include <new>

namespace rigidlab::cli {
namespace {

std::atomic<std::size_t> heap_total{0};
thread_local MemoryBudget* charged = nullptr;

// Counts the block `p` just allocated; false (and the block is not counted) when the budget
// this thread charges refuses it.
bool count_block(void* p) {
  const std::size_t size = malloc_usable_size(p);
  const std::size_t now = heap_total.fetch_add(size, std::memory_order_relaxed) + size;
  MemoryBudget* budget = charged;
  if (budget == nullptr || budget->heap_may_hold(now)) return true;
  heap_total.fetch_sub(size, std::memory_order_relaxed);
  budget->set_refused(true);
  return false;
}

void uncount_block(void* p) {
  if (p != nullptr) heap_total.fetch_sub(malloc_usable_size(p), std::memory_order_relaxed);
}

// malloc or aligned_alloc, with operator new's loop over the new-handler when the system has
// no memory; nullptr when it has none (and no handler) or the budget refuses.
void* allocate(std::size_t size, std::size_t alignment) {
  if (size == 0) size = 1;
  for (;;) {
    void* p;
    if (alignment <= alignof(std::max_align_t)) {
      p = std::malloc(size);
    } else {
      const std::size_t rounded = (size + alignment - 1) / alignment * alignment;
      p = rounded >= size ? std::aligned_alloc(alignment, rounded) : nullptr;
    }
    if (p != nullptr) {
      if (count_block(p)) return p;
      std::free(p);
      return nullptr;  // the limit, not the system: no new-handler can help
    }
    const std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) return nullptr;
    handler();
  }
}

void* allocate_or_throw(std::size_t size, std::size_t alignment) {
  void* p = allocate(size, alignment);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

void release(void* p) noexcept {
  uncount_block(p);
  std::free(p);
}

}  // namespace

std::size_t heap_bytes() { return heap_total.load(std::memory_order_relaxed); }

MemoryBudget::MemoryBudget(std::size_t limit_bytes)
    : limit_(limit_bytes), heap_baseline_(heap_bytes()) {}

bool MemoryBudget::lua_may_grow(std::size_t old_bytes, std::size_t new_bytes) const {
  return limit_ == 0 || new_bytes <= old_bytes ||
         lua_bytes_ - old_bytes + new_bytes + heap_growth() <= limit_;
}

bool MemoryBudget::heap_may_hold(std::size_t heap_now) const {
  const std::size_t growth = heap_now > heap_baseline_ ? heap_now - heap_baseline_ : 0;
  return limit_ == 0 || lua_bytes_ + growth <= limit_;
}

std::size_t MemoryBudget::heap_growth() const {
  const std::size_t now = heap_bytes();
  return now > heap_baseline_ ? now - heap_baseline_ : 0;
}

ChargeHeap::ChargeHeap(MemoryBudget* budget) : previous_(charged) { charged = budget; }

ChargeHeap::~ChargeHeap() { charged = previous_; }

}  // namespace rigidlab::cli

// ---- the replaced global allocation functions ([new.delete], every form) ------------------

using rigidlab::cli::allocate;
using rigidlab::cli::allocate_or_throw;
using rigidlab::cli::release;
constexpr std::size_t plain = alignof(std::max_align_t);

void* operator new(std::size_t size) { return allocate_or_throw(size, plain); }
void* operator new[](std::size_t size) { return allocate_or_throw(size, plain); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  return allocate(size, plain);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return allocate(size, plain);
}
void* operator new(std::size_t size, std::align_val_t alignment) {
  return allocate_or_throw(size, static_cast<std::size_t>(alignment));
}
void* operator new[](std::size_t size, std::align_val_t alignment) {
  return allocate_or_throw(size, static_cast<std::size_t>(alignment));
}
void* operator new(std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return allocate(size, static_cast<std::size_t>(alignment));
}
void* operator new[](std::size_t size, std::align_val_t alignment,
                     const std::nothrow_t&) noexcept {
  return allocate(size, static_cast<std::size_t>(alignment));
}

void operator delete(void* p) noexcept { release(p); }
void operator delete[](void* p) noexcept { release(p); }
void operator delete(void* p, std::size_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t) noexcept { release(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { release(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { release(p); }
void operator delete(void* p, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::align_val_t) noexcept { release(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { release(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { release(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { release(p); }
