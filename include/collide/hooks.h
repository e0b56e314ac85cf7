// Where collide's memory, assertions, warnings and profiling go: hooks an engine installs once, before
// it creates shapes or worlds (Box2D v3's b2SetAllocator and b2SetAssertFcn, Jolt's Allocate and
// AssertFailed are the models). Each has a default: the C++ heap, a message and abort, silence, and
// nothing. Hooks are process-wide; set them before other threads use collide.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace collide {

// ---- Memory ----------------------------------------------------------------------------------------
// Every array the library keeps or grows (bodies, contacts, pairs, the broad phase's nodes, the
// solver's batches, the joints, shapes' vertices and faces, the step's scratch and each thread's
// narrow-phase scratch) is an Array, whose memory comes from the installed allocator. allocate
// returns `bytes` aligned to `alignment` (a power of two, at least alignof(std::max_align_t)), or
// nullptr when it has none (the library then throws std::bad_alloc, or in a build without
// exceptions tells the error handler and aborts, as operator new would); free gets back the same bytes
// and alignment. A block asks for a little more than its array needs: a header records which
// allocator gave it, and the block goes back to that one even after another is installed (a
// thread's scratch outlives the world that grew it). The allocator's functions must be callable from
// any thread, the world's workers included, and stay valid while any of its blocks lives.
struct Allocator {
  void* (*allocate)(std::size_t bytes, std::size_t alignment, void* context) = nullptr;
  void (*free)(void* memory, std::size_t bytes, std::size_t alignment, void* context) = nullptr;
  void* context = nullptr;
};

// Installs `allocator` (both functions set) for the arrays created or grown from now on, or the
// default again (a default Allocator{}): the C++ heap, except that on systems with mmap a block of
// 1 MiB or more is mapped from the system and unmapped when freed, so that a large array's old
// block goes back at once instead of staying resident in the heap. At most 63 allocators in a
// process's life.
void setAllocator(const Allocator& allocator);

// Blocks the library's arrays hold now, and the bytes their arrays asked for (headers not counted).
std::size_t liveAllocations();
std::size_t liveAllocatedBytes();

namespace detail {
void* allocateBytes(std::size_t bytes, std::size_t alignment);
void freeBytes(void* memory, std::size_t bytes, std::size_t alignment) noexcept;
// Of a block of `bytes` from allocateBytes, the whole pages within [from, from + count) go back to
// the system where the default allocator mapped the block (elsewhere nothing happens): their
// contents are lost, and they read as zero if touched again. For a block about to be freed whose
// contents were copied out (growth without both blocks held whole at once).
void releaseCopiedPages(void* memory, std::size_t bytes, std::size_t alignment, void* from,
                        std::size_t count) noexcept;

// The standard allocator interface over the installed hooks.
template <typename T>
struct HookAllocator {
  using value_type = T;
  HookAllocator() noexcept = default;
  template <typename U>
  HookAllocator(const HookAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(allocateBytes(n * sizeof(T), alignof(T))); }
  void deallocate(T* p, std::size_t n) noexcept { freeBytes(p, n * sizeof(T), alignof(T)); }
  template <typename U>
  bool operator==(const HookAllocator<U>&) const noexcept {
    return true;
  }
};
}  // namespace detail

// A std::vector whose memory comes from the installed allocator.
template <typename T>
using Array = std::vector<T, detail::HookAllocator<T>>;

// ---- Assertions ------------------------------------------------------------------------------------
// The library's internal invariants (an index in range, a pivot that exists, a colour without a
// body twice) are checked by assertions in builds that enable them: without NDEBUG, or with
// COLLIDE_ENABLE_ASSERTS defined when the library is compiled; in a release build they compile out.
// A failed one calls the handler with the condition's text, the file and the line; the handler
// returns true to abort (a breakpoint first, if the engine likes), false to go on. Bad input is not
// an assertion: it is a collide::Error naming the value.
using AssertHandler = bool (*)(const char* condition, const char* file, int line);
// nullptr restores the default: the condition, file and line on stderr, then abort.
void setAssertHandler(AssertHandler handler);
// Whether this build of the library checks its assertions.
bool assertionsEnabled();

// ---- Warnings --------------------------------------------------------------------------------------
// What the library has to say that is not an error: Info (an array grew past its capacity, so the
// step allocated), Warning (a body frozen by the fault guard, a joint tree the direct solve could
// not factor). The message is one line, without a newline; it lives until the handler returns.
enum class LogLevel : std::uint8_t { Info, Warning };
using LogHandler = void (*)(LogLevel level, const char* message, void* context);
// nullptr restores the default: silence.
void setLogHandler(LogHandler handler, void* context = nullptr);

// ---- Profiling -------------------------------------------------------------------------------------
// Zones around each stage of the step (broad phase, narrow phase, solve, continuous, events,
// islands) and the world's parallel tasks, for an external profiler (Tracy's ___tracy_emit_zone_begin
// and _end, Superluminal, Optick, the engine's own). Compiled in only with the CMake option
// COLLIDE_PROFILE_ZONES (the macro COLLIDE_PROFILE_ZONES=1 when the library is built); otherwise the
// hooks are kept but never called. `name` is a string literal; zones nest and end on the thread that
// began them. The step's stage times are data every step either way (StepStats::time).
struct ProfileHooks {
  void (*beginZone)(const char* name, void* context) = nullptr;
  void (*endZone)(void* context) = nullptr;
  void* context = nullptr;
};
void setProfileHooks(const ProfileHooks& hooks);
// Whether this build of the library calls the profile hooks.
bool profileZonesEnabled();

// ---- Hull building ---------------------------------------------------------------------------------
// collide builds convex hulls (ConvexHull::fromPoints, k-DOPs, the box's polytope) with Qhull. A
// build without Qhull (the CMake option COLLIDE_WITH_QHULL=OFF: the WebAssembly build, for which
// Debian has no Qhull; collide.js installs three.js's ConvexHull) takes the hull's triangles from a
// finder the host installs: given `count` points as 3 * count floats (x, y, z), it appends the
// hull's triangles to `triangles` as three indices into the points each, in any orientation, and
// returns false if it found no hull. collide checks that they close a surface and merges coplanar
// neighbours into faces, as Qhull's merging does. An installed finder is used in every build.
using HullTriangleFinder = bool (*)(const float* xyz, std::size_t count,
                                    std::vector<std::uint32_t>& triangles, void* context);
// nullptr restores the default: Qhull, or in a build without it, hulls refused with an Error.
void setHullTriangleFinder(HullTriangleFinder finder, void* context = nullptr);
// Whether this build can build hulls now: Qhull compiled in, or a finder installed.
bool canBuildHulls();

}  // namespace collide
