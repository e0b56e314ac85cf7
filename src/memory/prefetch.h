// Asking the memory system for data ahead of its use (the world's pair loop, the contact batch
// build, the hulls' arrays). Through these functions, not __builtin_prefetch directly: GCC finds a
// helper that does nothing but prefetch free of effects (its pure-const analysis) and drops the
// calls to it, so a prefetch written in a small lambda silently vanished from the contact solver's
// batch build. An asm statement is an effect the optimiser keeps.
#pragma once

#include <cstddef>

namespace collide::detail {

inline __attribute__((always_inline)) void prefetchLine(const void* address) {
#if defined(__x86_64__) || defined(__i386__)
  asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(address)));
#else
  __builtin_prefetch(address);
#endif
}

// Every cache line of [data, data + bytes).
inline __attribute__((always_inline)) void prefetchBytes(const void* data, std::size_t bytes) {
  const char* begin = static_cast<const char*>(data);
  for (std::size_t offset = 0; offset < bytes; offset += 64) prefetchLine(begin + offset);
}

// Both ends of a record: one not aligned to the cache lines straddles two.
template <typename Record>
inline __attribute__((always_inline)) void prefetchRecord(const Record& record) {
  prefetchLine(&record);
  prefetchLine(reinterpret_cast<const char*>(&record) + sizeof(Record) - 1);
}

}  // namespace collide::detail
