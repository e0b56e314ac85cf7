// How the library fails on bad input, in both builds (collide/error.h).
//
// With exceptions (COLLIDE_EXCEPTIONS=1) a failure throws collide::Error and unwinds to the caller.
// Without them, a failure records the message as the thread's pending error and the failing function
// returns a neutral value; each caller that can go on only with a good result checks
// COLLIDE_RETURN_IF_FAILED right after the call, so control goes back out as an exception would,
// and nothing is changed on the way. The outermost ErrorScope (a public function that calls other
// functions that can fail) hands the message to the engine's error handler when it closes. A
// failure outside any scope is handed over at once.
//
//   if (!(radius > 0)) COLLIDE_FAIL("sphere: radius must be ...", Shape{});   // fail, return {}
//   const Foo foo = makeFoo(...);  COLLIDE_RETURN_IF_FAILED(BodyId{});        // pass a failure on
//   withErrorContext("body 'x': ", [&] { ... });                              // prefix the message
#pragma once

#include <collide/error.h>

#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#ifndef COLLIDE_EXCEPTIONS
#define COLLIDE_EXCEPTIONS 1
#endif

namespace collide::detail {

#if COLLIDE_EXCEPTIONS

[[noreturn]] inline void raiseError(std::string message) { throw Error(message); }
constexpr bool errorPending() { return false; }

class ErrorScope {
 public:
  ErrorScope() noexcept {}  // user-provided: a scope is a statement of intent, never "unused"
  ErrorScope(const ErrorScope&) = delete;
  ErrorScope& operator=(const ErrorScope&) = delete;
};

// Runs f; an Error it raises comes out with `prefix` in front of its message (and `suffix` after).
template <typename F>
decltype(auto) withErrorContext(std::string_view prefix, F&& f, std::string_view suffix = {}) {
  try {
    return f();
  } catch (const Error& e) {
    throw Error(std::string(prefix) + e.what() + std::string(suffix));
  }
}

#define COLLIDE_FAIL(message, ...) ::collide::detail::raiseError(message)
#define COLLIDE_RETURN_IF_FAILED(...) static_cast<void>(0)

#else

// Records `message` as the pending error (the first one of a call wins), or hands it to the error
// handler at once outside any scope.
void raiseError(std::string message);
bool errorPending();
// Puts `prefix` in front of the pending error's message and `suffix` after it.
void wrapPendingError(std::string_view prefix, std::string_view suffix);

class ErrorScope {
 public:
  ErrorScope();
  ~ErrorScope();
  ErrorScope(const ErrorScope&) = delete;
  ErrorScope& operator=(const ErrorScope&) = delete;
};

template <typename F>
decltype(auto) withErrorContext(std::string_view prefix, F&& f, std::string_view suffix = {}) {
  const ErrorScope scope;
  if constexpr (std::is_void_v<decltype(f())>) {
    f();
    if (errorPending()) wrapPendingError(prefix, suffix);
  } else {
    auto result = f();
    if (errorPending()) wrapPendingError(prefix, suffix);
    return result;
  }
}

#define COLLIDE_FAIL(message, ...)          \
  do {                                      \
    ::collide::detail::raiseError(message); \
    return __VA_ARGS__;                     \
  } while (false)
#define COLLIDE_RETURN_IF_FAILED(...)                          \
  do {                                                         \
    if (::collide::detail::errorPending()) return __VA_ARGS__; \
  } while (false)

#endif

}  // namespace collide::detail
