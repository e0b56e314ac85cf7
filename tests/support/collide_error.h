// Bad input in either build of the library (collide/error.h): with exceptions a call throws
// collide::Error; without them (COLLIDE_EXCEPTIONS=OFF, -fno-exceptions) it reports to the error
// handler and returns a neutral result. The tests ask "which error did this call report?" the same
// way in both, so every bad-input test runs in both builds.
#pragma once

#include <collide/error.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>
#include <optional>
#include <string>

#ifndef COLLIDE_EXCEPTIONS
#define COLLIDE_EXCEPTIONS 1
#endif

namespace collide::test {

// The message of the first error `f` reported, or nothing. Without exceptions the handler is
// replaced for the call and put back after; an Error of another thread is not seen.
inline std::optional<std::string> errorOf(const std::function<void()>& f) {
#if COLLIDE_EXCEPTIONS
  try {
    f();
  } catch (const Error& e) {
    return std::string(e.what());
  }
  return std::nullopt;
#else
  struct Capture {
    std::optional<std::string> message;
  } capture;
  setErrorHandler(
      [](const char* message, void* context) {
        auto& c = *static_cast<Capture*>(context);
        if (!c.message) c.message = message;
      },
      &capture);
  f();
  setErrorHandler(nullptr);
  return capture.message;
#endif
}

// Matches a callable that reports an error whose message matches `matcher`.
MATCHER_P(ReportsError, matcher,
          std::string(negation ? "does not report" : "reports") + " a collide::Error whose message " +
              ::testing::DescribeMatcher<std::string>(matcher)) {
  const std::optional<std::string> message = errorOf(arg);
  if (!message) {
    *result_listener << "reports no error";
    return false;
  }
  *result_listener << "reports \"" << *message << "\"";
  return ::testing::ExplainMatchResult(matcher, *message, result_listener);
}

}  // namespace collide::test

// The statement reports a collide::Error (throws one, or without exceptions hands one to the handler).
#define EXPECT_COLLIDE_ERROR(statement) \
  EXPECT_TRUE(::collide::test::errorOf([&] { statement; }).has_value()) << #statement
#define ASSERT_COLLIDE_ERROR(statement) \
  ASSERT_TRUE(::collide::test::errorOf([&] { statement; }).has_value()) << #statement
// The statement reports no error; the message of one that it does is printed.
#define EXPECT_NO_COLLIDE_ERROR(statement) \
  EXPECT_EQ(::collide::test::errorOf([&] { statement; }).value_or(""), "") << #statement
#define ASSERT_NO_COLLIDE_ERROR(statement) \
  ASSERT_EQ(::collide::test::errorOf([&] { statement; }).value_or(""), "") << #statement
