// test_hostile_files.cpp — hostile input beyond the model file itself: the
// file rule wherever a file is read (file_rule.h), output patterns, the
// length of every message, the texture budget, and correctly rounded
// positions of text models (exact_positions.h). Every bad input here must
// end as one line (an error, or a warning where rendering goes on) and
// leave no output; each CLI run is under `timeout`, so a hang fails.
#include "cli_support.h"
#include "io/file_rule.h"
#include "io/scene.h"
#include "test_support.h"
#include "io/texture.h"
#include "render/views.h"

#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <catch2/catch.hpp>
#include <zlib.h>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <climits>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using Catch::Matchers::Contains;

namespace {

// `clraster ARGS` with stdin from `input` (a shell redirection or a pipe
// in front), killed after 60 s (status 124): a hang fails the test.
test::Run runHostile(const std::string& args, const std::string& input = "</dev/null")
{
  const std::string errPath = test::tempDir() + "/hostile-stderr-" + std::to_string(getpid()) + ".txt";
  const bool pipe = input.size() && input.back() == '|';
  const std::string cmd = (pipe ? input + " " : std::string()) + "timeout 60 '" + CLRASTER_BIN + "' " + args + " 2>'" +
                          errPath + "'" + (pipe ? "" : " " + input);
  return test::runShell(cmd, errPath);
}

// The peak resident memory in kB of `command` under /bin/sh: wait4 reports
// the largest of the shell and every process it waited for. One run's own
// peak, where getrusage(RUSAGE_CHILDREN) would be the largest of all runs.
long peakRssKb(const std::string& command)
{
  const char* c = command.c_str();
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", c, static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  struct rusage usage {};
  REQUIRE(wait4(pid, &status, 0, &usage) == pid);
  REQUIRE((WIFEXITED(status) && WEXITSTATUS(status) == 0));
  return usage.ru_maxrss;
}

// Each stderr line, less its "clraster: " or "clraster: warning: " prefix.
std::vector<std::string> messages(const std::string& err)
{
  std::vector<std::string> out;
  std::istringstream lines(err);
  for (std::string line; std::getline(lines, line);) {
    for (const char* prefix : {"clraster: warning: ", "clraster: "})
      if (line.rfind(prefix, 0) == 0) {
        line = line.substr(std::strlen(prefix));
        break;
      }
    out.push_back(line);
  }
  return out;
}

// One error line containing `needle`, at most 300 bytes, exit 1.
void expectShortError(const test::Run& r, const std::string& needle)
{
  INFO("stderr: " << r.err.substr(0, 2000));
  CHECK(r.status == 1);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.find(needle) != std::string::npos);
  for (const std::string& m : messages(r.err)) CHECK(m.size() <= 300);
}

std::string freshDir(const std::string& name)
{
  const std::string dir = test::tempDir() + "/" + name;
  REQUIRE(std::system(("rm -rf '" + dir + "' && mkdir -p '" + dir + "'").c_str()) == 0);
  return dir;
}

size_t filesIn(const std::string& dir)
{
  size_t n = 0;
  FILE* p = popen(("ls -A '" + dir + "' | wc -l").c_str(), "r");
  REQUIRE(p);
  const bool read = std::fscanf(p, "%zu", &n) == 1;
  REQUIRE(read);
  pclose(p);
  return n;
}

const char* const kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";

// A sparse file of `bytes` bytes (no disk blocks).
std::string sparseFile(const std::string& path, uint64_t bytes)
{
  std::ofstream(path, std::ios::binary) << "x";
  REQUIRE(truncate(path.c_str(), off_t(bytes)) == 0);
  return path;
}

void appendChunk(std::string& png, const char* type, const std::string& data)
{
  auto be32 = [&](uint32_t v) {
    for (int k = 3; k >= 0; --k) png += char((v >> (8 * k)) & 0xFF);
  };
  be32(uint32_t(data.size()));
  const std::string body = std::string(type, 4) + data;
  png += body;
  be32(uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))));
}

