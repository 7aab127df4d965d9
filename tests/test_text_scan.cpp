// test_text_scan.cpp — the direct text readers' shared machinery
// (io/text_scan.h): line-aligned parts, the thread runner and the strict
// number scanners, checked against std::from_chars and hand-made cases.
#include "io/text_scan.h"

#include <catch2/catch.hpp>

#include <atomic>
#include <charconv>
#include <cstring>
#include <random>
#include <string>

TEST_CASE("text scan: parts are line-aligned and cover the text in order", "[io][text]")
{
  std::string text;
  std::mt19937 rng(7);
  for (int i = 0; i < 5000; ++i) text += std::string(rng() % 40, 'x') + (i % 3 ? "\n" : "\r\n");
  text += "last line without its end";
  for (size_t parts : {1, 2, 3, 7, 64}) {
    const auto split = clr::splitLines(text.data(), text.data() + text.size(), parts);
    REQUIRE(!split.empty());
    REQUIRE(split.size() <= parts);
    CHECK(split.front().begin == text.data());
    CHECK(split.back().end == text.data() + text.size());
    for (size_t i = 0; i + 1 < split.size(); ++i) {
      CHECK(split[i].end == split[i + 1].begin);
      CHECK(split[i].end[-1] == '\n');
    }
  }
  // One long line: one part however many are asked for.
  const std::string one(1000, 'y');
  CHECK(clr::splitLines(one.data(), one.data() + one.size(), 4).size() == 1);
  CHECK(clr::splitLines(one.data(), one.data(), 4).empty());
  CHECK(clr::textParts(100) == 1);
  CHECK(clr::countLines(text.data(), text.data() + text.size()) == 5000);
}

TEST_CASE("text scan: every part runs once", "[io][text]")
{
  std::vector<std::atomic<int>> runs(5);
  clr::runParts(5, [&](size_t i) { ++runs[i]; });
  for (auto& r : runs) CHECK(r == 1);
}

TEST_CASE("text scan: floats are correctly rounded whole words", "[io][text]")
{
  // Words whose float is the one std::from_chars gives (correctly rounded), read to their end.
  std::mt19937 rng(11);
  std::vector<std::string> words = {
      "0",      "-0",           "+1.5",           ".5",    "-.25",          "5.",  "1e-3",
      "1E+10",  "3.4028235e38", "1.17549435e-38", "1e-45", "7.0064923e-46", "0.1", "16777217",
      "-2.5e-7"};
  for (int i = 0; i < 2000; ++i) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", 7 + int(rng() % 3),
                  std::ldexp(double(rng()) / 4294967296.0 - 0.5, int(rng() % 60) - 30));
    words.push_back(buf);
  }
  for (const std::string& w : words) {
    INFO(w);
    for (const char* tail : {"", " ", "\t1", "\r\n", "\n"}) {
      const std::string text = w + tail;
      float got = 42.0f, want = 0.0f;
      const char* end = clr::scanFloat(text.data(), text.data() + text.size(), got);
      REQUIRE(end == text.data() + w.size());
      const char* b = w.data() + (w[0] == '+' ? 1 : 0);
      std::from_chars(b, w.data() + w.size(), want);
      CHECK(std::memcmp(&got, &want, sizeof got) == 0);
    }
  }
  for (const char* bad :
       {"", "+", "-", "+-1", "--1", "1x", "1e", "1.0.0", "inf", "nan", "-inf", "0x10", "1,5", "e5", "#1", "1\f"}) {
    INFO(bad);
    float v = 0.0f;
    CHECK(clr::scanFloat(bad, bad + std::strlen(bad), v) == nullptr);
  }
}

TEST_CASE("text scan: unsigned integers and line ends", "[io][text]")
{
  const std::string text = "123 0\t99999999999999999 007\r\n-1 1.5 1234567890123456789";
  const char* p = text.data();
  const char* end = text.data() + text.size();
  uint64_t v = 0;
  p = clr::scanUnsigned(p, end, v);
  REQUIRE(p);
  CHECK(v == 123);
  p = clr::scanUnsigned(clr::skipBlanks(p, end), end, v);
  REQUIRE(p);
  CHECK(v == 0);
  p = clr::scanUnsigned(clr::skipBlanks(p, end), end, v);
  REQUIRE(p);
  CHECK(v == 99999999999999999u);
  p = clr::scanUnsigned(clr::skipBlanks(p, end), end, v);
  REQUIRE(p);
  CHECK(v == 7);
  const char* next = nullptr;
  CHECK(clr::lineEnd(p, end, &next) == p);
  CHECK(next == p + 2);
  for (const char* bad : {"-1", "1.5", "1234567890123456789", "", "x"}) {
    INFO(bad);
    CHECK(clr::scanUnsigned(bad, bad + std::strlen(bad), v) == nullptr);
  }
  const char* last = nullptr;
  CHECK(clr::lineEnd(text.data() + 30, end, &last) == end);
  CHECK(last == end);
}
