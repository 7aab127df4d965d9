// error.hpp — clraster::Error, the one exception type of the library (and
// of the CLI, whose clr::Error it is): a one-line message fit to print.
#pragma once

#include <stdexcept>
#include <string>

// What the shared library exports (it hides everything else).
#if defined(__GNUC__) || defined(__clang__)
#define CLRASTER_API __attribute__((visibility("default")))
#else
#define CLRASTER_API
#endif

namespace clraster {

struct CLRASTER_API Error : std::runtime_error {
  using std::runtime_error::runtime_error;
  // p itself, or an Error when it is null: the object `what` was moved from.
  template <typename T>
  static T* live(T* p, const char* what)
  {
    if (!p) throw Error(std::string(what) + ": used after it was moved from");
    return p;
  }
};

}  // namespace clraster
