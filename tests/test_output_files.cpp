// test_output_files.cpp — what output files look like from outside: they
// are created with the process's umask (a private render stays private),
// SIGINT, SIGTERM or SIGHUP during a run leave no temporary file beside
// them, and a PNG, small or large (deflated on two threads), holds the
// image's pixels under a strict reader (zlib checks the stream's Adler-32).
#include "cli_support.h"
#include "test_support.h"

#include "base/temp_files.h"
#include "io/image_io.h"

#include <catch2/catch.hpp>

#include <csignal>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

unsigned modeOf(const std::string& path)
{
  struct stat st;
  REQUIRE(stat(path.c_str(), &st) == 0);
  return unsigned(st.st_mode & 07777);
}

std::string freshDir(const std::string& name)
{
  const std::string dir = test::tempDir() + "/" + name;
  REQUIRE(std::system(("rm -rf '" + dir + "' && mkdir -p '" + dir + "'").c_str()) == 0);
  return dir;
}

// The RGB rows of a PNG (8-bit RGB, any row filters), read strictly:
// chunk CRCs, one zlib stream with its Adler-32, exactly the rows' bytes.
std::vector<unsigned char> pngRows(const std::vector<unsigned char>& png, uint32_t& width, uint32_t& height)
{
  auto be32 = [&](size_t at) {
    return uint32_t(png[at]) << 24 | uint32_t(png[at + 1]) << 16 | uint32_t(png[at + 2]) << 8 | png[at + 3];
  };
  REQUIRE(png.size() > 8);
  std::vector<unsigned char> idat;
  for (size_t at = 8; at + 12 <= png.size();) {
    const uint32_t n = be32(at);
    REQUIRE(at + 12 + n <= png.size());
    const std::string kind(png.begin() + at + 4, png.begin() + at + 8);
    CHECK(crc32(0, &png[at + 4], n + 4) == be32(at + 8 + n));
    if (kind == "IHDR") {
      width = be32(at + 8);
      height = be32(at + 12);
      REQUIRE(png[at + 16] == 8);  // bit depth
      REQUIRE(png[at + 17] == 2);  // RGB
    }
    if (kind == "IDAT") idat.insert(idat.end(), png.begin() + at + 8, png.begin() + at + 8 + n);
    at += 12 + n;
  }
  const size_t stride = 3 * size_t(width);
  std::vector<unsigned char> raw(height * (stride + 1) + 1);
  uLongf rawSize = raw.size();
  REQUIRE(uncompress(raw.data(), &rawSize, idat.data(), idat.size()) == Z_OK);
  REQUIRE(rawSize == height * (stride + 1));
  std::vector<unsigned char> rows(height * stride);
  for (uint32_t y = 0; y < height; ++y) {
    const unsigned char filter = raw[y * (stride + 1)];
    REQUIRE(filter <= 4);
    for (size_t x = 0; x < stride; ++x) {
      const int a = x >= 3 ? rows[y * stride + x - 3] : 0, b = y ? rows[(y - 1) * stride + x] : 0;
      const int c = x >= 3 && y ? rows[(y - 1) * stride + x - 3] : 0;
      const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
      const int predicted[] = {0, a, b, (a + b) / 2, pa <= pb && pa <= pc ? a : pb <= pc ? b : c};
      rows[y * stride + x] = static_cast<unsigned char>(raw[y * (stride + 1) + 1 + x] + predicted[filter]);
    }
  }
  return rows;
}

}  // namespace

TEST_CASE("outputs: a PNG holds the image's pixels small or large", "[outputs]")
{
  // 64x48 is deflated in one piece, 1200x700 (2.5 MB of rows) in two halves on two threads.
  for (const auto& [w, h] : {std::pair<uint32_t, uint32_t>{64, 48}, {1200, 700}}) {
    INFO(w << "x" << h);
    std::vector<uint32_t> rgba(size_t(w) * h);
    uint32_t state = 46;
    for (size_t i = 0; i < rgba.size(); ++i) {
      state = state * 1664525u + 1013904223u;  // a smooth gradient with noise: matches and literals
      rgba[i] = (i % w) * 255 / w | ((i / w) * 255 / h) << 8 | (state >> 28) << 16 | 0xFF000000u;
    }
    uint32_t width = 0, height = 0;
    const std::vector<unsigned char> rows = pngRows(clr::encodePng("test.png", w, h, rgba.data()), width, height);
    REQUIRE(width == w);
    REQUIRE(height == h);
    size_t differ = 0;
    for (size_t i = 0; i < rgba.size(); ++i)
      for (int c = 0; c < 3; ++c) differ += rows[3 * i + c] != ((rgba[i] >> (8 * c)) & 0xFF);
    CHECK(differ == 0);
  }
}

