// memory.h — host memory a request may still take, checked before
// allocating: too much is a clr::Error naming the size, not a killed process.
#pragma once

#include <cstdint>
#include <string>

namespace clr {

// The least of RLIMIT_AS and RLIMIT_DATA less what is in use, and MemAvailable; `bound` names it.
struct HostHeadroom {
  uint64_t bytes = UINT64_MAX;
  const char* bound = "";
};
HostHeadroom hostHeadroom();

// "9,395,240,960 bytes (8.7 GiB)".
std::string byteCount(uint64_t bytes);

// Throws "WHAT needs N bytes ..., more than ..." past the headroom or callerLimit.
void checkHostMemory(const std::string& what, uint64_t bytes, uint64_t callerLimit = UINT64_MAX);

}  // namespace clr
