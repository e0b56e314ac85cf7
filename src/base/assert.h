// COLLIDE_ASSERT: an internal invariant, checked where assertions are enabled (collide/hooks.h:
// builds without NDEBUG, or with COLLIDE_ENABLE_ASSERTS) and compiled out elsewhere, its condition
// not evaluated. A failed one goes to the engine's assert handler (setAssertHandler).
#pragma once

#if !defined(NDEBUG) || defined(COLLIDE_ENABLE_ASSERTS)
#define COLLIDE_ASSERTS_ENABLED 1
#else
#define COLLIDE_ASSERTS_ENABLED 0
#endif

namespace collide::detail {
[[gnu::cold]] void assertFailed(const char* condition, const char* file, int line);
}  // namespace collide::detail

#if COLLIDE_ASSERTS_ENABLED
#define COLLIDE_ASSERT(condition) \
  ((condition) ? static_cast<void>(0) : ::collide::detail::assertFailed(#condition, __FILE__, __LINE__))
#else
#define COLLIDE_ASSERT(condition) static_cast<void>(sizeof(static_cast<bool>(condition)))
#endif
