// Per-step scratch arrays: rebuilt every step, kept from step to step for their capacity.
#pragma once

#include <cstddef>
#include <vector>

namespace collide::detail {

// Resizes a scratch array whose elements the caller writes anew (what it held is not kept). When it
// must grow, its old block is freed before the new one is taken, so the two never hold memory at
// once, and the new one has an eighth to spare: a count that creeps up from step to step does not
// take a new block each step, and the array holds about what the busiest step needed (a vector's
// own growth doubles, to up to twice that, with the old block alive while it copies).
template <typename T, typename Allocator>
void resizeScratch(std::vector<T, Allocator>& v, std::size_t n) {
  if (n > v.capacity()) {
    std::vector<T, Allocator>(v.get_allocator()).swap(v);
    v.reserve(n + n / 8);
  }
  v.resize(n);
}

// Frees a scratch array grown for a burst that is over: one of a megabyte or more whose last use
// needed less than a quarter of it. The next use takes a block its size (the default allocator
// maps blocks of this size from the system, so the freed one goes back to it at once).
template <typename T, typename Allocator>
void releaseOversizedScratch(std::vector<T, Allocator>& v, std::size_t lastUse) {
  constexpr std::size_t kLargeBytes = std::size_t{1} << 20;
  if (v.capacity() * sizeof(T) >= kLargeBytes && lastUse < v.capacity() / 4)
    std::vector<T, Allocator>(v.get_allocator()).swap(v);
}

}  // namespace collide::detail
