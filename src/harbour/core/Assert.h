#pragma once

namespace harbour::core {

/// Called when an assertion fails; the default prints and aborts. Tests may install their own.
using AssertHandler = void (*)(const char* expression, const char* message, const char* file, int line);

/// Installs `handler` and returns the previous one.
AssertHandler set_assert_handler(AssertHandler handler);
/// Reports a failed assertion through the installed handler.
[[gnu::cold]] void assert_failed(const char* expression, const char* message, const char* file, int line);

}  // namespace harbour::core

/// Checks a programming invariant (never user input), in every build type.
#define HARBOUR_ASSERT(cond, msg)                                                \
  do {                                                                           \
    if (!(cond)) ::harbour::core::assert_failed(#cond, msg, __FILE__, __LINE__); \
  } while (false)
