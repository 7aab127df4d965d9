// test_cli.cpp — the command line's error paths and its output guarantees:
// every bad input gets a one-line message naming the problem and a non-zero
// exit, and no failure leaves a half-written or clobbered output file.
#include "cli_support.h"
#include "test_support.h"

#include <catch2/catch.hpp>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
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

// kGltfBadIndex with its last index in range: a valid file, and the base of
// the malformed variants below.
std::string validGltf()
{
  std::string g = kGltfBadIndex;
  g.replace(g.find("ADAAkA"), 6, "ADAAIA");
  return g;
}

// validGltf() with the first `from` replaced by `to`.
std::string gltfWith(const std::string& from, const std::string& to)
{
  std::string g = validGltf();
  const size_t at = g.find(from);
  REQUIRE(at != std::string::npos);
  return g.replace(at, from.size(), to);
}

// A malformed scene file: `clraster render` fails with one line naming the
// file and `needle`, and creates no output.
void expectSceneError(const std::string& name, const std::string& content, const std::string& needle)
{
  const std::string png = tmpDir() + "/hostile-" + name + ".png";
  std::remove(png.c_str());
  const std::string path = writeFile(name, content);
  const Run r = expectError("render '" + path + "' -o '" + png + "' --size 32x32", needle);
  CHECK(r.err.rfind(std::string("clraster: ") + path + ": ", 0) == 0);
  struct stat st;
  CHECK(stat(png.c_str(), &st) != 0);
  CHECK(leftoverTemps(png) == 0);
}

const std::string kPlyHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face "
    "1\nproperty list uchar int vertex_indices\nend_header\n";

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
  // Each is found from the arguments alone (checkCameraArgs), before any
  // device work: with a device that does not exist as well, the camera's
  // error is the one reported. A camera that only the scene's framing makes
  // impossible is found after the build.
  const std::string out = " -o '" + tmpDir() + "/camera.png'";
  for (const std::string device : {"", " --device no-such-device-anywhere"}) {
    for (const auto& [flags, needle] :
         {std::pair{"--fov 0", "--fov must lie"}, std::pair{"--fov 180", "--fov must lie"},
          std::pair{"--fov -5", "--fov must lie"}, std::pair{"--near 0", "--near must be > 0"},
          std::pair{"--near -1", "--near must be > 0"}, std::pair{"--near 2 --far 1", "--far must be greater"},
          std::pair{"--near 2 --far 2", "--far must be greater"},
          std::pair{"--eye 1,1,1 --target 1,1,1", "--eye and --target must differ"},
          std::pair{"--eye 0,5,0 --target 0,0,0 --up 0,1,0", "--up must not be parallel"}}) {
      const Run r = expectError(std::string("render ") + flags + out + device, needle);
      CHECK(r.err.find("--device") == std::string::npos);
    }
  }
  // The eye's default lies on (0.55, 0.45, 1) from the target (camera.cpp).
  expectError("render --target 0,0,0 --up 0.55,0.45,1" + out, "--up must not be parallel");
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
  // Blank lines before a magic with text after it: assimp looped for minutes
  // on such a header (found by the fuzzer, tests/fuzz_corpus/ply_magic_run_on).
  expectError("render '" + writeFile("runon.ply", "\nplyformat ascii 1.0\nelement vertex 3\nend_header\n") + "'" + out,
              "runon.ply: PLY header line 2: text after the magic 'ply'");
  // Blank lines before a well-formed header are still PLY, checked as such.
  expectError("render '" + writeFile("blank.ply", "\n\nply\nformat ascii 1.0\nelement vertex 3\nproperty banana x\n") +
                  "'" + out,
              "blank.ply: PLY header line 6: unknown property type 'banana'");
  expectError("render '" +
                  writeFile("truncated.ply",
                            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                            "end_header\n0 0 0\n1 0") +
                  "'" + out,
              "truncated.ply: PLY line 11: a vertex line with too few values");
  expectError("render '" + writeFile("no-mesh.obj", "o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\n") + "'" + out, "no-mesh.obj");
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

