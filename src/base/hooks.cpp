// The engine's hooks (collide/hooks.h): the allocator every Array goes through, the assertion
// handler, the log handler and the profiler's zones.
#include <collide/error.h>
#include <collide/hooks.h>

#include "base/assert.h"
#include "base/fail.h"
#include "base/log.h"
#include "base/profile.h"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <new>
#include <string>

// Not under AddressSanitizer, which checks the bounds of the heap's blocks and not of mappings.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define COLLIDE_ADDRESS_SANITIZER 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define COLLIDE_ADDRESS_SANITIZER 1
#endif

#if (defined(__unix__) || defined(__APPLE__)) && !defined(__EMSCRIPTEN__) && \
    !defined(COLLIDE_ADDRESS_SANITIZER)
#include <sys/mman.h>
#define COLLIDE_MAPS_LARGE_BLOCKS 1
#else
#define COLLIDE_MAPS_LARGE_BLOCKS 0
#endif

namespace collide {

namespace {

// Every allocator installed, kept for good: a block records the one that gave it in a header before
// it and goes back to that one, even after another was installed (a thread's scratch outlives the
// worlds that grew it). Entry 0 is the C++ heap.
constexpr std::size_t kMaxAllocators = 64;
// The default allocator maps a block of 1 MiB or more straight from the system and unmaps it when
// it is freed (where the system has mmap). A large array's freed block then goes back at once,
// and its unused capacity holds no memory until touched. Through the C++ heap, glibc raises its own
// mapping threshold to the size of each mapped block freed (a contact array that doubled), and
// from then on serves every smaller block, the solver's and the broad phase's arrays among them,
// from its heap, whose freed holes stay resident (docs/benchmarks.md, Memory). Below 1 MiB the
// heap's reuse of its holes wins (mapping from 256 KiB raised R1's and R4's peaks by 1 and 2 MB).
// What the mapped blocks cannot reuse is what the program freed in the heap before them (a scene
// file's text and document): `collide run` hands that back before it builds the world.
#if COLLIDE_MAPS_LARGE_BLOCKS
constexpr std::size_t kMappedBlockBytes = std::size_t{1} << 20;
constexpr std::size_t kPageBytes = 4096;  // the smallest page of these systems: a mapping's alignment
#endif
void* heapAllocate(std::size_t bytes, std::size_t alignment, void*) {
#if COLLIDE_MAPS_LARGE_BLOCKS
  if (bytes >= kMappedBlockBytes && alignment <= kPageBytes) {
    void* block = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    return block == MAP_FAILED ? nullptr : block;
  }
#endif
  return ::operator new(bytes, std::align_val_t(alignment), std::nothrow);
}
void heapFree(void* memory, std::size_t bytes, std::size_t alignment, void*) {
#if COLLIDE_MAPS_LARGE_BLOCKS
  if (bytes >= kMappedBlockBytes && alignment <= kPageBytes) {
    munmap(memory, bytes);
    return;
  }
#else
  static_cast<void>(bytes);
#endif
  ::operator delete(memory, std::align_val_t(alignment));
}
Allocator gAllocators[kMaxAllocators] = {{&heapAllocate, &heapFree, nullptr}};
std::atomic<std::size_t> gInstalled{1};
std::atomic<const Allocator*> gCurrent{&gAllocators[0]};
std::mutex gInstallMutex;

std::atomic<std::size_t> gLiveAllocations{0};
std::atomic<std::size_t> gLiveBytes{0};

// The header before each block: at least the block's alignment (so the block stays aligned) and
// room for the pointer to its allocator, which sits just before the block.
std::size_t headerBytes(std::size_t alignment) { return std::max(alignment, alignof(std::max_align_t)); }

bool defaultAssertHandler(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "collide: assertion failed: %s (%s:%d)\n", condition, file, line);
  return true;
}
std::atomic<AssertHandler> gAssertHandler{&defaultAssertHandler};

std::atomic<LogHandler> gLogHandler{nullptr};
std::atomic<void*> gLogContext{nullptr};

ProfileHooks gProfileHooks;

void defaultErrorHandler(const char* message, void*) {
  std::fprintf(stderr, "collide: error: %s\n", message);
}
std::atomic<ErrorHandler> gErrorHandler{&defaultErrorHandler};
std::atomic<void*> gErrorContext{nullptr};

// The thread's error state: the last error handed over, and in a build without exceptions the
// pending one of the call in progress (ErrorScope depth > 0).
struct ThreadErrors {
  std::string last;
  std::string pending;
  bool hasPending = false;
  int depth = 0;
};
thread_local ThreadErrors tErrors;

[[maybe_unused]] void deliverError(std::string message) {
  tErrors.last = std::move(message);
  gErrorHandler.load()(tErrors.last.c_str(), gErrorContext.load());
}

}  // namespace

bool exceptionsEnabled() { return COLLIDE_EXCEPTIONS != 0; }

void setErrorHandler(ErrorHandler handler, void* context) {
  gErrorContext.store(context);
  gErrorHandler.store(handler ? handler : &defaultErrorHandler);
}

const char* lastError() { return tErrors.last.c_str(); }
void clearLastError() { tErrors.last.clear(); }