// A real RGB PNG of w×h black pixels, its rows deflated as a stream: a few
// hundred kB that decode to w·h·4 bytes.
std::string blackPng(uint32_t w, uint32_t h)
{
  std::string png = "\x89PNG\r\n\x1a\n";
  std::string ihdr;
  for (uint32_t v : {w, h})
    for (int k = 3; k >= 0; --k) ihdr += char((v >> (8 * k)) & 0xFF);
  ihdr += std::string("\x08\x02\x00\x00\x00",
                      5);  // 8 bits, RGB, deflate, no filter choice, no interlace
  appendChunk(png, "IHDR", ihdr);
  z_stream z{};
  REQUIRE(deflateInit(&z, 9) == Z_OK);
  const std::vector<unsigned char> row(1 + size_t(w) * 3, 0);
  std::string idat;
  std::vector<unsigned char> out(1 << 16);
  for (uint32_t y = 0; y <= h; ++y) {
    z.next_in = const_cast<unsigned char*>(row.data());
    z.avail_in = y < h ? uInt(row.size()) : 0;
    do {
      z.next_out = out.data();
      z.avail_out = uInt(out.size());
      deflate(&z, y < h ? Z_NO_FLUSH : Z_FINISH);
      idat.append(reinterpret_cast<char*>(out.data()), out.size() - z.avail_out);
    } while (z.avail_out == 0);
  }
  deflateEnd(&z);
  appendChunk(png, "IDAT", idat);
  appendChunk(png, "IEND", "");
  return png;
}

}  // namespace

