// test_views.cpp — `clraster render --views`: the views file (good input and
// each kind of bad input, one error line and no output), shard selection,
// output names, frames identical to single-view renders of the same cameras,
// the writer thread, the stats line, and the progress bar (only on a
// terminal).
#include "cli_support.h"
#include "render/frame_writer.h"
#include "test_support.h"
#include "render/views.h"

#include <catch2/catch.hpp>

#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <regex>
#include <string>
#include <vector>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#include <stb/stb_image.h>

using Catch::Matchers::Contains;
using test::expectError;
using test::run;
using test::writeFile;

namespace {

// A unit cube on a ground quad: different cameras see different images.
const char* const kCubeObj =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "v -2 -0.01 -2\nv 3 -0.01 -2\nv 3 -0.01 3\nv -2 -0.01 3\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\nf 9 12 11 10\n";

std::vector<clr::ViewSpec> parse(const std::string& text)
{
  return clr::parseViews("v.json", text, clr::CameraArgs{}, 64, 48);
}

// The message parseViews throws for text ("" when it throws none).
std::string parseError(const std::string& text)
{
  try {
    parse(text);
  } catch (const clr::Error& e) {
    return e.what();
  }
  return "";
}

// A fresh, empty folder under the tests' scratch directory.
std::string freshDir(const std::string& name)
{
  const std::string dir = test::tempDir() + "/" + name;
  REQUIRE(std::system(("rm -rf '" + dir + "' && mkdir -p '" + dir + "'").c_str()) == 0);
  return dir;
}

size_t countFiles(const std::string& dir)
{
  size_t n = 0;
  for (int i = 0; i < 10; ++i) n += test::exists(dir + "/out_" + std::to_string(i) + ".png");
  return n;
}

}  // namespace

TEST_CASE("views: a good file, merged over the command line's values", "[views]")
{
  clr::CameraArgs defaults;
  defaults.fovDegrees = 30.0f;
  defaults.zFar = 50.0f;
  const auto views = clr::parseViews("v.json",
                                     R"({"views": [
      {"eye": [1, 2, 3], "target": [0, 0.5, 0], "up": [0, 0, 1], "fov": 60, "near": 0.25, "far": 9, "size": [32, 16]},
      {},
      {"eye": [-4, 5.5, 6]}
    ]})",
                                     defaults, 64, 48);
  REQUIRE(views.size() == 3);
  CHECK(*views[0].camera.eye == glm::vec3(1, 2, 3));
  CHECK(*views[0].camera.target == glm::vec3(0, 0.5f, 0));
  CHECK(*views[0].camera.up == glm::vec3(0, 0, 1));
  CHECK(views[0].camera.fovDegrees == 60.0f);
  CHECK(*views[0].camera.zNear == 0.25f);
  CHECK(*views[0].camera.zFar == 9.0f);
  CHECK((views[0].width == 32 && views[0].height == 16));
  // Keys left out take the command line's values, or stay unset for framing.
  CHECK(!views[1].camera.eye);
  CHECK(!views[1].camera.zNear);
  CHECK(views[1].camera.fovDegrees == 30.0f);
  CHECK(*views[1].camera.zFar == 50.0f);
  CHECK((views[1].width == 64 && views[1].height == 48));
  CHECK(*views[2].camera.eye == glm::vec3(-4, 5.5f, 6));
  CHECK(!views[2].camera.target);
}

