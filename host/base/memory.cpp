// memory.cpp — host memory headroom from getrlimit and /proc (memory.h).
#include "base/memory.h"

#include "base/error.h"
#include "base/warnings.h"

#include <cstdio>
#include <cstring>
#include <sys/resource.h>
#include <unistd.h>

namespace clr {

namespace {

// Fields of /proc/self/statm in bytes: total program size (address space)
// and data + stack; 0 when unreadable.
void statm(uint64_t& size, uint64_t& data)
{
  size = data = 0;
  if (FILE* f = std::fopen("/proc/self/statm", "r")) {
    unsigned long long pages[7] = {};
    if (std::fscanf(f, "%llu %llu %llu %llu %llu %llu", &pages[0], &pages[1], &pages[2], &pages[3], &pages[4],
                    &pages[5]) == 6) {
      const uint64_t page = uint64_t(sysconf(_SC_PAGESIZE));
      size = pages[0] * page;
      data = pages[5] * page;
    }
    std::fclose(f);
  }
}

// MemAvailable of /proc/meminfo in bytes; UINT64_MAX when unreadable.
uint64_t memAvailable()
{
  uint64_t bytes = UINT64_MAX;
  if (FILE* f = std::fopen("/proc/meminfo", "r")) {
    char line[256];
    unsigned long long kb = 0;
    while (std::fgets(line, sizeof line, f))
      if (std::sscanf(line, "MemAvailable: %llu kB", &kb) == 1) {
        bytes = kb * 1024;
        break;
      }
    std::fclose(f);
  }
  return bytes;
}

}  // namespace

HostHeadroom hostHeadroom()
{
  HostHeadroom h;
  uint64_t size = 0, data = 0;
  statm(size, data);
  auto lower = [&](uint64_t bytes, const char* bound) {
    if (bytes < h.bytes) h = {bytes, bound};
  };
  struct rlimit limit;
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    lower(limit.rlim_cur > size ? limit.rlim_cur - size : 0, "left under the address-space limit (RLIMIT_AS)");
  if (getrlimit(RLIMIT_DATA, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    lower(limit.rlim_cur > data ? limit.rlim_cur - data : 0, "left under the data limit (RLIMIT_DATA)");
  lower(memAvailable(), "of memory available (MemAvailable)");
  return h;
}

std::string byteCount(uint64_t bytes)
{
  char gib[32];
  std::snprintf(gib, sizeof gib, "%.1f GiB", double(bytes) / double(uint64_t(1) << 30));
  return Warnings::grouped(bytes) + " bytes (" + gib + ")";
}

void checkHostMemory(const std::string& what, uint64_t bytes, uint64_t callerLimit)
{
  if (bytes > callerLimit)
    throw Error(what + " needs " + byteCount(bytes) + " of memory, more than the limit of " + byteCount(callerLimit));
  const HostHeadroom h = hostHeadroom();
  if (bytes > h.bytes)
    throw Error(what + " needs " + byteCount(bytes) + " of host memory, more than the " + byteCount(h.bytes) + " " +
                h.bound);
}

}  // namespace clr
