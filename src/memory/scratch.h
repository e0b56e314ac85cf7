// Per-step scratch arrays: rebuilt every step, kept from step to step for their capacity.
#pragma once

#include <collide/hooks.h>

#include <algorithm>
#include <cstddef>
#include <type_traits>
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

// Grows a kept array's block to `capacity` elements (its records kept) without the old and the new
// block both held whole: the records are copied a quarter megabyte at a time, and each stretch
// copied goes back to the system from the old block where the default allocator mapped it. A
// vector's own growth holds both while it copies: a contact array doubling from 2 to 4 MB as a
// landing's contacts arrive is a 2 MB peak that is gone a moment later.
template <typename T>
void growByStretches(Array<T>& v, std::size_t capacity) {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);
  if (capacity <= v.capacity()) return;
  Array<T> bigger;
  bigger.reserve(capacity);
  constexpr std::size_t kStretch = std::max<std::size_t>(1, (std::size_t{1} << 18) / sizeof(T));
  for (std::size_t i = 0; i < v.size(); i += kStretch) {
    const std::size_t n = std::min(kStretch, v.size() - i);
    bigger.insert(bigger.end(), v.begin() + static_cast<std::ptrdiff_t>(i),
                  v.begin() + static_cast<std::ptrdiff_t>(i + n));
    releaseCopiedPages(v.data(), v.capacity() * sizeof(T), alignof(T), v.data() + i, n * sizeof(T));
  }
  v.swap(bigger);
}

}  // namespace collide::detail
