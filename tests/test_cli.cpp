// test_cli.cpp — the command line's error paths and its output guarantees:
// every bad input gets a one-line message naming the problem and a non-zero
// exit, and no failure leaves a half-written or clobbered output file.
#include "cli_support.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <string>

namespace {

using test::expectError;
using test::leftoverTemps;
using test::Run;
using test::run;
using test::slurp;
using test::writeFile;

std::string tmpDir()
{
  return test::tempDir();
}

const std::string kSmallObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n";

// Two triangles; the second indexes vertex 9 of 4.
const char* const kGltfBadIndex =
    "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0, \"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0}], "
    "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0}, \"indices\": 1}]}], \"buffers\": "
    "[{\"byteLength\": 60, \"uri\": "
    "\"data:application/"
    "octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAACAPwAAgD8AAAAAAAABAAIAAQADAAkA\"}], "
    "\"bufferViews\": [{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 48}, {\"buffer\": 0, \"byteOffset\": 48, "
    "\"byteLength\": 12}], \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 4, \"type\": "
    "\"VEC3\", \"min\": [0, 0, 0], \"max\": [1, 1, 0]}, {\"bufferView\": 1, \"componentType\": 5123, \"count\": 6, "
    "\"type\": \"SCALAR\"}]}";

}  // namespace

TEST_CASE("cli: bad flags and values", "[cli]")
{
  const std::string out = " -o '" + tmpDir() + "/flags.png'";
  expectError("render --bogus" + out, "unknown option '--bogus'");
  expectError("frobnicate", "unknown command");
  expectError("render", "missing -o");
  expectError("render -o", "-o: missing value");
  expectError("render --size 0x10" + out, "--size");
  expectError("render --size 100000x10" + out, "--size");
  expectError("render --size 64" + out, "is not WxH");
  expectError("render --size 64xabc" + out, "--size");
  expectError("render --shade fancy" + out, "--shade: unknown value 'fancy'");
  expectError("render --cull front" + out, "--cull: unknown mode");
  expectError("render --filter cubic" + out, "--filter: unknown value 'cubic'");
  expectError("render --light-point 1,2" + out, "--light-point: '1,2' is not x,y,z");
  expectError("render --light-point 1,2,3,0" + out, "--light-point: range r must be > 0");
  expectError("render --light-point 1,2,3,x" + out, "--light-point: 'x' is not a finite number");
  expectError("render --frames 0" + out, "--frames");
  expectError("render --eye 1,2" + out, "--eye");
  expectError("render --eye 1,2,nan" + out, "--eye");
  expectError("render --device 999" + out, "no such device index");
  expectError("render --device no-such-device-name" + out, "no device name matches");
}

TEST_CASE("cli: impossible cameras", "[cli]")
{
  const std::string out = " -o '" + tmpDir() + "/camera.png'";
  expectError("render --fov 0" + out, "--fov");
  expectError("render --fov 180" + out, "--fov");
  expectError("render --fov -5" + out, "--fov");
  expectError("render --near 0" + out, "--near");
  expectError("render --near -1" + out, "--near");
  expectError("render --near 2 --far 1" + out, "--far");
  expectError("render --near 2 --far 2" + out, "--far");
  expectError("render --eye 1,1,1 --target 1,1,1" + out, "--eye and --target");
  expectError("render --eye 0,5,0 --target 0,0,0 --up 0,1,0" + out, "--up");
}

TEST_CASE("cli: bad scene files name the file and the problem", "[cli]")
{
  const std::string out = " -o '" + tmpDir() + "/scene.png'";
  const std::string dir = tmpDir();
  expectError("render '" + dir + "/missing.obj'" + out, "missing.obj: cannot open");
  expectError("render '" + writeFile("empty.obj", "") + "'" + out, "empty.obj: file is empty");
  expectError(
      "render '" + writeFile("garbage.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty banana x\n") + "'" + out,
      "garbage.ply: PLY header line 4: unknown property type 'banana'");
  expectError("render '" + writeFile("noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n") + "'" + out,
              "noend.ply: PLY header has no end_header");
  expectError("render '" +
                  writeFile("truncated.ply",
                            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                            "end_header\n0 0 0\n1 0") +
                  "'" + out,
              "truncated.ply");
  expectError("render '" + writeFile("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1\n") + "'" + out, "points.obj");
  // Assimp's OFF reader would clamp the index with only a log message.
  expectError("render '" + writeFile("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n") + "'" + out,
              "range.off: OFF: Vertex index is out of range");
  expectError("render '" + writeFile("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n") + "'" + out,
              "range.obj: OBJ: vertex index out of range");
  // Assimp's glTF reader would drop the bad face with only a log warning.
  expectError("render '" + writeFile("range.gltf", kGltfBadIndex) + "'" + out, "range.gltf: Some faces had out");
  expectError("render '" +
                  writeFile("nobuffer.gltf", "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":60}]}") +
                  "'" + out,
              "nobuffer.gltf");
  expectError("render '" + writeFile("notamesh.stl", std::string(200, '\x01')) + "'" + out, "notamesh.stl");
  expectError("render '" + dir + "'" + out, dir);
}

TEST_CASE("cli: an unwritable output is reported before anything is rendered", "[cli]")
{
  expectError("render -o /nonexistent-dir/out.png", "/nonexistent-dir/out.png: cannot write");
}

TEST_CASE("cli: a failing run leaves an existing output untouched", "[cli]")
{
  const std::string target = writeFile("keep.png", "previous contents");
  expectError("render '" + tmpDir() + "/missing.obj' -o '" + target + "'", "missing.obj");
  CHECK(slurp(target) == "previous contents");
  CHECK(leftoverTemps(target) == 0);
}

TEST_CASE("cli: renders a file, NaN vertices culled, and reports stats", "[cli]")
{
  const std::string scene = writeFile("nan.obj", kSmallObj + "v nan 0 0\nv 0 inf 0\nf 5 1 2\nf 6 2 3\n");
  const std::string png = tmpDir() + "/nan.png";
  std::remove(png.c_str());
  const Run r = run("render '" + scene + "' -o '" + png + "' --size 64x48 --shade id --stats --frames 2");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.empty());
  const std::string png_bytes = slurp(png);
  CHECK(png_bytes.substr(1, 3) == "PNG");
  CHECK(r.out.find("\"triangles_in\":4") != std::string::npos);
  CHECK(r.out.find("\"triangles_culled\":2") != std::string::npos);
  CHECK(r.out.find("\"frame_ms\":") != std::string::npos);
  CHECK(r.out.find("\"stage_ms\":{") != std::string::npos);
  CHECK(r.out.find("\"device_bytes\":") != std::string::npos);
  CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  CHECK(leftoverTemps(png) == 0);
}

TEST_CASE("cli: devices lists at least one device", "[cli]")
{
  const Run r = run("devices");
  CHECK(r.status == 0);
  CHECK(r.out.find("0: [") == 0);
}
