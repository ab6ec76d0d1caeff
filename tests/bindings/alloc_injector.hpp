// A Lua allocator for the binding tests that refuses allocations on demand, as rigidlab's
// --max-memory allocator (cli/limits.cpp) refuses them past the cap: it returns NULL, Lua
// collects garbage, tries once more and raises "not enough memory".
#pragma once

#include <cstdlib>

// Counts the allocations that grow a block and refuses those from `first_refused` on
// (`refuse_one`: only that one). first_refused = -1: refuses nothing.
struct Injector {
  long count = 0;
  long first_refused = -1;
  bool refuse_one = true;
  bool refused = false;

  static void* allocate(void* self_pointer, void* block, std::size_t old_size,
                        std::size_t new_size) {
    auto& self = *static_cast<Injector*>(self_pointer);
    const std::size_t old_bytes = block != nullptr ? old_size : 0;
    if (new_size == 0) {
      std::free(block);
      return nullptr;
    }
    if (new_size > old_bytes) {
      ++self.count;
      const bool refuse = self.refuse_one ? self.count == self.first_refused
                                          : self.first_refused > 0 && self.count >= self.first_refused;
      if (refuse) {
        self.refused = true;
        return nullptr;
      }
    }
    return std::realloc(block, new_size);
  }
};