TEST_CASE("cli: hostile scene files are rejected with one line and no output", "[cli]")
{
  SECTION("a valid glTF renders, so the variants below fail for their one change")
  {
    const std::string png = tmpDir() + "/valid-gltf.png";
    const Run r = run("render '" + writeFile("valid.gltf", validGltf()) + "' -o '" + png + "' --size 32x32");
    INFO(r.err);
    CHECK(r.status == 0);
  }
  SECTION("indices out of range")
  {
    expectSceneError("range-hostile.ply", kPlyHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n", "out of range");
    expectSceneError("range-hostile.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", "index");
  }
  SECTION("non-finite and huge positions")
  {
    expectSceneError("nan.obj", kSmallObj + "v nan 0 0\nf 5 1 2\n", "has a non-finite position (nan, 0, 0)");
    expectSceneError("inf.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 inf 0\n3 0 1 2\n", "vertex 2 has a non-finite position");
    expectSceneError("inf.ply", kPlyHeader + "0 0 0\n1 0 0\n-inf 1 0\n3 0 1 2\n", "non-finite position");
    expectSceneError("huge.obj", kSmallObj + "v 0 3e38 0\nf 5 1 2\n", "beyond the supported 1e18");
    expectSceneError("huge-scale.gltf", gltfWith("{\"mesh\": 0}", "{\"mesh\": 0, \"scale\": [1e30, 1, 1]}"),
                     "beyond the supported 1e18");
  }
  SECTION("glTF accessors of the wrong type")
  {
    expectSceneError("position-ushort.gltf", gltfWith("\"componentType\": 5126", "\"componentType\": 5123"),
                     "glTF: attribute POSITION uses an accessor of componentType 5123");
    expectSceneError("position-scalar.gltf", gltfWith("\"VEC3\"", "\"SCALAR\""),
                     "glTF: attribute POSITION uses an accessor of type SCALAR");
    expectSceneError("position-mat4.gltf", gltfWith("\"VEC3\"", "\"MAT4\""),
                     "glTF: attribute POSITION uses an accessor of type MAT4");
    expectSceneError("indices-float.gltf", gltfWith("\"componentType\": 5123", "\"componentType\": 5126"),
                     "glTF: indices uses an accessor of componentType 5126");
    expectSceneError("component-unknown.gltf", gltfWith("\"componentType\": 5126", "\"componentType\": 1234"),
                     "glTF: an accessor has no valid componentType");
    expectSceneError("deep.gltf", std::string(1000, '[') + std::string(1000, ']'), "nested deeper than 64 levels");
  }
  SECTION("truncated files, each format")
  {
    expectSceneError("truncated.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2", "cannot import");
    expectSceneError("truncated.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n", "cannot import");
    expectSceneError("truncated-ascii.ply", kPlyHeader + "0 0 0\n1 0 0\n0 1", "a vertex line with too few values");
    std::string ply = kPlyHeader;
    ply.replace(ply.find("ascii"), 5, "binary_little_endian");
    expectSceneError("truncated-binary.ply", ply + std::string(30, '\0'), "truncated-binary.ply");
    expectSceneError("truncated-ascii.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n",
                     "truncated-ascii.stl");
    expectSceneError("truncated-binary.stl",
                     std::string(80, '\0') + std::string("\x02\0\0\0", 4) + std::string(60, '\0'),
                     "truncated-binary.stl");
    const std::string gltf = validGltf();
    expectSceneError("truncated.gltf", gltf.substr(0, gltf.size() / 2), "invalid JSON");
    expectSceneError("truncated.glb", std::string("glTF\x02\0\0\0\x40\0\0\0\xe8\x03\0\0JSON{}", 22),
                     "GLB header states 64 bytes, the file has 22");
    expectSceneError("short-chunk.glb", std::string("glTF\x02\0\0\0\x16\0\0\0\xe8\x03\0\0JSON{}", 22),
                     "GLB JSON chunk truncated");
  }
  SECTION("missing buffers")
  {
    expectSceneError("missing-bin.gltf", gltfWith("\"uri\": \"data:", "\"uri\": \"no-such-file.bin\", \"x\": \"data:"),
                     "cannot use 'no-such-file.bin'");
  }
  SECTION("counts larger than the file")
  {
    expectSceneError("count.off", "OFF\n1000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                     "OFF header vertex count 1000000000 exceeds what the file's 45 bytes hold");
    std::string ply = kPlyHeader;
    ply.replace(ply.find("vertex 3"), 8, "vertex 4000000000");
    expectSceneError("count.ply", ply + "0 0 0\n", "element 'vertex' has 4000000000 items");
  }
  SECTION("a FIFO, as the scene or as a glTF buffer, is refused rather than waited on")
  {
    const std::string fifo = tmpDir() + "/hostile-fifo.bin";
    std::remove(fifo.c_str());
    REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
    const std::string png = tmpDir() + "/hostile-fifo.png";
    expectError("render '" + fifo + "' -o '" + png + "'", fifo + ": not a regular file");
    expectSceneError("fifo-buffer.gltf", gltfWith("\"uri\": \"data:", "\"uri\": \"hostile-fifo.bin\", \"x\": \"data:"),
                     "cannot use 'hostile-fifo.bin'");
    std::remove(fifo.c_str());
  }
}

TEST_CASE("cli: a scene file loads while the program builds and its error comes first", "[cli]")
{
  // A file's quick checks run first, then its import on a second thread
  // while the device's program builds (api_command.cpp): a bad scene is the error
  // reported either way, also when the device fails as well, and a good
  // scene leaves the device's error.
  const std::string png = tmpDir() + "/both-bad.png";
  std::remove(png.c_str());
  const std::string header = writeFile("both-bad.ply", "ply\nformat ascii 1.0\nelement vertex 3\n");
  const std::string points = writeFile("both-bad.obj", "o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
  const std::string device = " --device no-such-device-anywhere";
  for (const auto& [scene, needle] :
       {std::pair{header, header + ": PLY header has no end_header"},
        std::pair{points, points + ": cannot import (Validation failed: aiScene::mNumMeshes is 0"}}) {
    const Run r = expectError("render '" + scene + "' -o '" + png + "'" + device, needle);
    CHECK(r.err.find("--device") == std::string::npos);
  }
  const std::string good = writeFile("both-good.obj", kSmallObj);
  expectError("render '" + good + "' -o '" + png + "'" + device,
              "--device no-such-device-anywhere: no device name matches");
  struct stat st;
  CHECK(stat(png.c_str(), &st) != 0);
  CHECK(leftoverTemps(png) == 0);
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

TEST_CASE("cli: renders a file and reports stats", "[cli]")
{
  const std::string scene = writeFile("small.obj", kSmallObj);
  const std::string png = tmpDir() + "/small.png";
  std::remove(png.c_str());
  const Run r = run("render '" + scene + "' -o '" + png + "' --size 64x48 --shade id --stats --frames 2");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.empty());
  const std::string png_bytes = slurp(png);
  CHECK(png_bytes.substr(1, 3) == "PNG");
  CHECK(r.out.find("\"triangles_in\":2") != std::string::npos);
  CHECK(r.out.find("\"triangles_culled\":0") != std::string::npos);
  CHECK(r.out.find("\"frame_ms\":") != std::string::npos);
  CHECK(r.out.find("\"stage_ms\":{") != std::string::npos);
  CHECK(r.out.find("\"device_idle_ms\":") != std::string::npos);
  CHECK(r.out.find("\"device_bytes\":") != std::string::npos);
  for (const char* key : {"read_ms", "parse_ms", "prepare_ms", "build_ms", "encode_ms", "total_ms"})
    CHECK(r.out.find(std::string("\"") + key + "\":") != std::string::npos);
  CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  CHECK(leftoverTemps(png) == 0);
}

TEST_CASE("cli: --stats of a single picture renders its one frame only", "[cli]")
{
  // Without --frames no warm-up frame runs: the picture's frame is both the
  // first and the timed one, so both fields print the same measurement.
  const std::string png = tmpDir() + "/single-stats.png";
  const Run r = run("render -o '" + png + "' --size 32x24 --stats");
  INFO(r.out + r.err);
  REQUIRE(r.status == 0);
  auto field = [&](const std::string& key) {
    const size_t at = r.out.find("\"" + key + "\":");
    REQUIRE(at != std::string::npos);
    const size_t begin = at + key.size() + 3;
    return r.out.substr(begin, r.out.find(',', begin) - begin);
  };
  CHECK(field("frames") == "1");
  CHECK(field("first_frame_ms") == field("frame_ms"));
}

TEST_CASE("cli: stats that cannot be written are an error", "[cli]")
{
  // A render ends without tearing the device down (main.cpp), flushing its
  // standard output itself: a full device must still fail the run.
  const std::string scene = writeFile("small.obj", kSmallObj);
  const std::string png = tmpDir() + "/full-stdout.png";
  expectError("render '" + scene + "' -o '" + png + "' --size 16x16 --stats >/dev/full",
              "cannot write standard output");
  CHECK(leftoverTemps(png) == 0);
}

TEST_CASE("cli: a one-point scene far from the origin is framed", "[cli]")
{
  // Every vertex at one spot: the default camera must still stand off from it.
  for (const char* at : {"1000", "1e17"}) {
    const std::string v = std::string("v ") + at + " " + at + " " + at + "\n";
    const std::string scene = writeFile("point.obj", v + v + v + "f 1 2 3\n");
    const std::string png = tmpDir() + "/point.png";
    const Run r = run("render '" + scene + "' -o '" + png + "' --size 16x16");
    INFO(at << ": " << r.err);
    CHECK(r.status == 0);
  }
}

TEST_CASE("cli: devices lists at least one device", "[cli]")
{
  const Run r = run("devices");
  CHECK(r.status == 0);
  CHECK(r.out.find("0: [") == 0);
}

TEST_CASE("cli: files assimp would misread are read right or refused", "[cli]")
{
  // OBJ: ".5" is a number (assimp skipped the line, shifting every later index); an alpha is dropped.
  const std::string out = tmpDir() + "/misread.png";
  for (const char* obj : {"v 0 0 0\nv .5 .5 0\nv 1 0 0\nv 0 7 0\nf 1 2 3\n",
                          "v 0 0 0\nv .5 .5 0 1 0 .5 1\nv 1 0 0\nv 0 7 0\nf 1 2 3\n"}) {
    const Run r = run("info '" + writeFile("misread.obj", obj) + "' --json");
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains("\"max\":[1,0.5,0]") && Catch::Contains("\"triangles\":1"));  // not (0, 7, 0)
    CHECK(run("render '" + tmpDir() + "/misread.obj' -o '" + out + "' --shade color --size 16x16").status == 0);
  }
  expectSceneError("two-numbers.obj", "v 0 0 0\nv 1 2\nv 1 0 0\nv 0 1 0\nf 1 3 4\n", "a vertex line of 2 numbers");
  // OBJ: a last line without its line end, across the OBJ reader's 16 MiB block, was dropped.
  const std::string lastLine = "v 0 0 0\nv 1 0 0\nv 0 1 0\n# " + std::string((16u << 20) - 40000, 'x') +
                               "\nf 1 2 3\nf 1 2 3" + std::string(100000, ' ');
  const Run last = run("info '" + writeFile("last-line.obj", lastLine) + "'");
  CHECK_THAT(last.out, Catch::Contains("triangles  2\n"));
  std::remove((tmpDir() + "/last-line.obj").c_str());
  // OFF: assimp reads "-2" as vertex 0.
  expectSceneError("negative.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n9 9 9\n3 0 1 -2\n", "vertex index '-2'");
  // Binary PLY: a body shorter than its elements was read from whatever bytes follow.
  const std::string binaryHeader =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float "
      "z\nend_header\n";
  expectSceneError("short-body.ply", binaryHeader + std::string(20, '\0'), "PLY binary body of 20 bytes");
  // glTF: an accessor reaching past its bufferView; a primitive mode outside 0..6; a GLB shorter than its header.
  expectSceneError("past-view.gltf", gltfWith("\"byteLength\": 48}", "\"byteLength\": 44}"),
                   "attribute POSITION reads 48 bytes of a bufferView of 44");
  expectSceneError("mode9.gltf", gltfWith("\"indices\": 1}", "\"indices\": 1, \"mode\": 9}"), "no valid mode");
}

TEST_CASE("cli: a missing material library warns and non UTF-8 names stay valid JSON", "[cli]")
{
  const std::string model = writeFile("no-library.obj", "mtllib nope.mtl\nusemtl a\n" + kSmallObj);
  const Run r = run("render '" + model + "' -o '" + tmpDir() + "/no-library.png' --size 16x16");
  CHECK(r.status == 0);
  CHECK_THAT(r.err, Catch::Contains("cannot use 'nope.mtl'"));
  const std::string odd = writeFile("odd\xff.obj", kSmallObj);
  const Run info = run("info '" + odd + "' --json");
  INFO(info.err);
  CHECK(info.status == 0);
  CHECK_THAT(info.out, Catch::StartsWith("{") && Catch::Contains("\xEF\xBF\xBD"));  // U+FFFD for the byte
}

TEST_CASE("cli: outputs are written together or not at all", "[cli]")
{
  // -o with --aov: a folder where the EXR goes fails before rendering, and no PNG is left.
  const std::string dir = tmpDir() + "/together";
  std::system(("rm -rf '" + dir + "' && mkdir -p '" + dir + "/vis.exr' '" + dir + "/f_1.png'").c_str());
  expectError("render -o '" + dir + "/img.png' --aov '" + dir + "/vis.exr' --size 16x16", "vis.exr: cannot write");
  CHECK_FALSE(test::exists(dir + "/img.png"));
  // --views: a view's name that is a folder fails before any view is written.
  const std::string views = writeFile("together.json", "{\"views\": [{}, {}]}");
  expectError("render --views '" + views + "' -o '" + dir + "/f_%d.png' --size 16x16", "f_1.png: cannot write");
  CHECK_FALSE(test::exists(dir + "/f_0.png"));
}

TEST_CASE("cli: warnings for a depth range and a narrow fov name their cause", "[cli]")
{
  const std::string out = " -o '" + tmpDir() + "/depth-range.png' --size 16x16";
  const Run r = run("render --near 1e-8 --far 1e8" + out);
  CHECK(r.status == 0);
  CHECK_THAT(r.err, Catch::Contains("warning: far/near = 1e+16 is over float32 depth's 1e4"));
  CHECK(run("render --near 1e-8 --far 1e8 --depth auto" + out).err.empty());
  expectError("render --fov 1e-30" + out, "--fov: too narrow");
  expectError("render --eye 1e30,0,0" + out, "--eye and --target lie too far apart");
  expectError("render --fov 0x2Dp0" + out, "--fov: '0x2Dp0' is not a finite number");
  expectError("render --size ' 16x16'" + out, "--size");
  expectError("render --device 99999999999999999999" + out, "no such device index");
}
