// test_file_primitives.cpp — model files a newcomer brings: PLY headers with
// lines assimp skips, normals repaired (zero, NaN, missing), and a file's own
// lines and points drawn by the lines stage, depth-tested against its
// triangles. Renders go through the clraster binary and are decoded here.
#include "cli_support.h"
#include "test_support.h"

#include <catch2/catch.hpp>
#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <set>
#include <string>
#include <vector>

namespace {

using test::expectError;
using test::Run;
using test::run;
using test::slurp;
using test::writeFile;

const std::string kModels = "/usr/share/assimp/models/";

struct Image {
  int width = 0, height = 0;
  std::vector<uint32_t> rgb;  // 0xRRGGBB per pixel, top row first
  uint32_t at(int x, int y) const { return rgb[size_t(y) * width + x]; }
  size_t count(uint32_t colour) const
  {
    size_t n = 0;
    for (uint32_t c : rgb) n += c == colour;
    return n;
  }
  size_t distinct() const { return std::set<uint32_t>(rgb.begin(), rgb.end()).size(); }
};

Image decode(const std::string& path)
{
  Image img;
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &img.width, &img.height, &channels, 3);
  REQUIRE(data != nullptr);
  for (int i = 0; i < img.width * img.height; ++i)
    img.rgb.push_back(uint32_t(data[3 * i]) << 16 | uint32_t(data[3 * i + 1]) << 8 | data[3 * i + 2]);
  stbi_image_free(data);
  return img;
}

// Renders `scene` with `flags` into tempDir()/name.png; the run (exit 0
// required) and its image.
std::pair<Run, Image> render(const std::string& scene, const std::string& flags, const std::string& name)
{
  const std::string png = test::tempDir() + "/" + name + ".png";
  std::remove(png.c_str());
  const Run r = run("render '" + scene + "' -o '" + png + "' " + flags);
  INFO("render " << scene << " " << flags << ": " << r.err);
  REQUIRE(r.status == 0);
  return {r, decode(png)};
}

constexpr uint32_t kWhite = 0xFFFFFF;

std::string base64(const std::string& bytes)
{
  static const char* const kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    uint32_t v = 0;
    for (size_t k = 0; k < 3; ++k) v = v << 8 | (k < n ? uint8_t(bytes[i + k]) : 0u);
    out += kDigits[v >> 18 & 63];
    out += kDigits[v >> 12 & 63];
    out += n > 1 ? kDigits[v >> 6 & 63] : '=';
    out += n > 2 ? kDigits[v & 63] : '=';
  }
  return out;
}

// A glTF quad (two triangles in the plane z = 0) with the given normals.
std::string quadGltf(const std::vector<float>& normals)
{
  const std::vector<float> positions = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const std::vector<uint16_t> indices = {0, 1, 2, 0, 2, 3};
  std::string bytes(reinterpret_cast<const char*>(positions.data()), 48);
  bytes.append(reinterpret_cast<const char*>(normals.data()), 48);
  bytes.append(reinterpret_cast<const char*>(indices.data()), 12);
  return "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0, \"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0}],"
         " \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0, \"NORMAL\": 1}, \"indices\": 2}]}],"
         " \"buffers\": [{\"byteLength\": 108, \"uri\": \"data:application/octet-stream;base64," +
         base64(bytes) +
         "\"}], \"bufferViews\": [{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 48},"
         " {\"buffer\": 0, \"byteOffset\": 48, \"byteLength\": 48}, {\"buffer\": 0, \"byteOffset\": 96, "
         "\"byteLength\": "
         "12}], \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\", \"min\":"
         " [-1, -1, 0], \"max\": [1, 1, 0]}, {\"bufferView\": 1, \"componentType\": 5126, \"count\": 4, \"type\":"
         " \"VEC3\"}, {\"bufferView\": 2, \"componentType\": 5123, \"count\": 6, \"type\": \"SCALAR\"}]}";
}

}  // namespace

TEST_CASE("PLY headers with lines assimp skips load, lines that mislead it are refused", "[cli][models]")
{
  // Blender's PLY exporter writes "Created by ..." after the format line.
  const Run wuson = render(kModels + "PLY/Wuson.ply", "--size 64x48", "wuson-ply").first;
  CHECK(wuson.err.empty());
  const std::string body =
      "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const std::string created = writeFile("created.ply", "ply\nformat ascii 1.0\nCreated by a tool\n" + body);
  render(created, "--size 32x32", "created-ply");
  // Among an element's properties, assimp would end the element at the
  // unknown line and drop the properties after it.
  std::string among = "ply\nformat ascii 1.0\n" + body;
  among.insert(among.find("property float y"), "made by a tool\n");
  expectError("render '" + writeFile("among.ply", among) + "' -o " + test::tempDir() + "/among.png",
              "among.ply: PLY header line 6: property after the unknown header line 5 of its element");
}

TEST_CASE("zero vertex normals of an STL are recomputed, with one warning", "[cli][models]")
{
  // The file's normals: binary STL, every facet normal (0, 0, 0).
  const std::string stl = kModels + "STL/Wuson.stl";
  const std::string bytes = slurp(stl);
  REQUIRE(bytes.size() > 84);
  uint32_t facets = 0;
  std::memcpy(&facets, &bytes[80], 4);
  REQUIRE(bytes.size() == 84 + 50 * size_t(facets));
  for (uint32_t f = 0; f < facets; ++f) REQUIRE(bytes.substr(84 + 50 * size_t(f), 12) == std::string(12, '\0'));
  // Repaired: one warning line naming the file and the count, and a lit,
  // shaded picture (the zero normals gave one colour in --shade normal).
  const auto [r, img] = render(stl, "--size 96x64 --shade normal", "wuson-stl-normal");
  const std::string warning = "clraster: warning: " + stl + ": " + std::to_string(3 * facets) + " of " +
                              std::to_string(3 * facets) +
                              " vertex normals were zero, NaN or missing; recomputed from the geometry\n";
  CHECK(r.err == warning);
  CHECK(img.distinct() > 100);
  const Run info = run("info '" + stl + "'");
  CHECK(info.out.find("normals    from file, " + std::to_string(3 * facets) + " repaired") != std::string::npos);
}

