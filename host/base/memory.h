// memory.h — how much host memory a request may still take, checked before
// allocating, so that a request too large for the machine, or for a limit
// the process runs under (RLIMIT_AS, RLIMIT_DATA), is a clr::Error naming
// the size instead of a process killed by the kernel or aborted by a driver.
#pragma once

#include <cstdint>
#include <string>

namespace clr {

// The most host memory that can still be allocated: the least of
// RLIMIT_AS less the address space in use, RLIMIT_DATA less the data in
// use, and the kernel's MemAvailable. `bound` names which one it is.
struct HostHeadroom {
  uint64_t bytes = UINT64_MAX;
  const char* bound = "";
};
HostHeadroom hostHeadroom();

// "9,395,240,960 bytes (8.7 GiB)".
std::string byteCount(uint64_t bytes);

// Throws clr::Error "WHAT needs N bytes of host memory, more than the M
// bytes BOUND" when bytes exceed the headroom or callerLimit.
void checkHostMemory(const std::string& what, uint64_t bytes, uint64_t callerLimit = UINT64_MAX);

}  // namespace clr
