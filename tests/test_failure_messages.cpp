// test_failure_messages.cpp — the one mapping from a failure to its line
// (failureMessage, flags.h): each kind of exception gets its message, and the
// library's guarded() (api_impl.h) throws a clraster::Error with that same
// line, so the CLI and the library say the same thing.
#include "api/api_impl.h"

#include <catch2/catch.hpp>

#include <functional>
#include <new>
#include <stdexcept>
#include <string>

namespace {

std::string messageOf(const std::function<void()>& fail)
{
  try {
    fail();
  } catch (const std::exception&) {
    return clr::failureMessage();
  }
  return "(nothing thrown)";
}

}  // namespace

TEST_CASE("failures: one message for each kind in the CLI and the library alike", "[cli]")
{
  const std::function<void()> failures[] = {
      [] { throw clr::Error("scene.obj: cannot open"); },
      [] { throw cl::Error(CL_OUT_OF_RESOURCES, "clEnqueueNDRangeKernel"); },
      [] { throw std::bad_alloc(); },
      [] { throw std::runtime_error("something else"); },
  };
  const std::string expected[] = {
      "scene.obj: cannot open",
      "OpenCL call clEnqueueNDRangeKernel failed: CL_OUT_OF_RESOURCES (-5)",
      "out of host memory",
      "something else",
  };
  for (size_t k = 0; k < std::size(failures); ++k) {
    CAPTURE(k);
    CHECK(messageOf(failures[k]) == expected[k]);
    std::string fromLibrary = "(nothing thrown)";
    try {
      clraster::guarded(failures[k]);
    } catch (const clraster::Error& e) {
      fromLibrary = e.what();
    }
    CHECK(fromLibrary == expected[k]);
  }
}
