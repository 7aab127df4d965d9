// test_asset_root.cpp — the model-folder rule (asset_root.h): a texture, a
// material library or a glTF buffer outside the model's folder (by "..",
// by an absolute path, by a symbolic link) is refused with one warning or
// error naming the reference, worded as for a missing or unreadable file;
// --assets widens the root and --assets any lifts it (the library's
// Scene::load: api_test.cpp). Each case also renders
// with the rule lifted, so a test shows the file would have been read.
#include "cli_support.h"
#include "io/scene.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <string>

using Catch::Matchers::Contains;

namespace {

// A folder tree: ROOT/model (the model's folder) and ROOT/secret beside it.
std::string freshTree(const std::string& name)
{
  const std::string root = test::tempDir() + "/" + name;
  REQUIRE(std::system(("rm -rf '" + root + "' && mkdir -p '" + root + "/model/sub' '" + root + "/secret'").c_str()) ==
          0);
  return root;
}

void write(const std::string& path, const std::string& bytes)
{
  FILE* f = std::fopen(path.c_str(), "wb");
  REQUIRE(f);
  REQUIRE(std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size());
  std::fclose(f);
}

// A 1×1 uncompressed TGA of one colour (stb_image reads it).
std::string tga(unsigned char r, unsigned char g, unsigned char b)
{
  std::string t(18, '\0');
  t[2] = 2;              // uncompressed true colour
  t[12] = 1, t[14] = 1;  // 1×1
  t[16] = 24;            // bits per pixel
  return t + char(b) + char(g) + char(r);
}

// An OBJ triangle with texture coordinates whose one material names `texture`.
void texturedObj(const std::string& dir, const std::string& texture)
{
  write(dir + "/t.mtl", "newmtl m\nKd 1 1 1\nmap_Kd " + texture + "\n");
  write(dir + "/t.obj",
        "mtllib t.mtl\nv -1 -1 0\nv 1 -1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\n");
}

// The stderr line and the PNG bytes of `render MODEL --shade texture`.
struct Rendered {
  test::Run run;
  std::string png;
};
Rendered render(const std::string& model, const std::string& flags = "")
{
  const std::string out = model + ".png";
  std::remove(out.c_str());
  Rendered r{test::run("render '" + model + "' -o '" + out + "' --size 8x8 --shade texture " + flags), ""};
  r.png = test::slurp(out);
  return r;
}

// A glTF triangle whose positions come from the buffer `uri` (36 bytes).
std::string gltf(const std::string& uri)
{
  return R"({"asset": {"version": "2.0"}, "buffers": [{"uri": ")" + uri +
         R"(", "byteLength": 36}], "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})";
}

std::string trianglePositions()
{
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  return std::string(reinterpret_cast<const char*>(p), sizeof p);
}

}  // namespace

TEST_CASE("assets: a texture outside the model's folder is refused by name as a missing one is", "[assets][cli]")
{
  const std::string root = freshTree("assets-texture");
  const std::string model = root + "/model";
  write(root + "/secret/x.tga", tga(255, 0, 0));
  write(model + "/inside.tga", tga(255, 0, 0));
  REQUIRE(symlink("../secret/x.tga", (model + "/link.tga").c_str()) == 0);
  REQUIRE(symlink("inside.tga", (model + "/alias.tga").c_str()) == 0);
  write(model + "/text.tga", "not an image at all");
  // Step 1: the baselines: a texture inside the folder, and none at all.
  texturedObj(model, "inside.tga");
  const Rendered textured = render(model + "/t.obj");
  REQUIRE(textured.run.status == 0);
  REQUIRE(textured.run.err.empty());
  texturedObj(model, "alias.tga");  // a link that stays inside
  CHECK(render(model + "/t.obj").png == textured.png);
  texturedObj(model, "missing.tga");
  const Rendered missing = render(model + "/t.obj");
  REQUIRE(missing.run.status == 0);
  REQUIRE(missing.png != textured.png);
  // Step 2: every way out, and every unusable file inside: the same one
  // warning, naming the reference, and the untextured image.
  const std::string absolute = root + "/secret/x.tga";
  for (const std::string& ref : {std::string("../secret/x.tga"), absolute, std::string("link.tga"),
                                 std::string("missing.tga"), std::string("text.tga"), std::string("sub")}) {
    texturedObj(model, ref);
    const Rendered r = render(model + "/t.obj");
    INFO(ref << ": " << r.run.err);
    CHECK(r.run.status == 0);
    CHECK(std::count(r.run.err.begin(), r.run.err.end(), '\n') == 1);
    CHECK_THAT(r.run.err, Contains("t.obj: material 1: cannot use '" + ref +
                                   "': missing, unreadable, malformed or outside the model's folder (see --assets); "
                                   "rendered without the texture"));
    CHECK(r.png == missing.png);
  }
  // Step 3: --assets DIR widens the root; --assets any lifts the rule.
  texturedObj(model, "../secret/x.tga");
  const Rendered widened = render(model + "/t.obj", "--assets '" + root + "/secret'");
  CHECK(widened.run.err.empty());
  CHECK(widened.png == textured.png);
  texturedObj(model, absolute);
  const Rendered any = render(model + "/t.obj", "--assets any");
  CHECK(any.run.err.empty());
  CHECK(any.png == textured.png);
  test::expectError("render '" + model + "/t.obj' -o '" + model + "/o.png' --assets '" + root + "/none'",
                    "--assets: '" + root + "/none' is not a directory");
}

