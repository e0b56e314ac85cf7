// Asking the memory system for data ahead of its use (the contacts stage's pair loop, the bounds
// stage, the contact batch build, the hulls' arrays). Through these functions, not
// __builtin_prefetch directly: GCC finds a helper that does nothing but prefetch free of effects
// (its pure-const analysis) and drops the calls to it, so a prefetch in a small lambda can vanish
// from the build. An asm statement is an effect the optimiser keeps.
#pragma once

#include <cstddef>
#include <cstdint>

namespace collide::detail {

#if defined(__GNUC__)
#define COLLIDE_PREFETCH_INLINE inline __attribute__((always_inline))
#else
#define COLLIDE_PREFETCH_INLINE inline
#endif

COLLIDE_PREFETCH_INLINE void prefetchLine(const void* address) {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(address)));
#elif defined(__GNUC__)
  __builtin_prefetch(address);
#else
  (void)address;  // no portable prefetch: the loads simply wait
#endif
}

// Every cache line that [data, data + bytes) touches: one line every 64 bytes from the start, then
// the last byte's (a range not starting on a line spans one line more). The count depends on the
// size only, not on where the range lies, so that the work (and a fuzzer's view of it) is the same
// wherever the allocator put the data.
COLLIDE_PREFETCH_INLINE void prefetchBytes(const void* data, std::size_t bytes) {
  if (bytes == 0) return;
  constexpr std::size_t kLine = 64;
  const char* first = static_cast<const char*>(data);
  for (std::size_t offset = 0; offset < bytes; offset += kLine) prefetchLine(first + offset);
  prefetchLine(first + bytes - 1);
}

// Both ends of a record: one not aligned to the cache lines straddles two.
template <typename Record>
COLLIDE_PREFETCH_INLINE void prefetchRecord(const Record& record) {
  prefetchLine(&record);
  prefetchLine(reinterpret_cast<const char*>(&record) + sizeof(Record) - 1);
}

}  // namespace collide::detail
