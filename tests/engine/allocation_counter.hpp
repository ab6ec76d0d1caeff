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
