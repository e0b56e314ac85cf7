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
#include <vector>

#ifndef COLLIDE_EXCEPTIONS
#define COLLIDE_EXCEPTIONS 1
#endif

namespace collide::test {

// Each message the error handler got during f, in order: the handler is replaced for the call and
// put back after (an Error of another thread is not seen). With exceptions the handler hears
// nothing, and an Error f throws is caught and dropped.
inline std::vector<std::string> handledErrors(const std::function<void()>& f) {
  std::vector<std::string> messages;
  setErrorHandler([](const char* message,
                     void* context) { static_cast<std::vector<std::string>*>(context)->push_back(message); },
                  &messages);
#if COLLIDE_EXCEPTIONS
  try {
    f();
  } catch (const Error&) {
  }
#else
  f();
#endif
  setErrorHandler(nullptr);
  return messages;
}

// The message of the first error `f` reported (the Error it threw, or without exceptions the first
// message the handler got), or nothing.
inline std::optional<std::string> errorOf(const std::function<void()>& f) {
#if COLLIDE_EXCEPTIONS
  try {
    f();
  } catch (const Error& e) {
    return std::string(e.what());
  }
  return std::nullopt;
#else
  const std::vector<std::string> messages = handledErrors(f);
  if (messages.empty()) return std::nullopt;
  return messages.front();
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
