// test_program_cache.cpp — the compiled-program cache (program_cache.h): a
// stored program loads and renders the pixels the source build renders; a
// missing, corrupt, truncated or foreign file is ignored, never an error;
// `clraster cache` stores what render and the library build, and fails on
// bad arguments with one line.
#include "cli_support.h"
#include "pipeline/program_cache.h"
#include "test_support.h"

#include <catch2/catch.hpp>

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
