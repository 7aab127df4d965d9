// error.hpp — clraster::Error, the one exception type of the library (and
// of the CLI, whose clr::Error it is): a one-line message fit to print.
#pragma once

#include <stdexcept>

// What the shared library exports (it hides everything else).
#if defined(__GNUC__) || defined(__clang__)
#define CLRASTER_API __attribute__((visibility("default")))
#else
#define CLRASTER_API
#endif

namespace clraster {

struct CLRASTER_API Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace clraster