TEST_CASE("views: each kind of bad file names the file, the view and the problem", "[views]")
{
  // Syntax.
  CHECK_THAT(parseError(""), Contains("v.json: parse error at line 1"));
  CHECK_THAT(parseError("{\"views\": [{\"eye\": [1, 2, 3]}\n"), Contains("v.json: parse error at line 2"));
  CHECK_THAT(parseError("{\"views\": [{}],}"), Contains("v.json: parse error"));
  CHECK_THAT(parseError("{\"views\": [{\"eye\": [1, 2, 1e400]}]}"), Contains("v.json: number overflow"));
  CHECK_THAT(parseError("{\"views\": [{}], \"views\": [{}]}"), Contains("v.json: duplicate key \"views\""));
  CHECK_THAT(parseError("{\"views\": [{\"fov\": 40, \"fov\": 50}]}"), Contains("v.json: duplicate key \"fov\""));
  // The top level.
  CHECK(parseError("[1, 2]") == "v.json: must be a JSON object {\"views\": [...]}");
  CHECK(parseError("{}") == "v.json: missing \"views\"");
  CHECK(parseError("{\"view\": []}") == "v.json: unknown key \"view\" (only \"views\")");
  CHECK(parseError("{\"views\": {}}") == "v.json: \"views\" must be an array");
  CHECK(parseError("{\"views\": []}") == "v.json: \"views\" is empty");
  // One view.
  auto viewError = [](const std::string& view) { return parseError("{\"views\": [{}, " + view + "]}"); };
  CHECK(viewError("3") == "v.json: view 1: must be an object {\"eye\": [x, y, z], ...}");
  CHECK(viewError("{\"fovy\": 45}") == "v.json: view 1: unknown key \"fovy\" (eye, target, up, fov, near, far, size)");
  CHECK(viewError("{\"eye\": [1, 2]}") == "v.json: view 1: \"eye\" must be an array of 3 numbers");
  CHECK(viewError("{\"target\": \"0,0,0\"}") == "v.json: view 1: \"target\" must be an array of 3 numbers");
  CHECK(viewError("{\"up\": [0, \"1\", 0]}") == "v.json: view 1: \"up\"[1] must be a number");
  CHECK(viewError("{\"eye\": [0, 0, 1e39]}") == "v.json: view 1: \"eye\"[2] must be a finite number");
  CHECK(viewError("{\"fov\": 180}") == "v.json: view 1: \"fov\" must lie in (0, 180) degrees");
  CHECK(viewError("{\"fov\": 0}") == "v.json: view 1: \"fov\" must lie in (0, 180) degrees");
  CHECK(viewError("{\"fov\": null}") == "v.json: view 1: \"fov\" must be a number");
  CHECK(viewError("{\"near\": 0}") == "v.json: view 1: \"near\" must be > 0");
  CHECK(viewError("{\"far\": -1}") == "v.json: view 1: \"far\" must be > 0");
  CHECK(viewError("{\"near\": 2, \"far\": 2}") == "v.json: view 1: \"far\" must be greater than \"near\"");
  CHECK(viewError("{\"size\": \"64x64\"}") == "v.json: view 1: \"size\" must be [W, H]");
  CHECK(viewError("{\"size\": [64]}") == "v.json: view 1: \"size\" must be [W, H]");
  CHECK(viewError("{\"size\": [0, 64]}") == "v.json: view 1: \"size\"[0] must be an integer in 1..16384");
  CHECK(viewError("{\"size\": [64, 16385]}") == "v.json: view 1: \"size\"[1] must be an integer in 1..16384");
  CHECK(viewError("{\"size\": [64.5, 64]}") == "v.json: view 1: \"size\"[0] must be an integer in 1..16384");
  // Cameras only the scene's bounds make impossible.
  clr::Bounds bounds;
  bounds.min = glm::vec3(0.0f);
  bounds.max = glm::vec3(1.0f);
  bounds.empty = false;
  auto frameError = [&](const std::string& view) {
    try {
      clr::frameViews("v.json", parse("{\"views\": [{}, " + view + "]}"), bounds);
    } catch (const clr::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(frameError("{\"eye\": [1, 1, 1], \"target\": [1, 1, 1]}") == "v.json: view 1: eye and target must differ");
  CHECK(frameError("{\"eye\": [0, 5, 0], \"target\": [0, 0, 0]}") ==
        "v.json: view 1: up must not be parallel to the view direction");
  CHECK(frameError("{\"near\": 1000}") == "v.json: view 1: far must be greater than near");
  CHECK(frameError("{\"eye\": [3, 2, 1]}").empty());
}

TEST_CASE("views: a file of many views parses in one pass up to the named limit", "[views]")
{
  // kMaxViews empty views parse (a parser quadratic in the count takes hours
  // on this many); one more is refused while parsing, naming the limit.
  auto views = [](size_t n) {
    std::string text = "{\"views\": [";
    text.reserve(text.size() + 3 * n + 2);
    for (size_t i = 0; i < n; ++i) text += i ? ",{}" : "{}";
    return text + "]}";
  };
  CHECK(parse(views(clr::kMaxViews)).size() == clr::kMaxViews);
  CHECK(parseError(views(clr::kMaxViews + 1)) ==
        "v.json: more than " + std::to_string(clr::kMaxViews) + " views (the limit of a views file)");
  // Any value counts as a view (a scalar is refused later as not an object).
  std::string scalars = "{\"views\": [1";
  for (size_t i = 0; i < clr::kMaxViews; ++i) scalars += ",1";
  CHECK_THAT(parseError(scalars + "]}"), Contains("views (the limit of a views file)"));
  CHECK(parseError("{\"views\": [{}, {\"eye\": [1, 2, 3], \"eye\": [1, 2, 3]}]}") == "v.json: duplicate key \"eye\"");
}

TEST_CASE("views: a bad views file is one error line and writes no output", "[views]")
{
  const std::string dir = freshDir("views-bad");
  const std::string scene = writeFile("views-cube.obj", kCubeObj);
  auto expectNothingWritten = [&](const std::string& views, const std::string& needle) {
    const std::string path = writeFile("views-bad.json", views);
    expectError("render '" + scene + "' --views '" + path + "' -o '" + dir + "/out_%d.png' --size 16x16", needle);
    CHECK(countFiles(dir) == 0);
  };
  expectNothingWritten("", "views-bad.json: file is empty");
  expectNothingWritten("{\"views\": [{}, {}", "views-bad.json: parse error at line 1");
  // Views 0 and 1 are good; view 2 fails when parsed, or when framed.
  expectNothingWritten("{\"views\": [{}, {}, {\"eye\": 5}]}", "views-bad.json: view 2: \"eye\" must be an array");
  expectNothingWritten("{\"views\": [{}, {}, {\"eye\": [0.5, 0.5, 0.5], \"target\": [0.5, 0.5, 0.5]}]}",
                       "views-bad.json: view 2: eye and target must differ");
  // Found from the file alone, before any device work (checkViewCameras): a
  // device that does not exist as well is not the error reported.
  const std::string sameEye =
      writeFile("views-same-eye.json", "{\"views\": [{}, {\"eye\": [1, 1, 1], \"target\": [1, 1, 1]}]}");
  const test::Run r = expectError("render '" + scene + "' --views '" + sameEye + "' -o '" + dir +
                                      "/out_%d.png' --size 16x16 --device no-such-device-anywhere",
                                  "views-same-eye.json: view 1: eye and target must differ");
  CHECK(r.err.find("--device") == std::string::npos);
  // Found only by framing on the scene (the default eye lies on (0.55, 0.45, 1) from the target).
  expectNothingWritten("{\"views\": [{}, {}, {\"target\": [0, 0, 0], \"up\": [0.55, 0.45, 1]}]}",
                       "views-bad.json: view 2: up must not be parallel");
  expectError("render --views '" + dir + "/missing.json' -o '" + dir + "/out_%d.png'", "missing.json: cannot open");
  CHECK(countFiles(dir) == 0);
  // An unwritable output folder is found before rendering.
  const std::string good = writeFile("views-good.json", "{\"views\": [{}, {}]}");
  expectError("render --views '" + good + "' -o /nonexistent-dir/out_%d.png",
              "/nonexistent-dir/out_0.png: cannot write");
}

TEST_CASE("views: --shard K/N selects every N-th view from K", "[views]")
{
  // Selection.
  using V = std::vector<size_t>;
  CHECK(clr::shardViews(7, clr::Shard{0, 1}) == V{0, 1, 2, 3, 4, 5, 6});
  CHECK(clr::shardViews(7, clr::Shard{0, 3}) == V{0, 3, 6});
  CHECK(clr::shardViews(7, clr::Shard{1, 3}) == V{1, 4});
  CHECK(clr::shardViews(7, clr::Shard{2, 3}) == V{2, 5});
  CHECK(clr::shardViews(3, clr::Shard{4, 8}) == V{});
  CHECK(clr::shardViews(1, clr::Shard{0, 8}) == V{0});
  // Every view exactly once over all shards.
  for (uint32_t n = 1; n <= 6; ++n) {
    std::vector<size_t> all;
    for (uint32_t k = 0; k < n; ++k)
      for (size_t v : clr::shardViews(10, clr::Shard{k, n})) all.push_back(v);
    std::sort(all.begin(), all.end());
    CHECK(all == V{0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  }
  // Parsing.
  CHECK(clr::parseShard("2/5").index == 2);
  CHECK(clr::parseShard("2/5").count == 5);
  CHECK(clr::parseShard("0/1").count == 1);
  CHECK_THROWS_WITH(clr::parseShard("5/5"), Contains("--shard: K must be less than N"));
  CHECK_THROWS_WITH(clr::parseShard("3"), Contains("--shard: '3' is not K/N"));
  CHECK_THROWS_WITH(clr::parseShard("-1/4"), Contains("--shard K: '-1'"));
  CHECK_THROWS_WITH(clr::parseShard("x/4"), Contains("--shard K: 'x'"));
  CHECK_THROWS_WITH(clr::parseShard("1/0"), Contains("--shard N: '0'"));
  CHECK_THROWS_WITH(clr::parseShard("1/"), Contains("--shard N: ''"));
  CHECK_THROWS_WITH(clr::parseShard("1/2/3"), Contains("--shard N: '2/3'"));
  const std::string views = writeFile("views-shard.json", "{\"views\": [{}, {}, {}, {}, {}]}");
  expectError("render --views '" + views + "' -o out_%d.png --shard 3/3", "--shard: K must be less than N");
  expectError("render -o out.png --shard 0/2", "--shard needs --views");

  // End to end: shard 1/3 of 5 views writes views 1 and 4 under their global indices.
  const std::string dir = freshDir("views-shard");
  const test::Run r = run("render '" + writeFile("views-cube.obj", kCubeObj) + "' --views '" + views + "' -o '" + dir +
                          "/out_%d.png' --size 16x16 --shard 1/3");
  INFO(r.err);
  REQUIRE(r.status == 0);
  for (int v = 0; v < 5; ++v) CHECK(test::exists(dir + "/out_" + std::to_string(v) + ".png") == (v == 1 || v == 4));
}

TEST_CASE("views: output names come from a pattern with one integer conversion", "[views]")
{
  CHECK(clr::outputName("out_%04d.png", 7) == "out_0007.png");
  CHECK(clr::outputName("out_%d.png", 1234) == "out_1234.png");
  CHECK(clr::outputName("frames/%u-%%.png", 3) == "frames/3-%.png");
  CHECK(clr::outputName("%06i", 42) == "000042");
  CHECK_NOTHROW(clr::checkOutputPattern("out_%04d.png"));
  CHECK_NOTHROW(clr::checkOutputPattern("%%%d%%"));
  CHECK_NOTHROW(clr::checkOutputPattern("a%-5.3u"));
  CHECK_THROWS_WITH(clr::checkOutputPattern("out.png"), Contains("needs exactly one integer conversion"));
  CHECK_THROWS_WITH(clr::checkOutputPattern("out_%%d.png"), Contains("needs exactly one integer conversion"));
  CHECK_THROWS_WITH(clr::checkOutputPattern("%d_%d.png"), Contains("needs exactly one integer conversion"));
  CHECK_THROWS_WITH(clr::checkOutputPattern("%s_%d.png"), Contains("a conversion other than %d, %i or %u"));
  CHECK_THROWS_WITH(clr::checkOutputPattern("%ld.png"), Contains("a conversion other than %d, %i or %u"));
  CHECK_THROWS_WITH(clr::checkOutputPattern("%d%"), Contains("a conversion other than %d, %i or %u"));
  CHECK_THROWS_WITH(clr::checkOutputPattern("%n%d"), Contains("a conversion other than %d, %i or %u"));
  const std::string views = writeFile("views-names.json", "{\"views\": [{}]}");
  expectError("render --views '" + views + "' -o out.png", "-o: with --views, 'out.png' needs exactly one integer");
  expectError("render --views '" + views + "' -o out_%s.png", "-o: 'out_%s.png' has a conversion other than");
  expectError("render --views '" + views + "' -o out_%d.png --frames 3", "--frames cannot be combined with --views");
}

TEST_CASE("views: every frame equals a single-view render of the same camera", "[views]")
{
  // Step 1: four cameras (framed, explicit, own size and fov, own planes), one run.
  const std::string dir = freshDir("views-equal");
  const std::string scene = writeFile("views-cube.obj", kCubeObj);
  const std::string views = writeFile("views-equal.json", R"({"views": [
    {},
    {"eye": [2.5, 1.5, 3], "target": [0.5, 0.5, 0.5]},
    {"eye": [-2, 3, -1.5], "up": [0, 1, 0], "fov": 60, "size": [48, 32]},
    {"eye": [0.5, 0.5, 4], "near": 0.5, "far": 10, "fov": 30}
  ]})");
  const std::vector<std::string> single = {"--size 64x64", "--size 64x64 --eye 2.5,1.5,3 --target 0.5,0.5,0.5",
                                           "--size 48x32 --eye -2,3,-1.5 --up 0,1,0 --fov 60",
                                           "--size 64x64 --eye 0.5,0.5,4 --near 0.5 --far 10 --fov 30"};
  const test::Run all =
      run("render '" + scene + "' --views '" + views + "' -o '" + dir + "/out_%d.png' --size 64x64 --cull back");
  INFO(all.err);
  REQUIRE(all.status == 0);

  // Step 2: each view alone, compared pixel for pixel (and byte for byte).
  std::vector<std::string> images;
  for (size_t v = 0; v < single.size(); ++v) {
    const std::string alone = dir + "/alone_" + std::to_string(v) + ".png";
    const std::string many = dir + "/out_" + std::to_string(v) + ".png";
    const test::Run r = run("render '" + scene + "' -o '" + alone + "' " + single[v] + " --cull back");
    INFO("view " << v << ": " << r.err);
    REQUIRE(r.status == 0);
    int w[2], h[2], c[2];
    unsigned char* a = stbi_load(alone.c_str(), &w[0], &h[0], &c[0], 3);
    unsigned char* b = stbi_load(many.c_str(), &w[1], &h[1], &c[1], 3);
    REQUIRE(a);
    REQUIRE(b);
    CHECK(w[0] == w[1]);
    CHECK(h[0] == h[1]);
    CHECK(w[1] == (v == 2 ? 48 : 64));
    if (w[0] == w[1] && h[0] == h[1]) {
      const std::string pa(reinterpret_cast<char*>(a), size_t(w[0]) * h[0] * 3);
      const std::string pb(reinterpret_cast<char*>(b), size_t(w[1]) * h[1] * 3);
      CHECK(pa == pb);
      images.push_back(pb);
      // Not trivially equal: the cube covers some pixels, not all.
      CHECK(std::count(pb.begin(), pb.end(), pb[0]) < std::ptrdiff_t(pb.size()));
    }
    CHECK(test::slurp(alone) == test::slurp(many));
    stbi_image_free(a);
    stbi_image_free(b);
  }
  // The cameras really differ.
  REQUIRE(images.size() == 4);
  CHECK(images[0] != images[1]);
  CHECK(images[1] != images[3]);
  CHECK(test::leftoverTemps(dir + "/out_0.png") == 0);
}

TEST_CASE("views: --stats prints one JSON line for the run", "[views]")
{
  const std::string dir = freshDir("views-stats");
  const std::string views = writeFile("views-stats.json", "{\"views\": [{}, {}, {}, {}, {}]}");
  const test::Run r = run("render '" + writeFile("views-cube.obj", kCubeObj) + "' --views '" + views + "' -o '" + dir +
                          "/out_%d.png' --size 32x32 --shard 0/2 --stats");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.empty());
  CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  CHECK_THAT(r.out, Contains("\"views\":5,\"shard\":\"0/2\",\"frames\":3,"));
  CHECK_THAT(r.out, Contains("\"total_ms\":"));
  CHECK_THAT(r.out, Contains("\"frame_ms\":"));
  // The scene's upload is reported on its own, and is part of the start-up.
  std::smatch m;
  REQUIRE(std::regex_search(r.out, m, std::regex("\"startup_ms\":([0-9.]+),\"prepare_ms\":([0-9.]+),")));
  CHECK(std::stod(m[2].str()) > 0.0);
  CHECK(std::stod(m[2].str()) <= std::stod(m[1].str()));
  CHECK_THAT(r.out, Contains("\"write_ms\":"));
  // The run's split, as one view's (cli.md, "Statistics").
  for (const char* key : {"read_ms", "parse_ms", "build_ms", "encode_ms", "command_ms"})
    CHECK_THAT(r.out, Contains(std::string("\"") + key + "\":"));
  CHECK(countFiles(dir) == 3);
}

TEST_CASE("views: the writer thread reports a failed write", "[views]")
{
  clr::FrameWriter writer(1);
  writer.push(clr::Frame{"/nonexistent-dir/a.png", 1, 1, {0u}});
  CHECK_THROWS_WITH(writer.finish(), Contains("/nonexistent-dir/a.png: cannot write"));
}

TEST_CASE("views: the progress bar shows on a terminal only", "[views]")
{
  // The line itself.
  CHECK(clr::progressLine(0, 100, 0.0) == "[........................] 0/100 frames  0.0 frames/s  ETA --:--");
  CHECK(clr::progressLine(25, 100, 5.0) == "[######..................] 25/100 frames  5.0 frames/s  ETA 0:15");
  CHECK(clr::progressLine(100, 100, 4.0) == "[########################] 100/100 frames  25.0 frames/s  ETA 0:00");
  CHECK(clr::progressLine(1, 10000, 1.0) == "[........................] 1/10000 frames  1.0 frames/s  ETA 2:46:39");

  const std::string dir = freshDir("views-progress");
  const std::string scene = writeFile("views-cube.obj", kCubeObj);
  const std::string views = writeFile("views-progress.json", "{\"views\": [{}, {}, {}]}");
  const std::string args = "render '" + scene + "' --views '" + views + "' -o '" + dir + "/out_%d.png' --size 16x16";

  // Stderr to a file: nothing at all on it.
  const test::Run quiet = run(args);
  CHECK(quiet.status == 0);
  CHECK(quiet.err.empty());

  // Stderr on a pseudo-terminal: the bar, ending at 3/3 and a newline. A
  // machine without pseudo-terminals (a chroot or container without
  // /dev/pts) cannot show this half; the test says so and checks the rest.
  int master = -1, slave = -1;
  if (openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) {
    WARN("no pseudo-terminal available (openpty failed): the terminal half of this test did not run");
    return;
  }
  const std::string command = std::string("exec '") + CLRASTER_BIN + "' " + args + " >/dev/null </dev/null";
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    close(master);
    dup2(slave, STDERR_FILENO);
    close(slave);
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  close(slave);
  std::string tty;
  char buf[4096];
  for (;;) {
    const ssize_t n = read(master, buf, sizeof buf);
    if (n > 0) tty.append(buf, size_t(n));
    if (n == 0 || (n < 0 && errno != EINTR)) break;  // EIO once the child has exited
  }
  close(master);
  int status = 0;
  waitpid(pid, &status, 0);
  INFO(tty);
  CHECK((WIFEXITED(status) && WEXITSTATUS(status) == 0));
  CHECK_THAT(tty, Contains("\r[........................] 0/3 frames"));
  CHECK_THAT(tty, Contains("\r[########################] 3/3 frames"));
  CHECK_THAT(tty, Contains("frames/s  ETA 0:00"));
  CHECK(tty.find('\n') == tty.size() - 1);
}
