// test_program_cache.cpp — the compiled-program cache (program_cache.h): a
// stored program loads and renders the pixels the source build renders; a
// missing, corrupt, truncated or foreign file is ignored, never an error, and
// so is a swapped binary whose key and checksum were recomputed, or a folder
// or file other users can write;
// `clraster cache` stores what render and the library build, and fails on
// bad arguments with one line.
#include "cli_support.h"
#include "pipeline/program_cache.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <openssl/evp.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <unistd.h>

namespace {

using test::Run;
using test::slurp;

// A cache directory of this test process's own.
std::string cacheDir(const char* name)
{
  const std::string dir = test::tempDir() + "/kcache-" + name + "-" + std::to_string(getpid());
  std::system(("rm -rf '" + dir + "'").c_str());
  return dir;
}

// `clraster ARGS` with CLRASTER_CACHE_DIR=dir ("" disables the cache).
Run runWithCache(const std::string& dir, const std::string& args)
{
  const std::string errPath = test::tempDir() + "/stderr-cache-" + std::to_string(getpid()) + ".txt";
  return test::runShell(
      "CLRASTER_CACHE_DIR='" + dir + "' '" + CLRASTER_BIN + "' " + args + " 2>'" + errPath + "' </dev/null", errPath);
}

void overwrite(const std::string& path, const std::string& bytes)
{
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

}  // namespace

TEST_CASE("program cache: a stored program loads, and damaged or foreign files are misses", "[cache]")
{
  const std::string dir = cacheDir("unit");
  REQUIRE(setenv("CLRASTER_CACHE_DIR", dir.c_str(), 1) == 0);
  const clr::ClContext& ctx = test::context();
  const cl::Device& device = ctx.info.device;
  const std::string options = clr::programOptions(ctx.buildOptions(), false);
  CHECK(!clr::loadCachedProgram(ctx.context, device, options)());  // nothing stored yet
  const std::string path = clr::storeProgramBinary(ctx.program, device, options);
  CHECK(path.rfind(dir + "/", 0) == 0);
  const cl::Program loaded = clr::loadCachedProgram(ctx.context, device, options);
  REQUIRE(loaded());
  CHECK(loaded.getInfo<CL_PROGRAM_KERNEL_NAMES>() == ctx.program.getInfo<CL_PROGRAM_KERNEL_NAMES>());
  // Another build's options are another key, so a miss.
  CHECK(!clr::loadCachedProgram(ctx.context, device, clr::programOptions(ctx.buildOptions(), true))());
  const std::string good = slurp(path);
  REQUIRE(good.size() > 64);
  SECTION("one payload byte flipped")
  {
    std::string bad = good;
    bad[bad.size() / 2] ^= 0x20;
    overwrite(path, bad);
  }
  SECTION("truncated")
  {
    overwrite(path, good.substr(0, good.size() - 100));
  }
  SECTION("header only")
  {
    overwrite(path, good.substr(0, 32));
  }
  SECTION("another key in the header")
  {
    std::string bad = good;
    bad[8] ^= 1;
    overwrite(path, bad);
  }
  SECTION("not a cache file")
  {
    overwrite(path, "ply\nformat ascii 1.0\n");
  }
  CHECK(!clr::loadCachedProgram(ctx.context, device, options)());
  setenv("CLRASTER_CACHE_DIR", "", 1);  // as test_main.cpp leaves it
}

TEST_CASE("program cache: a swapped binary with its key and checksum recomputed is not loaded", "[cache]")
{
  const std::string dir = cacheDir("swap");
  REQUIRE(setenv("CLRASTER_CACHE_DIR", dir.c_str(), 1) == 0);
  clr::ClContext& ctx = test::context();
  const cl::Device& device = ctx.info.device;
  const std::string frame = clr::programOptions(ctx.buildOptions(), false);
  const std::string extras = clr::programOptions(ctx.buildOptions(), true);
  const std::string framePath = clr::storeProgramBinary(ctx.program, device, frame);
  const std::string extrasPath = clr::storeProgramBinary(ctx.extras(), device, extras);
  REQUIRE(clr::loadCachedProgram(ctx.context, device, frame)());
  // The extras binary under the frame program's key: header key and size
  // rewritten, and as its check SHA-256 of key and binary (what anyone who
  // cannot read the folder's secret can compute).
  const std::string other = slurp(extrasPath);
  const std::string key = clr::programCacheKey(device, frame);
  std::string swapped = other;
  swapped.replace(8, 32, key);
  unsigned char digest[32];
  const std::string message = key + other.substr(80);
  EVP_Digest(message.data(), message.size(), digest, nullptr, EVP_sha256(), nullptr);
  swapped.replace(48, 32, std::string(reinterpret_cast<const char*>(digest), 32));
  overwrite(framePath, swapped);
  CHECK(!clr::loadCachedProgram(ctx.context, device, frame)());
  // The same file under another secret (another user's cache) is refused too.
  overwrite(framePath, other.substr(0, 8) + key + other.substr(40));
  CHECK(!clr::loadCachedProgram(ctx.context, device, frame)());
  setenv("CLRASTER_CACHE_DIR", "", 1);
}

TEST_CASE("program cache: a folder or file other users can write is refused", "[cache][cli]")
{
  const std::string dir = cacheDir("perm");
  const Run stored = runWithCache(dir, "cache");
  INFO("stderr: " << stored.err);
  REQUIRE(stored.status == 0);
  struct stat st;
  REQUIRE(stat(dir.c_str(), &st) == 0);
  CHECK((st.st_mode & 0777) == 0700);
  const std::string first = stored.out.substr(0, stored.out.find('\n'));
  REQUIRE(stat(first.c_str(), &st) == 0);
  CHECK((st.st_mode & 0777) == 0600);
  REQUIRE(setenv("CLRASTER_CACHE_DIR", dir.c_str(), 1) == 0);
  const clr::ClContext& ctx = test::context();
  const std::string options = clr::programOptions(ctx.buildOptions(), false);
  const std::string out = test::tempDir() + "/kcache-perm-" + std::to_string(getpid()) + ".png";
  // A group- or world-writable folder, or entry: a miss for the loader, an
  // error for `clraster cache`, and a render that still succeeds.
  REQUIRE(clr::loadCachedProgram(ctx.context, ctx.info.device, options)());
  for (const auto& [path, mode] : {std::pair<std::string, mode_t>{dir, 0770}, {dir, 0707}, {first, 0660}}) {
    INFO(path << " mode " << std::oct << mode);
    REQUIRE(chmod(path.c_str(), mode) == 0);
    CHECK(!clr::loadCachedProgram(ctx.context, ctx.info.device, options)());
    const Run render = runWithCache(dir, "render --size 32x24 -o '" + out + "'");
    CHECK(render.status == 0);
    CHECK(render.err.empty());
    if (path == dir) {
      const Run refused = runWithCache(dir, "cache");
      CHECK(refused.status == 1);
      CHECK(refused.err.find("no other user can write") != std::string::npos);
    }
    REQUIRE(chmod(path.c_str(), path == dir ? 0700 : 0600) == 0);
  }
  CHECK(clr::loadCachedProgram(ctx.context, ctx.info.device, options)());
  setenv("CLRASTER_CACHE_DIR", "", 1);
}

TEST_CASE("program cache: `clraster cache` stores programs that render the same pixels", "[cache][cli]")
{
  const std::string dir = cacheDir("cli");
  const std::string tmp = test::tempDir() + "/kcache-" + std::to_string(getpid());
  const Run stored = runWithCache(dir, "cache");
  INFO("stderr: " << stored.err);
  REQUIRE(stored.status == 0);
  // Four programs: frame and extras, for vertex and clip-space inputs.
  size_t files = 0;
  for (size_t at = 0; (at = stored.out.find(".bin\n", at)) != std::string::npos; at += 5) ++files;
  CHECK(files == 4);
  CHECK(stored.out.rfind(dir + "/", 0) == 0);
  // The default frame, and one that takes the extras program (AOVs and lines).
  for (const bool extras : {false, true}) {
    INFO("extras: " << extras);
    auto render = [&](const std::string& cache, const std::string& name) {
      const std::string out = tmp + "-" + name + (extras ? "-x" : "");
      std::string args = "render --size 160x120 -o '" + out + ".png'";
      if (extras) args += " --wireframe --aov '" + out + ".exr'";
      const Run r = runWithCache(cache, args);
      INFO("stderr: " << r.err);
      REQUIRE(r.status == 0);
      return slurp(out + ".png") + (extras ? slurp(out + ".exr") : "");
    };
    const std::string fromSource = render("", "source");
    CHECK(fromSource.size() > 100);
    CHECK(fromSource == render(dir, "cached"));
  }
  // Every stored file damaged: the render builds from source and still succeeds.
  for (size_t at = 0, end; (end = stored.out.find('\n', at)) != std::string::npos; at = end + 1) {
    const std::string path = stored.out.substr(at, end - at);
    std::string bytes = slurp(path);
    REQUIRE(bytes.size() > 64);
    bytes[bytes.size() / 3] ^= 0x10;
    overwrite(path, bytes);
  }
  const Run damaged = runWithCache(dir, "render --size 160x120 -o '" + tmp + "-damaged.png'");
  CHECK(damaged.status == 0);
  CHECK(damaged.err.empty());
  CHECK(slurp(tmp + "-source.png") == slurp(tmp + "-damaged.png"));
}

TEST_CASE("program cache: bad arguments and an unusable directory fail with one line", "[cache][cli]")
{
  test::expectError("cache --bogus", "cache: unexpected argument '--bogus'");
  test::expectError("cache --device", "cache: unexpected argument '--device'");
  test::expectError("cache --device 99", "--device 99: no such device index");
  // A regular file where the directory should be: `cache` fails, render does not.
  const std::string file = test::writeFile("kcache-not-a-dir", "x");
  const Run r = runWithCache(file + "/sub", "cache");
  CHECK(r.status == 1);
  CHECK(r.err.find("kcache-not-a-dir") != std::string::npos);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  const std::string out = test::tempDir() + "/kcache-render-" + std::to_string(getpid()) + ".png";
  CHECK(runWithCache(file + "/sub", "render --size 32x24 -o '" + out + "'").status == 0);
  const Run none = runWithCache("", "cache");
  CHECK(none.status == 1);
  CHECK(none.err.find("no kernel cache directory") != std::string::npos);
}