TEST_CASE("outputs: files are created with the process's umask", "[outputs]")
{
  const std::string dir = freshDir("umask");
  for (const auto& [mask, want] : {std::pair<const char*, unsigned>{"077", 0600}, {"027", 0640}, {"022", 0644}}) {
    const std::string png = dir + "/u" + mask + ".png", exr = dir + "/u" + mask + ".exr";
    const test::Run r = test::runShell(std::string("umask ") + mask + "; '" + CLRASTER_BIN + "' render -o '" + png +
                                           "' --aov '" + exr + "' --size 8x8 2>'" + dir + "/err.txt'",
                                       dir + "/err.txt");
    INFO("umask " << mask << ": " << r.err);
    REQUIRE(r.status == 0);
    CHECK(modeOf(png) == want);
    CHECK(modeOf(exr) == want);
  }
}

TEST_CASE("outputs: a listed temporary file is removed by SIGINT SIGTERM and SIGHUP", "[outputs]")
{
  const std::string dir = freshDir("signals-unit");
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    const std::string target = dir + "/out" + std::to_string(sig) + ".png";
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {  // the default actions (as a program starts), a listed file, the signal
      for (int s : {SIGINT, SIGTERM, SIGHUP}) signal(s, SIG_DFL);
      clr::LiveTemp temp(target);
      if (test::leftoverTemps(target) != 1) _exit(3);
      raise(sig);
      _exit(0);  // not reached: the handler re-raises with the default action
    }
    int status = 0;
    REQUIRE(waitpid(child, &status, 0) == child);
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == sig);
    CHECK(test::leftoverTemps(target) == 0);
  }
}

TEST_CASE("outputs: a views run ended by a signal leaves no temporary file", "[outputs]")
{
  const std::string dir = freshDir("signals-views");
  std::string views = "{\"views\": [{}";
  for (int i = 1; i < 400; ++i) views += ", {\"eye\": [" + std::to_string(1 + i % 7) + ", 2, 3]}";
  const std::string viewsPath = test::writeFile("signals-views.json", views + "]}");
  int ended = 0;
  for (int round = 0; round < 6; ++round) {
    const int sig = (int[]){SIGINT, SIGTERM, SIGHUP}[round % 3];
    const std::string first = dir + "/v" + std::to_string(round) + "_0000.png";
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      for (int s : {SIGINT, SIGTERM, SIGHUP}) signal(s, SIG_DFL);
      const int devnull = open("/dev/null", O_WRONLY);
      dup2(devnull, 2);
      const std::string out = dir + "/v" + std::to_string(round) + "_%04d.png";
      execl(CLRASTER_BIN, CLRASTER_BIN, "render", "--views", viewsPath.c_str(), "-o", out.c_str(), "--size", "96x96",
            static_cast<char*>(nullptr));
      _exit(127);
    }
    // The signal once the first frame is written (or after a bounded wait).
    for (int i = 0; i < 4000 && !test::exists(first); ++i) usleep(5000);
    kill(child, sig);
    int status = 0;
    REQUIRE(waitpid(child, &status, 0) == child);
    ended += WIFSIGNALED(status) && WTERMSIG(status) == sig;
  }
  INFO("runs ended by their signal: " << ended);
  CHECK(ended > 0);
  const test::Run left = test::runShell("ls '" + dir + "' | grep -c 'tmp-' ; true", dir + "/none");
  CHECK(left.out == "0\n");
}

TEST_CASE("outputs: --aov or a PNG past an address-space limit is refused naming the size", "[outputs][rlimit]")
{
  // 4096x4096 visibility planes take about 2.7 GB of host memory beyond the
  // frame: under a 1.5 GB address-space limit, one error line, no output.
  const std::string dir = freshDir("aov-limit");
  const test::Run r = test::runShell("ulimit -v 1500000; '" + std::string(CLRASTER_BIN) + "' render -o '" + dir +
                                         "/a.png' --aov '" + dir + "/a.exr' --size 4096x4096 2>'" + dir + "/err.txt'",
                                     dir + "/err.txt");
  INFO("stderr: " << r.err);
  CHECK(r.status == 1);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.find(" bytes (") != std::string::npos);
  CHECK(r.err.find("RLIMIT_AS") != std::string::npos);
  CHECK(!test::exists(dir + "/a.png"));
  CHECK(!test::exists(dir + "/a.exr"));
  // A frame whose device buffers or PNG encoding do not fit a 1 GB limit
  // (stb's encoder failed without a size before).
  const test::Run png = test::runShell("ulimit -v 1000000; '" + std::string(CLRASTER_BIN) + "' render -o '" + dir +
                                           "/b.png' --size 8192x8192 2>'" + dir + "/err.txt'",
                                       dir + "/err.txt");
  INFO("stderr: " << png.err);
  CHECK(png.status == 1);
  CHECK(png.err.find(" bytes (") != std::string::npos);
  CHECK(!test::exists(dir + "/b.png"));
}
