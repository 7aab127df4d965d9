// text_scan.cpp — line-aligned parts, threads and number scanning for the
// direct text readers (see text_scan.h).
#include "io/text_scan.h"

#include <fast_float/fast_float.h>

#include <algorithm>
#include <cstring>
#include <thread>

namespace clr {

namespace {

// Below this many bytes per part, a thread costs more than it saves.
constexpr size_t kMinPartBytes = size_t(1) << 20;

}  // namespace

size_t textParts(size_t bytes)
{
  const size_t threads = std::max<size_t>(1, std::min<size_t>(16, std::thread::hardware_concurrency()));
  return std::max<size_t>(1, std::min(threads, bytes / kMinPartBytes));
}

std::vector<TextPart> splitLines(const char* begin, const char* end, size_t parts)
{
  std::vector<TextPart> out;
  const size_t size = size_t(end - begin);
  parts = std::max<size_t>(1, parts);
  const char* at = begin;
  for (size_t i = 1; i <= parts && at < end; ++i) {
    const char* cut = i == parts ? end : std::max(at, begin + size / parts * i);
    if (cut < end) {
      const void* nl = std::memchr(cut, '\n', size_t(end - cut));
      cut = nl ? static_cast<const char*>(nl) + 1 : end;
    }
    if (cut > at) out.push_back({at, cut});
    at = cut;
  }
  return out;
}

void runParts(size_t count, const std::function<void(size_t)>& job)
{
  std::vector<std::thread> threads;
  threads.reserve(count > 0 ? count - 1 : 0);
  for (size_t i = 1; i < count; ++i) threads.emplace_back(job, i);
  if (count > 0) job(0);
  for (std::thread& t : threads) t.join();
}

size_t countLines(const char* begin, const char* end)
{
  return size_t(std::count(begin, end, '\n'));
}

const char* scanFloat(const char* p, const char* end, float& value)
{
  const char* start = p;
  if (p < end && *p == '+') ++p;
  if (p < end && (*p == '+' || (*p == '-' && p != start))) return nullptr;
  // fast_float reads "inf" and "nan"; a word must start with a digit, a sign or '.'.
  const char* digit = p < end && *p == '-' ? p + 1 : p;
  if (digit == end || !((*digit >= '0' && *digit <= '9') || *digit == '.')) return nullptr;
  const auto result = fast_float::from_chars(p, end, value, fast_float::chars_format::general);
  if (result.ec != std::errc() && result.ec != std::errc::result_out_of_range) return nullptr;
  if (result.ptr == p || !endsWord(result.ptr, end)) return nullptr;
  return result.ptr;
}

const char* scanUnsigned(const char* p, const char* end, uint64_t& value)
{
  const char* const start = p;
  uint64_t v = 0;
  while (p < end && *p >= '0' && *p <= '9' && p - start < 18) v = v * 10 + uint64_t(*p++ - '0');
  if (p == start || !endsWord(p, end)) return nullptr;
  value = v;
  return p;
}

const char* lineEnd(const char* p, const char* end, const char** next)
{
  const void* nl = std::memchr(p, '\n', size_t(end - p));
  if (!nl) {
    *next = end;
    return end;
  }
  const char* e = static_cast<const char*>(nl);
  *next = e + 1;
  return e > p && e[-1] == '\r' ? e - 1 : e;
}

}  // namespace clr
