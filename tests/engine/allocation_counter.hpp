// Counts heap allocations, to check that a step allocates nothing once its buffers have grown
// (issue 13: no per-step heap allocation). It replaces the global operator new, so it goes in
// exactly one source file of a test executable: world_contacts_test.cpp in engine_tests,
// broad_phase_allocations.cpp in its own executable.
#pragma once

#include <atomic>
#include <cstdlib>
#include <new>

inline std::atomic<long> allocations{0};

void* operator new(std::size_t size) {
  ++allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
// Over-aligned types (SolverBody starts on a cache line: engine/constraint_row.hpp) come
// through the aligned forms, which would otherwise bypass the count.
void* operator new(std::size_t size, std::align_val_t align) {
  ++allocations;
  const std::size_t a = static_cast<std::size_t>(align);
  if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a + (size == 0 ? a : 0))) return p;
  throw std::bad_alloc();
}
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
