// What a container holds on the heap, in bytes, for World::memoryUse: the capacity it reserved,
// since the step's arrays keep theirs from step to step (a vector is cleared, not freed).
#pragma once

#include <cstddef>
#include <string>
#include <unordered_map>
#include <vector>

namespace collide::detail {

template <typename T, typename Allocator>
std::size_t heapBytes(const std::vector<T, Allocator>& v) {
  return v.capacity() * sizeof(T);
}

// A string's heap block, none while it fits in the string itself (the short-string buffer).
inline std::size_t heapBytes(const std::string& s) {
  return s.capacity() > std::string().capacity() ? s.capacity() + 1 : 0;
}

// The bucket array and one node per element (the value and the next pointer; libstdc++ also keeps
// the hash of keys it does not cache, which integers are not).
template <typename K, typename V, typename H, typename E, typename A>
std::size_t heapBytes(const std::unordered_map<K, V, H, E, A>& m) {
  return m.bucket_count() * sizeof(void*) + m.size() * (sizeof(std::pair<const K, V>) + sizeof(void*));
}

}  // namespace collide::detail
