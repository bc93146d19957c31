#include <cstdio>
#include <cstdlib>

#include "harbour/core/Assert.h"
#include "harbour/core/Warnings.h"

namespace harbour::core {
namespace {

void default_assert_handler(const char* expression, const char* message, const char* file, int line) {
  std::fprintf(stderr, "%s:%d: assertion failed: %s (%s)\n", file, line, expression, message);
  std::abort();
}

AssertHandler g_assert_handler = &default_assert_handler;

}  // namespace

AssertHandler set_assert_handler(AssertHandler handler) {
  AssertHandler previous = g_assert_handler;
  g_assert_handler = handler ? handler : &default_assert_handler;
  return previous;
}

void assert_failed(const char* expression, const char* message, const char* file, int line) {
  g_assert_handler(expression, message, file, line);
  std::abort();  // a handler that returns still stops the program
}

std::string_view to_string(Warning w) {
  switch (w) {
    case Warning::kNonFinite:
      return "non-finite value";
    case Warning::kMassDrift:
      return "mass drift";
    case Warning::kSolverMessage:
      return "rigid-body solver message";
    case Warning::kNegativeHeight:
      return "negative height";
    case Warning::kSolverLimit:
      return "solver iteration limit";
    case Warning::kCount:
      break;
  }
  return "unknown";
}

}  // namespace harbour::core
