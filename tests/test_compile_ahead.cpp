// test_compile_ahead.cpp — the helper process that compiles kernels ahead
// (host/compile_ahead.h). Its launches on an empty frame are valid on any
// device (and under Oclgrind); a pipeline whose context has a helper gets
// the kernels it asked for from it and draws the pixels of one without; and
// a helper that cannot start, fails or hangs changes nothing but the time.
// Nothing here times anything: a helper's gain is the bench's cold start
// (bench/run.sh).
#include "camera.h"
#include "cli_support.h"
#include "compile_ahead.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <set>
#include <sys/stat.h>

namespace {

// The built-in scene at 96×64, lambert (the lean resolve kernel), on a
// fresh pipeline of cl.
std::vector<uint32_t> defaultFrame(clr::ClContext& cl)
{
  const clr::Mesh mesh = clr::defaultScene();
  clr::Pipeline pipeline(cl);
  pipeline.uploadScene(mesh);
  const clr::Camera camera = clr::frameCamera(clr::CameraArgs{}, clr::meshBounds(mesh));
  const clr::FrameSettings settings = camera.frameSettings(96, 64, CLR_SHADE_LAMBERT);
  std::vector<uint32_t> image;
  pipeline.render(settings, image);
  return image;
}

// A context with a helper for `kernels` run from `executable`, kept even
// when the program build finds PoCL's cache warm.
clr::CompileAheadRequest request(const std::string& executable, std::vector<std::string> kernels)
{
  clr::CompileAheadRequest r{executable, std::move(kernels)};
  r.warmBuildMs = 0;
  return r;
}

}  // namespace

TEST_CASE("compile-ahead launches each kernel it knows on an empty frame", "[compile-ahead][launch]")
{
  static std::vector<std::string> ran;
  ran.clear();
  const std::vector<std::string> kernels = {"scan_chunks", "raster", "resolve_lambert", "resolve"};
  REQUIRE_NOTHROW(
      clr::compileKernelsAhead(test::context(), kernels, [](const std::string& name) { ran.push_back(name); }));
  CHECK(ran == kernels);
  // A kernel it does not know the arguments of is an error, not a guess.
  CHECK_THROWS_WITH(clr::compileKernelsAhead(test::context(), {"setup_triangles"}),
                    Catch::Contains("'setup_triangles' is not"));
}

TEST_CASE("a context's helper compiles the kernels it was asked for and the pixels stay the same",
          "[compile-ahead][helper]")
{
  const std::vector<uint32_t> expected = defaultFrame(test::context());
  clr::ClContext cl(test::deviceSelector(), 16, request(CLRASTER_BIN, {"scan_chunks", "resolve_lambert"}));
  if (!clr::CompileAhead::worthwhile(cl.info, 16)) {
    CHECK(cl.compileAhead.state() == clr::CompileAhead::State::off);
    WARN("no helper on " << cl.info.name << " (not PoCL's CPU device, or fewer than two cores)");
    return;
  }
  REQUIRE(cl.compileAhead.state() == clr::CompileAhead::State::running);
  CHECK(defaultFrame(cl) == expected);
  // The frame awaited each kernel before its first launch, and the helper ran both.
  CHECK(cl.compileAhead.awaited() == std::set<std::string>{"scan_chunks", "resolve_lambert"});
  CHECK(cl.compileAhead.ready() == std::set<std::string>{"scan_chunks", "resolve_lambert"});
  const clr::CompileAhead::State state = cl.compileAhead.state();
  CHECK((state == clr::CompileAhead::State::running || state == clr::CompileAhead::State::succeeded));
}

TEST_CASE("a helper that cannot start, fails or hangs changes nothing but the time", "[compile-ahead][helper]")
{
  const std::vector<uint32_t> expected = defaultFrame(test::context());
  if (!clr::CompileAhead::worthwhile(test::context().info, 16)) {
    WARN("no helper on " << test::context().info.name);
    return;
  }
  SECTION("no such executable")
  {
    clr::ClContext cl(test::deviceSelector(), 16, request(test::tempDir() + "/no-such-clraster", {"resolve_lambert"}));
    CHECK(cl.compileAhead.state() == clr::CompileAhead::State::failed);
    CHECK(defaultFrame(cl) == expected);
  }
  SECTION("a helper that fails")
  {
    clr::ClContext cl(test::deviceSelector(), 16, request("/bin/false", {"scan_chunks", "resolve_lambert"}));
    CHECK(defaultFrame(cl) == expected);
    CHECK(cl.compileAhead.state() == clr::CompileAhead::State::failed);
    CHECK(cl.compileAhead.ready().empty());
  }
  SECTION("a helper that hangs is stopped")
  {
    // (its wait is bounded by the context's own build time and half a second)
    const std::string hang = test::writeFile("hanging-helper.sh", "#!/bin/sh\nexec sleep 60\n");
    REQUIRE(chmod(hang.c_str(), 0755) == 0);
    clr::ClContext cl(test::deviceSelector(), 16, request(hang, {"scan_chunks", "resolve_lambert"}));
    CHECK(defaultFrame(cl) == expected);
    CHECK(cl.compileAhead.state() == clr::CompileAhead::State::stopped);
  }
}

TEST_CASE("cli: the compile-ahead helper's command checks its arguments", "[cli][compile-ahead]")
{
  test::expectError("__compile-ahead", "usage: clraster __compile-ahead");
  test::expectError("__compile-ahead --device 0 --lanes 16 setup_triangles", "'setup_triangles' is not");
}

TEST_CASE("cli: a render draws the same image with and without its helper", "[cli][compile-ahead]")
{
  const std::string with = test::tempDir() + "/ahead-on.png", without = test::tempDir() + "/ahead-off.png";
  REQUIRE(test::run("render -o '" + with + "' --size 96x64").status == 0);
  REQUIRE(setenv("CLRASTER_COMPILE_AHEAD", "0", 1) == 0);
  const int status = test::run("render -o '" + without + "' --size 96x64").status;
  unsetenv("CLRASTER_COMPILE_AHEAD");
  REQUIRE(status == 0);
  CHECK(test::slurp(with) == test::slurp(without));
}