TEST_CASE("assets: a material library outside the model's folder is refused as a missing one is", "[assets][cli]")
{
  const std::string root = freshTree("assets-library");
  const std::string model = root + "/model";
  write(root + "/secret/red.mtl", "newmtl m\nKd 1 0 0\n");
  const std::string triangle = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nusemtl m\nf 1 2 3\n";
  write(model + "/out.obj", "mtllib ../secret/red.mtl\n" + triangle);
  write(model + "/none.obj", "mtllib none.mtl\n" + triangle);
  const Rendered refused = render(model + "/out.obj", "--shade flat");
  const Rendered missing = render(model + "/none.obj", "--shade flat");
  INFO(refused.run.err);
  CHECK(refused.run.status == 0);
  CHECK(std::count(refused.run.err.begin(), refused.run.err.end(), '\n') == 1);
  CHECK_THAT(refused.run.err, Contains("out.obj: cannot use '../secret/red.mtl': missing, unreadable, malformed or "
                                       "outside the model's folder (see --assets); imported without it"));
  CHECK_THAT(missing.run.err, Contains("none.obj: cannot use 'none.mtl': missing, unreadable, malformed or "
                                       "outside the model's folder (see --assets); imported without it"));
  CHECK(refused.png == missing.png);
  const Rendered any = render(model + "/out.obj", "--shade flat --assets any");
  CHECK(any.run.err.empty());
  CHECK(any.png != missing.png);  // the red material was read
}

TEST_CASE("assets: a glTF buffer outside the model's folder is an error naming the reference", "[assets][cli]")
{
  const std::string root = freshTree("assets-buffer");
  const std::string model = root + "/model/sub";
  write(root + "/secret.bin", trianglePositions());
  write(model + "/pos.bin", trianglePositions());
  REQUIRE(symlink("../../secret.bin", (model + "/link.bin").c_str()) == 0);
  write(model + "/ok.gltf", gltf("pos.bin"));
  write(model + "/up.gltf", gltf("../../secret.bin"));
  write(model + "/link.gltf", gltf("link.bin"));
  write(model + "/none.gltf", gltf("none.bin"));
  write(model + "/abs.gltf", gltf(root + "/secret.bin"));
  // Step 1: CLI: the buffer inside renders, every other one is one error line.
  CHECK(render(model + "/ok.gltf").run.status == 0);
  for (const auto& [file, ref] : {std::pair<std::string, std::string>{"up.gltf", "../../secret.bin"},
                                  {"link.gltf", "link.bin"},
                                  {"none.gltf", "none.bin"}})
    test::expectError("render '" + model + "/" + file + "' -o '" + model + "/o.png'",
                      file + ": cannot import (cannot use '" + ref +
                          "': missing, unreadable, malformed or outside the model's folder (see --assets))");
  // assimp puts the model's folder before an absolute URI: it reaches the
  // file only from a model in the working directory.
  const std::string errPath = test::tempDir() + "/assets-abs-err.txt";
  const test::Run abs = test::runShell(
      "cd '" + model + "' && '" + CLRASTER_BIN + "' render abs.gltf -o o.png 2>'" + errPath + "'", errPath);
  CHECK(abs.status == 1);
  CHECK_THAT(abs.err, Contains("abs.gltf: cannot import (cannot use '" + root + "/secret.bin': missing"));
  const test::Run absAny = test::runShell(
      "cd '" + model + "' && '" + CLRASTER_BIN + "' render abs.gltf -o o.png --assets any 2>'" + errPath + "'",
      errPath);
  CHECK(absAny.status == 0);
  // Step 2: --assets widens the root for the CLI and the library alike.
  CHECK(render(model + "/up.gltf", "--assets '" + root + "'").run.status == 0);
  CHECK_THROWS_WITH(clr::loadScene(model + "/up.gltf"), Contains("cannot use '../../secret.bin'"));
  CHECK_THROWS_WITH(clr::loadScene(model + "/link.gltf"), Contains("cannot use 'link.bin'"));
  CHECK(clr::loadScene(model + "/up.gltf", root).numTris() == 1);
  CHECK(clr::loadScene(model + "/link.gltf", "any").numTris() == 1);
  CHECK(clr::loadScene(model + "/ok.gltf").numTris() == 1);
}

TEST_CASE("assets: a texture that fails is read once however many materials name it", "[assets][texture]")
{
  const std::string root = freshTree("assets-once");
  const std::string model = root + "/model";
  std::string mtl, obj = "mtllib t.mtl\nv -1 -1 0\nv 1 -1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n";
  for (int m = 0; m < 50; ++m) {
    mtl += "newmtl m" + std::to_string(m) + "\nKd 1 1 1\nmap_Kd bad.tga\n";
    obj += "usemtl m" + std::to_string(m) + "\nf 1/1 2/2 3/3\n";
  }
  write(model + "/bad.tga", "not an image");
  write(model + "/t.mtl", mtl);
  write(model + "/t.obj", obj);
  const clr::Mesh mesh = clr::loadScene(model + "/t.obj");
  // Read and warned of once: a warning per material would fold into "(and 49 more like it)".
  REQUIRE(mesh.warnings.lines().size() == 1);
  CHECK_THAT(mesh.warnings.lines()[0], !Catch::Contains("more like it"));
  CHECK(mesh.facts.missingTextures.size() == 1);
  CHECK(mesh.materials.size() >= 50);
}