TEST_CASE(
    "hostile: a FIFO, a device, a directory or an endless pipe where a "
    "file is expected is one error line",
    "[hostile][cli]")
{
  const std::string dir = freshDir("hostile-special");
  const std::string out = freshDir("hostile-special-out");
  const std::string fifo = dir + "/pipe.obj";
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  const std::string views = test::writeFile("hostile-views.json", "{\"views\": [{}]}");
  // Step 1: the model and the views file, each a FIFO, /dev/zero, a folder,
  // and /dev/stdin fed without end.
  for (const std::string& bad : {fifo, std::string("/dev/zero"), dir}) {
    expectShortError(runHostile("render '" + bad + "' -o '" + out + "/a.png'"), "not a regular file");
    expectShortError(runHostile("render --views '" + bad + "' -o '" + out + "/v%d.png'"), "not a regular file");
  }
  expectShortError(runHostile("render /dev/stdin -o '" + out + "/a.png'", "yes 'v 0 0 0' |"),
                   "/dev/stdin: not a regular");
  expectShortError(runHostile("render --views /dev/stdin -o '" + out + "/v%d.png'", "yes '{' |"),
                   "/dev/stdin: not a regular");
  // Step 2: files a model names: a material library and a texture. The
  // model renders without them, with one warning.
  const std::string texFifo = dir + "/tex.png";
  REQUIRE(mkfifo(texFifo.c_str(), 0600) == 0);
  for (const std::string& tex : {texFifo, std::string("/dev/zero"), dir}) {
    test::writeFile("hostile-tex.mtl", "newmtl m\nKd 1 1 1\nmap_Kd " + tex + "\n");
    const std::string model =
        test::writeFile("hostile-tex.obj", "mtllib hostile-tex.mtl\nusemtl m\n" + std::string(kTriangle));
    const test::Run r = runHostile("render '" + model + "' -o '" + out + "/t.png' --size 16x16");
    INFO(r.err);
    CHECK(r.status == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_THAT(r.err, Contains(": cannot use '") && Contains("rendered without the texture"));
  }
  // (assimp opens a material library beside the model)
  const std::string mtlFifo = test::tempDir() + "/hostile-lib.mtl";
  unlink(mtlFifo.c_str());
  REQUIRE(mkfifo(mtlFifo.c_str(), 0600) == 0);
  const std::string model =
      test::writeFile("hostile-mtl.obj", "mtllib hostile-lib.mtl\nusemtl m\n" + std::string(kTriangle));
  const test::Run r = runHostile("render '" + model + "' -o '" + out + "/m.png' --size 16x16");
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK_THAT(r.err, Contains("cannot use 'hostile-lib.mtl'") && Contains("imported without it"));
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  // Nothing but the renders that went on was written.
  CHECK(filesIn(out) == 2);
}

TEST_CASE("hostile: files over their size limit are refused before they are read", "[hostile][cli]")
{
  const std::string dir = freshDir("hostile-size");
  const std::string out = freshDir("hostile-size-out");
  const std::string model = sparseFile(dir + "/huge.obj", clr::kModelInput.maxBytes + 1);
  expectShortError(runHostile("render '" + model + "' -o '" + out + "/a.png'"), "exceeds the limit of 1073741824");
  const std::string views = sparseFile(dir + "/huge.json", clr::kViewsInput.maxBytes + 1);
  expectShortError(runHostile("render --views '" + views + "' -o '" + out + "/v%d.png'"), "exceeds the limit");
  sparseFile(dir + "/huge.png", clr::kTextureInput.maxBytes + 1);
  std::ofstream(dir + "/t.mtl") << "newmtl m\nKd 1 1 1\nmap_Kd huge.png\n";
  std::ofstream(dir + "/t.obj") << "mtllib t.mtl\nusemtl m\n" << kTriangle;
  const test::Run r = runHostile("render '" + dir + "/t.obj' -o '" + out + "/t.png' --size 16x16");
  CHECK(r.status == 0);
  CHECK_THAT(r.err, Contains("huge.png: texture file of 268435457 bytes exceeds the limit"));
  CHECK(filesIn(out) == 1);
  // Empty files too.
  std::ofstream(dir + "/empty.json").flush();
  expectShortError(runHostile("render --views '" + dir + "/empty.json' -o '" + out + "/v%d.png'"), "file is empty");
}

TEST_CASE(
    "hostile: output patterns are checked before formatting and names "
    "stay bounded",
    "[hostile][views]")
{
  auto error = [](const std::string& pattern) {
    try {
      clr::checkOutputPattern(pattern);
    } catch (const clr::Error& e) {
      CHECK(std::strlen(e.what()) <= 300);
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK_THAT(error("out_%999999999d.png"), Contains("width over 9"));
  CHECK_THAT(error("out_%10d.png"), Contains("width over 9"));
  CHECK_THAT(error("out_%.10d.png"), Contains("precision over 9"));
  CHECK_THAT(error("out_%#d.png"), Contains("a conversion other than"));
  CHECK_THAT(error("out_%*d.png"), Contains("a conversion other than"));
  CHECK(error("out_%9.9d.png").empty());
  CHECK(error("out_%-9u.png").empty());
  CHECK(clr::outputName("o%9.9d", 7) == "o000000007");
  CHECK(clr::outputName("o%9d", INT_MAX) == "o2147483647");
  // Names that cannot exist: a component over NAME_MAX, a path over PATH_MAX.
  CHECK_THAT(error(std::string(250, 'a') + "%9d.png"), Contains("a file or folder name over 255 bytes"));
  CHECK(error(std::string(240, 'a') + "%9d.png").empty());
  CHECK_THAT(error(std::string(5000, 'a') + "%d"), Contains("longer than a path may be"));
  CHECK_THAT(error(std::string(100000, '%') + "d"), Contains("longer than a path may be"));
  // On the command line: one short line, nothing written.
  const std::string out = freshDir("hostile-pattern");
  const std::string views = test::writeFile("hostile-pattern.json", "{\"views\": [{}]}");
  expectShortError(runHostile("render --views '" + views + "' -o '" + out + "/o%999999999d.png'"), "width over 9");
  expectShortError(runHostile("render --views '" + views + "' -o '" + out + "/" + std::string(100000, 'x') + "%d.png'"),
                   "longer than a path may be");
  CHECK(filesIn(out) == 0);
}

TEST_CASE("hostile: no message quotes more than a bounded part of a user string", "[hostile][cli]")
{
  const std::string dir = freshDir("hostile-long");
  const std::string huge(100000, 'q');
  const std::string longPath = dir + "/" + std::string(200, 'd') + "/" + std::string(200, 'e') + "/x.obj";
  REQUIRE(std::system(("mkdir -p '" + longPath.substr(0, longPath.rfind('/')) + "'").c_str()) == 0);
  std::ofstream(longPath) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n";  // an index out of range
  const std::string views = test::writeFile("hostile-long.json", "{\"views\": [{}]}");
  const std::string badKey = test::writeFile("hostile-key.json", "{\"views\": [{\"" + huge + "\": 1}]}");
  const std::string badJson = test::writeFile("hostile-json.json", "{\"views\": [" + huge + "]}");
  const std::string badWord = test::writeFile("hostile-word.obj", "v 0 0 0\nv 1 0 0\nv " + huge + " 1 0\nf 1 2 3\n");
  const std::string args[] = {
      "render '" + dir + "/" + huge + ".obj' -o " + dir + "/a.png",
      "render '" + longPath + "' -o " + dir + "/a.png",
      "render --views '" + dir + "/" + huge + "' -o " + dir + "/v%d.png",
      "render --views '" + badKey + "' -o " + dir + "/v%d.png",
      "render --views '" + badJson + "' -o " + dir + "/v%d.png",
      "render '" + badWord + "' -o " + dir + "/a.png",
      "render -o '" + dir + "/" + huge + ".png'",
      "render -o '" + dir + "/" + std::string(3000, 'n') + "/a.png'",
      "render -o a.png --size " + huge,
      "render -o a.png --eye " + huge,
      "render -o a.png --shade " + huge,
      "render -o a.png --cull " + huge,
      "render -o a.png --aa " + huge,
      "render -o a.png --frames " + huge,
      "render -o a.png --light-point 1,2,3," + huge,
      "render -o a.png --views '" + views + "' --shard " + huge,
      "render -o a.png -" + huge,
      "render a.obj b.obj" + huge + " -o a.png",
      huge,
  };
  for (const std::string& a : args) {
    const test::Run r = runHostile(a);
    INFO("clraster " << a.substr(0, 300) << "\nstderr: " << r.err.substr(0, 1000));
    CHECK(r.status == 1);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    for (const std::string& m : messages(r.err)) CHECK(m.size() <= 300);
  }
  // A texture path of 1000 bytes in a material: the warning is bounded too.
  test::writeFile("hostile-longtex.mtl", "newmtl m\nKd 1 1 1\nmap_Kd " + std::string(1000, 't') + ".png\n");
  const std::string model =
      test::writeFile("hostile-longtex.obj", "mtllib hostile-longtex.mtl\nusemtl m\n" + std::string(kTriangle));
  const test::Run r = runHostile("render '" + model + "' -o '" + dir + "/t.png' --size 16x16");
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK_THAT(r.err, Contains("rendered without the texture"));
  for (const std::string& m : messages(r.err)) CHECK(m.size() <= 300);
}

TEST_CASE(
    "hostile: textures are sized from their header and held to one "
    "budget per scene",
    "[hostile][texture]")
{
  // Step 1: the budget's arithmetic: whole mip chains, 4 bytes a texel.
  CHECK(clr::mipChainBytes(1, 1) == 4);
  CHECK(clr::mipChainBytes(2, 2) == 4 * (4 + 1));
  CHECK(clr::mipChainBytes(3, 1) == 4 * (3 + 1));
  CHECK(clr::mipChainBytes(16000, 16000) > clr::kTextureBudgetBytes);
  CHECK(clr::mipChainBytes(8192, 8192) < clr::kTextureBudgetBytes);
  clr::TextureBudget budget(40);
  CHECK_NOTHROW(budget.claim("a", 2, 2));
  CHECK_NOTHROW(budget.claim("b", 2, 2));
  CHECK_THROWS_AS(budget.claim("c", 1, 1), clr::TextureOverBudget);
  // Step 2: decodeTexture claims before it decodes.
  const std::string png = blackPng(4, 4);
  clr::TextureBudget small(4 * 21 - 1), enough(4 * 21);
  const auto* bytes = reinterpret_cast<const unsigned char*>(png.data());
  CHECK_THROWS_WITH(clr::decodeTexture("p.png", bytes, png.size(), small),
                    Contains("p.png: 4x4 needs 1 MiB with its mip levels, over "
                             "the scene's texture budget"));
  const clr::Texture t = clr::decodeTexture("p.png", bytes, png.size(), enough);
  CHECK((t.width == 4 && t.height == 4 && t.rgba.size() == 16));
  // Step 3: a small PNG that declares 16000x16000 (1 GB decoded): a warning,
  // the model renders untextured, and the process never holds the pixels.
  const std::string dir = freshDir("hostile-budget");
  const std::string huge = blackPng(16000, 16000);
  CHECK(huge.size() < 2000000);
  std::ofstream(dir + "/huge.png", std::ios::binary) << huge;
  std::ofstream(dir + "/t.mtl") << "newmtl m\nKd 1 1 1\nmap_Kd huge.png\n";
  std::ofstream(dir + "/t.obj") << "mtllib t.mtl\nusemtl m\n" << kTriangle;
  const test::Run r = runHostile("render '" + dir + "/t.obj' -o '" + dir + "/t.png' --size 16x16 --shade texture");
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK_THAT(r.err, Contains("huge.png: 16000x16000 needs 1303 MiB") && Contains("rendered without the texture"));
  CHECK(test::exists(dir + "/t.png"));
  // The process never held the pixels: its peak stays within 256 MiB of the
  // same render with a 4x4 texture, far below the 977 MiB the image decodes
  // to. Relative, since the device's driver sets the base (about 100 MiB
  // with PoCL, near 1 GiB with NVIDIA's OpenCL driver).
  std::ofstream(dir + "/small.png", std::ios::binary) << png;
  std::ofstream(dir + "/s.mtl") << "newmtl m\nKd 1 1 1\nmap_Kd small.png\n";
  std::ofstream(dir + "/s.obj") << "mtllib s.mtl\nusemtl m\n" << kTriangle;
  const auto peakOf = [&](const std::string& model) {
    return peakRssKb("timeout 60 '" + std::string(CLRASTER_BIN) + "' render '" + dir + "/" + model + "' -o '" + dir +
                     "/p.png' --size 16x16 --shade texture 2>/dev/null");
  };
  const long base = peakOf("s.obj"), hostile = peakOf("t.obj");
  INFO("peak RSS: " << base << " kB with a 4x4 texture, " << hostile << " kB with the 16000x16000 one");
  CHECK(hostile < base + 256 * 1024);
}

namespace {

// Coordinates on a jittered grid written with 7 decimals, and their
// correctly rounded floats.
struct Coordinates {
  std::vector<std::string> text;
  std::vector<float> exact;
};

Coordinates gridCoordinates(size_t count)
{
  Coordinates c;
  uint32_t state = 12345;
  for (size_t i = 0; i < count; ++i) {
    state = state * 1664525u + 1013904223u;
    char text[32];
    std::snprintf(text, sizeof text, "%.7f", double(i % 97) * 0.37 + double(state >> 8) * 1e-9 - 20.0);
    float exact = 0.0f;
    std::from_chars(text, text + std::strlen(text), exact);
    c.text.push_back(text);
    c.exact.push_back(exact);
  }
  return c;
}

// How many coordinates assimp alone (fast_atof) reads other than `expected`.
size_t assimpMisrounds(const std::string& path, const std::vector<float>& expected)
{
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, 0);
  REQUIRE(scene);
  std::vector<float> got;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m)
    for (unsigned v = 0; v < scene->mMeshes[m]->mNumVertices; ++v) {
      const aiVector3D& p = scene->mMeshes[m]->mVertices[v];
      got.insert(got.end(), {p.x, p.y, p.z});
    }
  REQUIRE(got.size() == expected.size());
  size_t wrong = 0;
  for (size_t k = 0; k < got.size(); ++k) wrong += got[k] != expected[k];
  return wrong;
}

// The loaded mesh's positions equal the exact values, corner by corner.
void checkExact(const clr::Mesh& mesh, const std::vector<float>& expected)
{
  REQUIRE(mesh.positions.size() == expected.size());
  size_t same = 0;
  for (size_t k = 0; k < expected.size(); ++k) {
    uint32_t a, b;
    std::memcpy(&a, &mesh.positions[k], 4);
    std::memcpy(&b, &expected[k], 4);
    same += a == b;
  }
  CHECK(same == expected.size());
}

}  // namespace

TEST_CASE(
    "hostile: text model positions are the correctly rounded values of "
    "their decimals",
    "[hostile][models]")
{
  const size_t tris = 200;
  const Coordinates c = gridCoordinates(9 * tris);
  auto coord = [&](size_t v, int k) { return c.text[3 * v + size_t(k)]; };
  const size_t verts = 3 * tris;
  // OBJ, its faces naming vertices backwards (negative indices too), so
  // assimp's corner order differs from the file's vertex order.
  std::string obj, off = "OFF\n" + std::to_string(verts) + " " + std::to_string(tris) + " 0\n";
  std::string ply = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(verts) +
                    "\nproperty float y\nproperty float x\nproperty double "
                    "z\nproperty uchar red\nelement face " +
                    std::to_string(tris) + "\nproperty list uchar int vertex_indices\nend_header\n";
  std::string stl = "solid t\n";
  std::vector<float> objExpected, inOrder;
  for (size_t v = 0; v < verts; ++v) {
    obj += "v " + coord(v, 0) + " " + coord(v, 1) + " " + coord(v, 2) + "\n";
    off += coord(v, 0) + " " + coord(v, 1) + "\t" + coord(v, 2) + "\n";
    ply += coord(v, 1) + " " + coord(v, 0) + " " + coord(v, 2) + " 7\n";
    for (int k = 0; k < 3; ++k) inOrder.push_back(c.exact[3 * v + size_t(k)]);
  }
  for (size_t t = 0; t < tris; ++t) {
    const size_t a = 3 * t, b = 3 * t + 1, d = 3 * t + 2;
    obj +=
        "f " + std::to_string(d + 1) + " " + std::to_string(int(b) - int(verts)) + " " + std::to_string(a + 1) + "\n";
    for (size_t v : {d, b, a})
      for (int k = 0; k < 3; ++k) objExpected.push_back(c.exact[3 * v + size_t(k)]);
    off += "3 " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(d) + "\n";
    ply += "3 " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(d) + "\n";
    stl += "facet normal 0 0 1\n outer loop\n";
    for (size_t v : {a, b, d}) stl += "  vertex " + coord(v, 0) + " " + coord(v, 1) + " " + coord(v, 2) + "\n";
    stl += " endloop\nendfacet\n";
  }
  stl += "endsolid t\n";
  // Each file: assimp alone misrounds dozens of its 1,800 coordinates,
  // clraster none.
  const std::pair<std::string, const std::vector<float>*> files[] = {
      {test::writeFile("hostile-exact.obj", obj), &objExpected},
      {test::writeFile("hostile-exact.off", off), &inOrder},
      {test::writeFile("hostile-exact.ply", ply), &inOrder},
      {test::writeFile("hostile-exact.stl", stl), &inOrder}};
  for (const auto& [path, expected] : files) {
    INFO(path);
    CHECK(assimpMisrounds(path, *expected) >= 40);
    checkExact(clr::loadScene(path), *expected);
  }
  // A coordinate that is not a whole decimal number is an error, not a
  // guess at what assimp's prefix parse made of it.
  CHECK_THROWS_WITH(clr::loadScene(test::writeFile("hostile-bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1.5x 0\nf 1 2 3\n")),
                    Contains("OBJ line 3: coordinate '1.5x' is not a decimal number"));
  CHECK_THROWS_WITH(clr::loadScene(test::writeFile("hostile-bad.stl",
                                                   "solid s\nfacet normal 0 0 1\nouter loop\n"
                                                   "vertex 0 0 0\nvertex 1,0 0 0\nvertex 0 1 0\n"
                                                   "endloop\nendfacet\nendsolid s\n")),
                    Contains("STL line 5: coordinate '1,0' is not a decimal number"));
  // OBJ text under another extension: assimp picks its OBJ reader by content,
  // which would read positions with fast_atof; refused.
  CHECK_THROWS_WITH(clr::loadScene(test::writeFile("hostile-obj.txt", obj)), Contains("name it so"));
}