#if !COLLIDE_EXCEPTIONS
namespace detail {

void raiseError(std::string message) {
  if (tErrors.depth == 0) {
    deliverError(std::move(message));
    return;
  }
  if (tErrors.hasPending) return;  // the first failure of a call is its cause
  tErrors.pending = std::move(message);
  tErrors.hasPending = true;
}

bool errorPending() { return tErrors.hasPending; }

void wrapPendingError(std::string_view prefix, std::string_view suffix) {
  tErrors.pending.insert(0, prefix);
  tErrors.pending += suffix;
}

ErrorScope::ErrorScope() {
  if (tErrors.depth++ == 0) tErrors.hasPending = false;
}

ErrorScope::~ErrorScope() {
  if (--tErrors.depth == 0 && tErrors.hasPending) {
    tErrors.hasPending = false;
    deliverError(std::move(tErrors.pending));
  }
}

}  // namespace detail
#endif

void setAllocator(const Allocator& allocator) {
  if ((allocator.allocate == nullptr) != (allocator.free == nullptr))
    COLLIDE_FAIL("setAllocator: allocate and free must both be set, or both be null (the C++ heap)");
  if (allocator.allocate == nullptr) {
    gCurrent.store(&gAllocators[0]);
    return;
  }
  const std::lock_guard lock(gInstallMutex);
  const std::size_t count = gInstalled.load();
  if (count == kMaxAllocators) {
    COLLIDE_FAIL("setAllocator: " + std::to_string(kMaxAllocators - 1) +
                 " allocators were installed already, the most one process can have");
  }
  gAllocators[count] = allocator;
  gInstalled.store(count + 1);
  gCurrent.store(&gAllocators[count]);
}

std::size_t liveAllocations() { return gLiveAllocations.load(); }
std::size_t liveAllocatedBytes() { return gLiveBytes.load(); }

namespace detail {

// An allocator that has no memory left: std::bad_alloc where there are exceptions; without them the
// engine's error handler hears of it, then the process aborts, as operator new does.
[[noreturn]] void outOfMemory(std::size_t bytes) {
#if COLLIDE_EXCEPTIONS
  static_cast<void>(bytes);
  throw std::bad_alloc();
#else
  deliverError("out of memory: the allocator returned null for " + std::to_string(bytes) + " bytes");
  std::abort();
#endif
}

void* allocateBytes(std::size_t bytes, std::size_t alignment) {
  const Allocator* allocator = gCurrent.load(std::memory_order_acquire);
  const std::size_t header = headerBytes(alignment);
  auto* raw = static_cast<unsigned char*>(allocator->allocate(header + bytes, header, allocator->context));
  if (!raw) outOfMemory(header + bytes);
  unsigned char* block = raw + header;
  std::memcpy(block - sizeof(allocator), &allocator, sizeof(allocator));
  gLiveAllocations.fetch_add(1, std::memory_order_relaxed);
  gLiveBytes.fetch_add(bytes, std::memory_order_relaxed);
  return block;
}

void freeBytes(void* memory, std::size_t bytes, std::size_t alignment) noexcept {
  if (!memory) return;
  auto* block = static_cast<unsigned char*>(memory);
  const Allocator* allocator = nullptr;
  std::memcpy(&allocator, block - sizeof(allocator), sizeof(allocator));
  const std::size_t header = headerBytes(alignment);
  gLiveAllocations.fetch_sub(1, std::memory_order_relaxed);
  gLiveBytes.fetch_sub(bytes, std::memory_order_relaxed);
  allocator->free(block - header, header + bytes, header, allocator->context);
}

void releaseCopiedPages(void* memory, std::size_t bytes, std::size_t alignment, void* from,
                        std::size_t count) noexcept {
#if COLLIDE_MAPS_LARGE_BLOCKS
  if (!memory || count == 0) return;
  auto* block = static_cast<unsigned char*>(memory);
  const Allocator* allocator = nullptr;
  std::memcpy(&allocator, block - sizeof(allocator), sizeof(allocator));
  const std::size_t header = headerBytes(alignment);
  // Only a block the default allocator mapped (heapAllocate): any other is the heap's or a user's.
  if (allocator != &gAllocators[0] || header + bytes < kMappedBlockBytes || header > kPageBytes) return;
  const auto first = (reinterpret_cast<std::uintptr_t>(from) + kPageBytes - 1) & ~(kPageBytes - 1);
  const auto last = (reinterpret_cast<std::uintptr_t>(from) + count) & ~(kPageBytes - 1);
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_DONTNEED);
#else
  static_cast<void>(memory), static_cast<void>(bytes), static_cast<void>(alignment), static_cast<void>(from),
      static_cast<void>(count);
#endif
}

void assertFailed(const char* condition, const char* file, int line) {
  const AssertHandler handler = gAssertHandler.load();
  if (handler(condition, file, line)) std::abort();
}

bool logging() { return gLogHandler.load() != nullptr; }

void logMessage(LogLevel level, const std::string& message) {
  const LogHandler handler = gLogHandler.load();
  if (handler) handler(level, message.c_str(), gLogContext.load());
}

void profileBegin(const char* name) {
  if (gProfileHooks.beginZone) gProfileHooks.beginZone(name, gProfileHooks.context);
}

void profileEnd() {
  if (gProfileHooks.endZone) gProfileHooks.endZone(gProfileHooks.context);
}

}  // namespace detail

void setAssertHandler(AssertHandler handler) {
  gAssertHandler.store(handler ? handler : &defaultAssertHandler);
}

bool assertionsEnabled() { return COLLIDE_ASSERTS_ENABLED != 0; }

void setLogHandler(LogHandler handler, void* context) {
  gLogContext.store(context);
  gLogHandler.store(handler);
}

void setProfileHooks(const ProfileHooks& hooks) { gProfileHooks = hooks; }

bool profileZonesEnabled() { return COLLIDE_PROFILE_ZONES != 0; }

}  // namespace collide