TEST_CASE("NaN and zero normals of a glTF are recomputed, the others kept", "[cli][models]")
{
  const float nan = std::nanf("");
  const std::string good = writeFile("normals-good.gltf", quadGltf({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}));
  const std::string bad = writeFile("normals-nan.gltf", quadGltf({nan, nan, nan, 0, 0, 1, 0, 0, 0, 0, 0, 1}));
  // The quad is flat, so the smoothed normals are the file's good ones, and
  // the picture is the good file's byte for byte.
  for (const char* mode : {"normal", "phong", "gouraud"}) {
    const std::string flags = std::string("--size 48x48 --eye 0.3,0.2,3 --target 0,0,0 --shade ") + mode;
    const auto [goodRun, goodImg] = render(good, flags, "normals-good");
    const auto [badRun, badImg] = render(bad, flags, "normals-nan");
    CHECK(goodRun.err.empty());
    CHECK(badRun.err == "clraster: warning: " + bad +
                            ": 2 of 4 vertex normals were zero, NaN or missing; recomputed from the geometry\n");
    CHECK(badImg.rgb == goodImg.rgb);
    CHECK(goodImg.distinct() > 1);
  }
  const Run info = run("info '" + bad + "' --json");
  CHECK(info.out.find("\"normals\":{\"in_file\":true,\"repaired\":2}") != std::string::npos);
}

TEST_CASE("files of only lines or points render", "[cli][models]")
{
  const std::string gen = kModels + "glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_";
  // glTF points, lines, line loop, line strip; without and with indices.
  for (const char* n : {"00", "01", "02", "03", "07", "08", "09", "10"}) {
    const auto [r, img] = render(gen + n + ".gltf", "--size 64x64 --line bresenham", std::string("mode-") + n);
    CHECK(r.err.empty());
    CHECK(img.count(kWhite) > 0);
  }
  // OBJ l and p, AC line objects, point clouds (vertices without faces;
  // assimp's AC reader leaves nosurfaces.ac's point list out of every node);
  // anti-aliased lines (the default) cover few pixels fully, so any pixel
  // off the background counts.
  for (const char* f : {"OBJ/testline.obj", "OBJ/testpoints.obj", "AC/openLine.ac", "AC/closedLine.ac",
                        "OBJ/point_cloud.obj", "PLY/points.ply", "AC/nosurfaces.ac"}) {
    const auto [r, img] = render(kModels + f, "--size 64x64", "linefile");
    CHECK(r.err.empty());
    CHECK(img.count(img.at(0, 0)) + 3 <= img.rgb.size());  // the point cloud's 3 points at least
  }
  // The primitives as `info` counts them: a loop of 4 vertices is 4
  // segments, its closing one included, as is a strip of 5 indices; points
  // are one per vertex.
  for (const auto& [n, count] :
       {std::pair{"02", "lines      4\npoints     0\n"}, std::pair{"10", "lines      4\npoints     0\n"},
        std::pair{"07", "lines      0\npoints     1024\n"}}) {
    const Run info = run("info '" + gen + n + ".gltf'");
    CHECK(info.out.find(count) != std::string::npos);
  }
}

TEST_CASE("a file's lines are depth-tested against its triangles", "[cli][models]")
{
  // A square at z = 0 facing the eye on +z; a horizontal line through the
  // middle of the picture, behind it (z = -1) or in front (z = +1).
  const std::string square = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";
  const std::string flags = "--size 64x64 --eye 0,0,5 --target 0,0,0 --near 1 --far 10 --line bresenham --shade normal";
  const std::string behind = writeFile("line-behind.obj", square + "v -4 0.01 -1\nv 4 0.01 -1\nl 5 6\n");
  const std::string front = writeFile("line-front.obj", square + "v -4 0.01 1\nv 4 0.01 1\nl 5 6\n");
  const Image b = render(behind, flags, "line-behind").second;
  const Image f = render(front, flags, "line-front").second;
  // The row of the line: white across the picture in front; behind, white
  // only outside the square (which covers the middle columns).
  int row = -1;
  for (int y = 0; y < 64; ++y)
    if (f.at(0, y) == kWhite) row = y;
  REQUIRE(row >= 0);
  CHECK(f.at(32, row) == kWhite);
  CHECK(b.at(0, row) == kWhite);
  CHECK(b.at(63, row) == kWhite);
  CHECK(b.at(32, row) != kWhite);
  CHECK(b.at(32, row) == b.at(32, row + 3));  // the square's colour
}

TEST_CASE("points are squares of --point-size pixels", "[cli][models]")
{
  // One point at the centre of view, inside the frustum: size 1 is one
  // pixel, 3 and 4 are 9 and 16 pixels, each fully white.
  const std::string obj = writeFile("one-point.obj", "v 0.1 0.1 0\nv -1 -1 0\nv 1 1 0\np 1\n");
  const std::string flags = "--size 64x48 --eye 0,0,5 --target 0,0,0 ";
  for (int size : {1, 3, 4}) {
    const Image img = render(obj, flags + "--point-size " + std::to_string(size), "point").second;
    CHECK(img.count(kWhite) == size_t(size * size));
  }
  expectError("render '" + obj + "' -o " + test::tempDir() + "/p.png --point-size 17",
              "--point-size: '17' must be an integer in 1..16");
}
