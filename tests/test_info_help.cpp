// test_info_help.cpp — `clraster info`, --help on every command, and the
// output-name rules (-o is a .png, --aov a .exr, --aov alone renders).
#include "cli_support.h"
#include "test_support.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>

namespace {

using test::expectError;
using test::Run;
using test::run;
using test::slurp;
using test::writeFile;

// An off-centre model with coordinates that %.6g would round: the framing's
// floats need all nine digits to come back.
const std::string kOddObj =
    "v 0.1234567 -0.333333 2.71828\nv 1.4142135 0.1 2.5\nv 0.3 1.7320508 2.9\nv 1.1 1.3 3.14159\n"
    "f 1 2 3\nf 2 4 3\nl 1 4\np 2\n";

// The flags line of `info`'s text report.
std::string flagsLine(const std::string& out)
{
  const std::string head = "default camera (paste into clraster render):\n  ";
  const size_t at = out.find(head);
  REQUIRE(at != std::string::npos);
  const size_t begin = at + head.size();
  return out.substr(begin, out.find('\n', begin) - begin);
}

}  // namespace

TEST_CASE("cli: help and --help on every command print usage and exit 0", "[cli]")
{
  for (const char* args : {"help", "--help", "-h", "render --help", "render -o x.png --help", "devices --help",
                           "cache --help", "info --help", "info -h"}) {
    INFO(args);
    const Run r = run(args);
    CHECK(r.status == 0);
    CHECK(r.out.rfind("usage:\n", 0) == 0);
    CHECK(r.out.find("clraster info MESH") != std::string::npos);
    CHECK(r.err.empty());
  }
  // Without a command: usage on stderr, exit 1.
  const Run none = run("");
  CHECK(none.status == 1);
  CHECK(none.err.rfind("usage:\n", 0) == 0);
  expectError("devices extra", "devices: unexpected argument 'extra'");
  expectError("frobnicate", "unknown command 'frobnicate' (render, info, devices, cache, help)");
}

TEST_CASE("cli: -o must name a .png and --aov a .exr", "[cli]")
{
  const std::string dir = test::tempDir();
  expectError("render -o " + dir + "/x.exr", "-o: '" + dir + "/x.exr' must be a file name ending in .png");
  expectError("render -o " + dir + "/x", "-o: '" + dir + "/x' must be a file name ending in .png");
  expectError("render -o .png", "-o: '.png' must be a file name ending in .png");
  expectError("render -o " + dir + "/x.png --aov " + dir + "/a.png",
              "--aov: '" + dir + "/a.png' must be a file name ending in .exr");
  expectError("render", "missing -o OUT.png (or --aov OUT.exr)");
  expectError("render --views " + dir + "/v.json", "missing -o OUT_%04d.png");
  expectError("render --views " + dir + "/v.json -o " + dir + "/v_%d.jpg", "must be a file name ending in .png");
  // Any case of the extension is the format's.
  const std::string upper = dir + "/upper.PNG";
  std::remove(upper.c_str());
  const Run r = run("render --size 16x16 -o " + upper);
  CHECK(r.status == 0);
  CHECK(slurp(upper).substr(1, 3) == "PNG");
}

TEST_CASE("cli: --aov alone writes the EXR and no PNG", "[cli]")
{
  const std::string dir = test::tempDir();
  const std::string exr = dir + "/alone.exr";
  std::remove(exr.c_str());
  const Run r = run("render --size 32x24 --aov " + exr);
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(slurp(exr).substr(0, 4) == std::string("\x76\x2f\x31\x01", 4));  // OpenEXR magic
  CHECK_FALSE(test::exists(dir + "/alone.png"));
}

TEST_CASE("cli: info reports counts, bounds and flags that reproduce the default picture", "[cli]")
{
  const std::string dir = test::tempDir();
  const std::string obj = writeFile("info-odd.obj", kOddObj);
  // Step 1: the text report.
  const Run info = run("info '" + obj + "'");
  INFO(info.err);
  REQUIRE(info.status == 0);
  CHECK(info.out.find("triangles  2\n") != std::string::npos);
  CHECK(info.out.find("vertices   9\n") != std::string::npos);  // assimp's OBJ reader: one per face corner
  CHECK(info.out.find("lines      1\n") != std::string::npos);
  CHECK(info.out.find("points     1\n") != std::string::npos);
  CHECK(info.out.find("min 0.123456702,-0.333332986,2.5  max 1.41421354,1.73205078,3.14159012") != std::string::npos);
  CHECK(info.out.find("normals    computed (none in file)") != std::string::npos);
  CHECK(info.out.find("uvs        none") != std::string::npos);
  const std::string flags = flagsLine(info.out);
  CHECK(flags.rfind("--eye ", 0) == 0);
  for (const char* f : {" --target ", " --up 0,1,0 ", " --near ", " --far "}) CHECK(flags.find(f) != std::string::npos);
  // Step 2: pasted into render, the flags give the default picture byte for
  // byte, in a lit mode and with the depth format chosen from near and far.
  for (const std::string& mode : {std::string("--shade phong"), std::string("--shade depth --depth auto")}) {
    INFO(mode);
    const std::string a = dir + "/info-default.png", b = dir + "/info-flags.png";
    std::remove(a.c_str());
    std::remove(b.c_str());
    REQUIRE(run("render '" + obj + "' --size 96x64 " + mode + " -o " + a).status == 0);
    REQUIRE(run("render '" + obj + "' --size 96x64 " + mode + " " + flags + " -o " + b).status == 0);
    CHECK(slurp(a).size() > 100);
    CHECK(slurp(a) == slurp(b));
  }
  // Step 3: one JSON object with the same numbers.
  const Run js = run("info '" + obj + "' --json");
  REQUIRE(js.status == 0);
  const nlohmann::json j = nlohmann::json::parse(js.out);
  CHECK(j["triangles"] == 2);
  CHECK(j["vertices"] == 9);
  CHECK(j["lines"] == 1);
  CHECK(j["points"] == 1);
  CHECK(j["render_flags"] == flags);
  CHECK(j["bounds"]["max"][2].get<float>() == 3.14159f);
  CHECK(j["normals"]["in_file"] == false);
  CHECK(j["missing_textures"].empty());
  // Step 4: errors are one line.
  expectError("info", "info: missing MESH");
  expectError("info '" + dir + "/no-such.obj'", "no-such.obj: cannot open");
  expectError("info '" + obj + "' --fov 200", "--fov must lie in (0, 180) degrees");
  expectError("info '" + obj + "' --bogus", "unknown option '--bogus'");
}

TEST_CASE("cli: info names missing textures", "[cli]")
{
  writeFile("info-missing.mtl", "newmtl m\nKd 1 1 1\nmap_Kd no-such-texture.png\n");
  const std::string obj = writeFile("info-missing.obj",
                                    "mtllib info-missing.mtl\nusemtl m\n"
                                    "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                    "f 1/1 2/2 3/3\n");
  const Run r = run("info '" + obj + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("textures 0 loaded, 1 missing") != std::string::npos);
  CHECK(r.out.find("missing texture: " + test::tempDir() + "/no-such-texture.png") != std::string::npos);
  CHECK(r.out.find("uvs        from file") != std::string::npos);
}
