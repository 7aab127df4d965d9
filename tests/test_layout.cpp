// test_layout.cpp — the scene's layout (layout.h) changes no output: for a
// mesh in the file's order and a copy with its triangles shuffled (a fixed
// seed), with the layout and without it (Pipeline::setLayout, the pipeline
// as it was before layouts), the triangle IDs, the AOVs, the id shading and
// the shaded images are the same, IDs speaking of each file's own order, and
// an exact depth tie goes to the triangle earlier in the file; on real
// models, for every method and camera. Vertices are welded only where every
// attribute is equal. A mesh moved into the upload renders as a borrowed one
// and is left with no arrays.
#include "test_support.h"

#include "render/camera.h"
#include "render/flags.h"
#include "render/frame_request.h"
#include "pipeline/layout.h"
#include "io/scene.h"
#include "pipeline/pipeline.h"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <numeric>
#include <random>
#include <set>

namespace {

constexpr uint32_t kW = 256, kH = 192;

// What a frame shows: IDs (input triangles per pixel, as readSetup names
// them), the id shading's image, a shaded image and the AOV planes.
struct Outputs {
  std::vector<uint32_t> ids, idImage, shaded;
  std::vector<float> aov;
};

Outputs renderAll(const clr::Mesh& mesh, bool layout, const clr::FrameSettings& base, uint32_t shadeMode)
{
  clr::Pipeline pipeline(test::context());
  pipeline.setLayout(layout);
  pipeline.uploadScene(mesh);
  Outputs out;
  clr::FrameSettings s = test::keepingVis(base);
  s.shadeMode = CLR_SHADE_ID;
  pipeline.render(s, out.idImage);
  out.ids = test::readTriIds(pipeline);
  pipeline.aov();
  out.aov = pipeline.readAov();
  s.shadeMode = shadeMode;
  s.keepVisAttributes = false;
  pipeline.render(s, out.shaded);
  return out;
}

// The shuffle's order: the file triangle behind each shuffled triangle,
// found by its vertex indices (shuffledTriangles keeps each triangle's).
std::vector<uint32_t> shuffleOrder(const clr::Mesh& file, const clr::Mesh& shuffled)
{
  std::map<std::array<uint32_t, 3>, uint32_t> where;
  for (uint32_t t = 0; t < file.numTris(); ++t)
    where[{file.indices[3 * t], file.indices[3 * t + 1], file.indices[3 * t + 2]}] = t;
  std::vector<uint32_t> order(shuffled.numTris());
  for (uint32_t t = 0; t < shuffled.numTris(); ++t)
    order[t] = where.at({shuffled.indices[3 * t], shuffled.indices[3 * t + 1], shuffled.indices[3 * t + 2]});
  return order;
}

// Elements in which two outputs differ (bitwise for floats: -0 is not 0),
// or SIZE_MAX when their sizes differ.
template <typename T>
size_t differing(const std::vector<T>& a, const std::vector<T>& b)
{
  if (a.size() != b.size()) return SIZE_MAX;
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(T)) != 0;
  return n;
}

// The id image's colour of a triangle index (resolve_id: index + 1, 24 bits).
uint32_t idColour(uint32_t tri)
{
  return tri == ref::kNone ? 0xFF000000u : 0xFF000000u | ((tri + 1u) & 0xFFFFFFu);
}

// Renders one frame of two pipelines of the same mesh (without and with the
// layout) and checks that their ids and images are the same; returns how
// many pixels the frame covers.
size_t sameFrame(clr::Pipeline& before, clr::Pipeline& laid, const clr::FrameSettings& settings)
{
  std::vector<uint32_t> imageBefore, imageLaid;
  before.render(settings, imageBefore);
  laid.render(settings, imageLaid);
  const std::vector<uint32_t> ids = test::readTriIds(before);
  CHECK(differing(test::readTriIds(laid), ids) == 0);
  CHECK(differing(imageLaid, imageBefore) == 0);
  return size_t(std::count_if(ids.begin(), ids.end(), [](uint32_t id) { return id != ref::kNone; }));
}

}  // namespace

TEST_CASE("A shuffled mesh and its file order render the same with and without the layout", "[layout]")
{
  // Step 1: a real mesh (assimp's test model), framed as the CLI does, and
  // its shuffled copy.
  const std::string path = "/usr/share/assimp/models/OFF/Wuson.off";
  const clr::Mesh file = clr::loadScene(path);
  REQUIRE(file.numTris() > 1000);
  const clr::Mesh shuffled = clr::shuffledTriangles(file, 12345);
  const std::vector<uint32_t> order = shuffleOrder(file, shuffled);
  REQUIRE(std::set<uint32_t>(order.begin(), order.end()).size() == file.numTris());
  size_t moved = 0;
  for (uint32_t t = 0; t < order.size(); ++t) moved += order[t] != t;
  REQUIRE(moved > file.numTris() / 2);
  const clr::Camera camera = clr::frameCamera(clr::CameraArgs{}, clr::meshBounds(file));
  const uint32_t mode = GENERATE(CLR_SHADE_LAMBERT, CLR_SHADE_PHONG);
  clr::RenderArgs args;
  args.shadeMode = mode;
  const clr::FrameSettings settings = clr::makeFrameSettings(args, camera, kW, kH, clr::meshBounds(file));
  // Step 2: the four renders.
  const Outputs fileBefore = renderAll(file, false, settings, mode);
  const Outputs fileLaid = renderAll(file, true, settings, mode);
  const Outputs shuffledBefore = renderAll(shuffled, false, settings, mode);
  const Outputs shuffledLaid = renderAll(shuffled, true, settings, mode);
  size_t covered = 0;
  for (uint32_t id : fileBefore.ids) covered += id != ref::kNone;
  REQUIRE(covered > kW * kH / 20);
  // Step 3: the layout changes nothing of either file.
  CHECK(differing(fileLaid.ids, fileBefore.ids) == 0);
  CHECK(differing(fileLaid.idImage, fileBefore.idImage) == 0);
  CHECK(differing(fileLaid.shaded, fileBefore.shaded) == 0);
  CHECK(differing(fileLaid.aov, fileBefore.aov) == 0);
  CHECK(differing(shuffledLaid.ids, shuffledBefore.ids) == 0);
  CHECK(differing(shuffledLaid.idImage, shuffledBefore.idImage) == 0);
  CHECK(differing(shuffledLaid.shaded, shuffledBefore.shaded) == 0);
  CHECK(differing(shuffledLaid.aov, shuffledBefore.aov) == 0);
  // Step 4: the shuffled file shows the same triangles by its own numbers,
  // the same pixels and the same AOVs but for the triangle id plane.
  std::vector<uint32_t> mapped(shuffledLaid.ids.size());
  std::vector<uint32_t> mappedImage(mapped.size());
  for (size_t p = 0; p < mapped.size(); ++p) {
    const uint32_t id = shuffledLaid.ids[p];
    mapped[p] = id == ref::kNone ? ref::kNone : order.at(id);
  }
  CHECK(differing(mapped, fileBefore.ids) == 0);
  // (the id image is top row first, the ids bottom row first)
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const uint32_t id = shuffledLaid.idImage[size_t(kH - 1 - y) * kW + x];
      const uint32_t tri = (id & 0xFFFFFFu) == 0 ? ref::kNone : order.at((id & 0xFFFFFFu) - 1);
      mappedImage[size_t(kH - 1 - y) * kW + x] = idColour(tri);
    }
  CHECK(differing(mappedImage, fileBefore.idImage) == 0);
  CHECK(differing(shuffledLaid.shaded, fileBefore.shaded) == 0);
  const size_t plane = size_t(kW) * kH;
  std::vector<float> aov = shuffledLaid.aov;
  for (size_t p = 0; p < plane; ++p) {
    const float id = aov[CLR_AOV_TRIANGLE_ID * plane + p];
    aov[CLR_AOV_TRIANGLE_ID * plane + p] = id < 0.0f ? id : float(order.at(uint32_t(id)));
  }
  CHECK(differing(aov, fileBefore.aov) == 0);
}

TEST_CASE("The layout changes no output of real models for any method or camera", "[layout]")
{
  // Step 1: assimp's test models of several kinds: textured (spider,
  // milk truck), many materials and parts (engine), a building of large
  // triangles (IFC house), quads and fans (Wuson). Each in its file's order
  // and shuffled, the cameras: the CLI's framing, an eye inside the model
  // (near-plane clipping) and one grazing its side.
  const std::string models = "/usr/share/assimp/models/";
  const std::string file =
      GENERATE(as<std::string>{}, "OFF/Wuson.off", "OBJ/spider.obj", "glTF/CesiumMilkTruck/CesiumMilkTruck.gltf",
               "IFC/AC14-FZK-Haus.ifc", "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
  const bool shuffle = GENERATE(false, true);
  INFO(file << (shuffle ? ", shuffled" : ""));
  const clr::Mesh loaded = clr::loadScene(models + file);
  const clr::Mesh mesh = shuffle ? clr::shuffledTriangles(loaded, 7) : loaded;
  REQUIRE(mesh.numTris() > 100);
  clr::Pipeline before(test::context()), laid(test::context());
  before.setLayout(false);
  before.uploadScene(mesh);
  laid.uploadScene(mesh);
  const clr::Bounds bounds = clr::meshBounds(mesh);
  // Step 2: every method and output that reads the records: the ids, the
  // AOVs and the image of each.
  const std::vector<std::vector<std::string>> methods = {{},
                                                         {"--shade", "id"},
                                                         {"--aa", "msaa4"},
                                                         {"--aa", "ssaa4"},
                                                         {"--wireframe"},
                                                         {"--visibility", "painter"},
                                                         {"--shade", "texture"},
                                                         {"--traversal", "spans"},
                                                         {"--traversal", "hierarchical"},
                                                         {"--edges", "float"},
                                                         {"--depth", "unorm24"},
                                                         {"--shade", "normal", "--interp", "affine"}};
  size_t covered = 0;
  const std::vector<clr::Camera> views = test::modelViews(bounds);
  for (size_t view = 0; view < views.size(); ++view) {
    const clr::Camera& camera = views[view];
    for (std::vector<std::string> words : methods) {
      std::string method = "default";
      for (size_t w = 0; w < words.size(); ++w) method = (w ? method + " " : std::string()) + words[w];
      INFO("view " << view << ", method " << method);
      words.insert(words.end(), {"-o", "x.png"});
      const clr::FrameSettings settings =
          test::keepingVis(clr::makeFrameSettings(clr::parseRenderArgs(words), camera, 160, 120, bounds));
      covered += sameFrame(before, laid, settings);
      if (settings.wireframe == CLR_WIREFRAME_OFF) {  // (the AOVs are of triangles only)
        before.aov();
        laid.aov();
        CHECK(differing(laid.readAov(), before.readAov()) == 0);
      }
    }
  }
  CHECK(covered > 3 * methods.size() * 160 * 120 / 50);  // the views are not empty
}

// Whether vertex a of mesh x and vertex b of mesh y agree bit for bit in
// every attribute.
bool sameVertex(const clr::Mesh& x, uint32_t a, const clr::Mesh& y, uint32_t b)
{
  const auto same = [](const std::vector<float>& p, uint32_t i, const std::vector<float>& q, uint32_t j, size_t n) {
    return (p.empty() && q.empty()) || std::memcmp(&p[n * i], &q[n * j], n * sizeof(float)) == 0;
  };
  return same(x.positions, a, y.positions, b, 3) && same(x.normals, a, y.normals, b, 3) &&
         same(x.uvs, a, y.uvs, b, 2) && same(x.colors, a, y.colors, b, 4);
}

TEST_CASE("The layout welds vertices equal in every attribute and no others", "[layout]")
{
  // Step 1: a file whose faces have vertices of their own (as assimp loads
  // OBJ, STL and Blender files): a shuffled grid of quads, each corner
  // repeated per triangle, with lines and points on the repeats. Some
  // repeats differ in one bit of one attribute: -0 against 0 in the normal,
  // the texture coordinate or colour one ulp apart; those stay apart.
  clr::Mesh file;
  constexpr int kSide = 40;
  std::mt19937 random(5);
  const auto corner = [&](int i, int j, uint32_t variant) {
    file.positions.insert(file.positions.end(), {float(i), float(j), 0.5f * float((i * j) % 3)});
    file.normals.insert(file.normals.end(), {0.0f, variant == 1 ? -0.0f : 0.0f, 1.0f});
    file.uvs.insert(file.uvs.end(), {float(i) / kSide, variant == 2 ? std::nextafter(0.25f, 1.0f) : 0.25f});
    file.colors.insert(file.colors.end(), {1.0f, 0.5f, variant == 3 ? std::nextafter(0.5f, 1.0f) : 0.5f, 1.0f});
    return uint32_t(file.numVerts() - 1);
  };
  std::vector<std::array<uint32_t, 3>> tris;
  for (int i = 0; i < kSide; ++i)
    for (int j = 0; j < kSide; ++j) {
      const uint32_t variant = random() % 8;  // 1..3: one corner differs
      tris.push_back({corner(i, j, 0), corner(i + 1, j, 0), corner(i + 1, j + 1, variant)});
      tris.push_back({corner(i, j, 0), corner(i + 1, j + 1, 0), corner(i, j + 1, 0)});
    }
  std::shuffle(tris.begin(), tris.end(), random);
  for (const auto& t : tris) file.indices.insert(file.indices.end(), t.begin(), t.end());
  file.lines = {file.indices[0], file.indices[4], file.indices[7], file.indices[9]};
  file.points = {file.indices[5], file.indices[11], corner(kSide + 1, 0, 0)};  // the last one only a point's
  std::vector<uint32_t> weld;
  const size_t distinct = clr::weldVertices(file, weld);
  std::set<std::vector<float>> kinds;  // the distinct vertices, counted independently
  for (uint32_t v = 0; v < file.numVerts(); ++v) {
    std::vector<float> key(&file.positions[3 * v], &file.positions[3 * v + 3]);
    key.push_back(std::signbit(file.normals[3 * v + 1]) ? 1.0f : 0.0f);
    key.insert(key.end(), &file.uvs[2 * v], &file.uvs[2 * v + 2]);
    key.insert(key.end(), &file.colors[4 * v], &file.colors[4 * v + 4]);
    kinds.insert(key);
  }
  REQUIRE(distinct == kinds.size());
  REQUIRE(distinct < file.numVerts() / 3);              // 6 corners per quad, about 1.4 distinct
  REQUIRE(distinct > size_t(kSide + 1) * (kSide + 1));  // the variants stayed apart
  // Step 2: the laid-out copy holds the distinct vertices, and each corner,
  // line end and point names one equal to the file's, bit for bit.
  const clr::SceneLayout layout = clr::layOutScene(file);
  const clr::Mesh& laid = layout.mesh;
  CHECK(laid.numVerts() == distinct);
  CHECK(laid.normals.size() == 3 * distinct);
  CHECK(laid.uvs.size() == 2 * distinct);
  CHECK(laid.colors.size() == 4 * distinct);
  REQUIRE(layout.laidVertex.size() == file.numVerts());
  size_t unequal = 0;
  for (uint32_t v = 0; v < file.numVerts(); ++v) {
    unequal += !sameVertex(file, v, laid, layout.laidVertex[v]);
    unequal += weld[v] != weld[layout.fileVertex[layout.laidVertex[v]]];
  }
  for (uint32_t t = 0; t < laid.numTris(); ++t)
    for (int k = 0; k < 3; ++k)
      unequal += !sameVertex(file, file.indices[3 * layout.fileTri[t] + k], laid, laid.indices[3 * t + k]);
  REQUIRE(laid.lines.size() == file.lines.size());
  REQUIRE(laid.points.size() == file.points.size());
  for (size_t i = 0; i < file.lines.size(); ++i) unequal += !sameVertex(file, file.lines[i], laid, laid.lines[i]);
  for (size_t i = 0; i < file.points.size(); ++i) unequal += !sameVertex(file, file.points[i], laid, laid.points[i]);
  CHECK(unequal == 0);
  // Step 3: without the layout nothing is welded.
  CHECK(clr::layOutScene(file, false).mesh.numVerts() == file.numVerts());
}

TEST_CASE("A welded OBJ file holds fewer bytes and reads back the file's clip positions", "[layout]")
{
  // assimp's OBJ import gives each face corner a vertex of its own.
  const clr::Mesh file = clr::loadScene("/usr/share/assimp/models/OBJ/WusonOBJ.obj");
  std::vector<uint32_t> weld;
  const size_t distinct = clr::weldVertices(file, weld);
  REQUIRE(distinct < file.numVerts() / 2);
  const clr::Camera camera = clr::frameCamera(clr::CameraArgs{}, clr::meshBounds(file));
  const clr::FrameSettings settings = clr::makeFrameSettings(clr::RenderArgs{}, camera, kW, kH, clr::meshBounds(file));
  std::vector<cl_float4> clip[2];
  std::vector<uint32_t> image[2];
  size_t bytes[2];
  for (int layout = 0; layout < 2; ++layout) {
    clr::Pipeline pipeline(test::context());
    pipeline.setLayout(layout == 1);
    pipeline.uploadScene(file);
    pipeline.render(settings, image[layout]);
    bytes[layout] = pipeline.deviceBytes();
    pipeline.transform();
    clip[layout] = pipeline.readClipPositions();
  }
  // Positions and normals of the vertices welded away, at least.
  CHECK(bytes[0] - bytes[1] >= 24 * (file.numVerts() - distinct));
  CHECK(differing(image[1], image[0]) == 0);
  REQUIRE(clip[1].size() == file.numVerts());
  CHECK(differing(clip[1], clip[0]) == 0);
}

TEST_CASE("The layout changes no output of any model assimp's corpus renders", "[layout]")
{
  // Every file the CLI renders in Debian's assimp-testmodels (the corpus
  // test's expected list, tests/assimp_corpus_expected.txt), framed as the
  // CLI frames it: with and without the layout (sorted triangles, welded
  // vertices), the ids, the lambert and the textured image bit for bit.
  std::ifstream list(CLRASTER_CORPUS_LIST);
  REQUIRE(list);
  size_t models = 0, welded = 0, covered = 0;
  for (std::string line; std::getline(list, line);) {
    const size_t tab = line.find('\t');
    if (line.empty() || line[0] == '#' || tab == std::string::npos || line.substr(tab + 1) != "ok") continue;
    const std::string path = "/usr/share/assimp/models/" + line.substr(0, tab);
    INFO(path);
    const clr::Mesh mesh = clr::loadScene(path);
    if (mesh.numTris() < 2) continue;  // (the layout keeps a lone triangle as it is)
    ++models;
    std::vector<uint32_t> weld;
    welded += clr::weldVertices(mesh, weld) < mesh.numVerts() && mesh.numVerts() > mesh.numTris();
    clr::Pipeline before(test::context()), laid(test::context());
    before.setLayout(false);
    before.uploadScene(mesh);
    laid.uploadScene(mesh);
    const clr::Bounds bounds = clr::meshBounds(mesh);
    const clr::Camera camera = clr::frameCamera(clr::CameraArgs{}, bounds);
    for (const char* shade : {"lambert", "texture"}) {
      INFO(shade);
      const clr::FrameSettings settings = test::keepingVis(
          clr::makeFrameSettings(clr::parseRenderArgs({"--shade", shade, "-o", "x.png"}), camera, 64, 48, bounds));
      covered += sameFrame(before, laid, settings);
    }
  }
  CHECK(models > 250);
  CHECK(welded > 50);  // files whose faces have vertices of their own
  CHECK(covered > models * 64 * 48 / 10);
}

TEST_CASE("An exact depth tie goes to the triangle earlier in the file under the layout", "[layout]")
{
  // Step 1: overlapping random triangles all in the plane z = 0.25 (an
  // identity MVP: every fragment of every triangle ties in depth), in a file
  // order far from spatial, so the layout sorts them.
  std::mt19937 random(31);
  std::uniform_real_distribution<float> centre(-1.0f, 1.0f), offset(-0.3f, 0.3f);
  test::Geometry g;
  for (int t = 0; t < 2000; ++t) {
    const glm::vec3 c(centre(random), centre(random), 0.25f);
    glm::vec3 v[3];
    for (glm::vec3& p : v) p = c + glm::vec3(offset(random), offset(random), 0.0f);
    g.addTriangle(v[0], v[1], v[2]);
  }
  const clr::Mesh file = g.mesh();
  const clr::SceneLayout layout = clr::layOutScene(file);
  size_t reordered = 0;
  for (uint32_t t = 0; t < layout.fileTri.size(); ++t) reordered += layout.fileTri[t] != t;
  REQUIRE(reordered > file.numTris() / 2);
  const uint32_t depthMode = GENERATE(CLR_DEPTH_FLOAT32, CLR_DEPTH_UNORM24);
  clr::FrameSettings settings = test::idSettings(kW, kH);
  settings.depthMode = depthMode;
  // Step 2: with and without the layout, the same IDs, the oracle's: each
  // covered pixel shows the earliest triangle of the file that covers it.
  const Outputs before = renderAll(file, false, settings, CLR_SHADE_LAMBERT);
  const Outputs laid = renderAll(file, true, settings, CLR_SHADE_LAMBERT);
  CHECK(differing(laid.ids, before.ids) == 0);
  CHECK(differing(laid.idImage, before.idImage) == 0);
  CHECK(differing(laid.aov, before.aov) == 0);
  ref::Options options;
  options.width = kW;
  options.height = kH;
  options.depthMode = depthMode;
  const ref::Result expected = ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), options);
  CHECK(differing(laid.ids, expected.triId) == 0);
  size_t later = 0;  // pixels won by a triangle that is not the file's first (ties decided)
  for (uint32_t id : laid.ids) later += id != ref::kNone && id > 0;
  CHECK(later > kW * kH / 4);
}

TEST_CASE("A frame with nothing in view launches no raster and keeps an image already its background",
          "[layout][resolve]")
{
  // One triangle over the middle of a 64 x 48 viewport (identity MVP); a
  // translation moves it out of view.
  test::Geometry g;
  g.addTriangle({-0.5f, -0.5f, 0.0f}, {0.5f, -0.5f, 0.0f}, {0.0f, 0.5f, 0.0f});
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  clr::FrameSettings shown = test::idSettings(64, 48);
  shown.shadeMode = CLR_SHADE_LAMBERT;
  clr::FrameSettings away = shown;
  away.mvp = glm::translate(glm::mat4(1.0f), glm::vec3(5.0f, 0.0f, 0.0f));
  std::vector<uint32_t> image;
  auto frame = [&](const clr::FrameSettings& s) {
    const clr::FrameStats stats = pipeline.render(s, image);
    CHECK(stats.stageMs.count("resolve") == 1);
    // Work follows what is in view: nothing binned, no emit and no raster launched (but in a frame sized from
    // the last one's, which launches them before its totals are known: Pipeline::runFrame).
    CHECK(stats.stageMs.count("raster") == stats.stageMs.count("setup_emit"));
    CHECK(stats.stageMs.count("raster") == (stats.binEntries > 0 || stats.speculative ? 1u : 0u));
    return stats.imageKept;
  };
  auto all = [&](uint32_t colour) { return std::count(image.begin(), image.end(), colour) == long(image.size()); };
  const uint32_t lit = CLR_BACKGROUND_LIT;
  // Step 1: the first empty frame paints; the next keeps.
  CHECK_FALSE(frame(away));
  CHECK(all(lit));
  CHECK(frame(away));
  CHECK(all(lit));
  // Step 2: a covered frame, then an empty one must paint again; the covered
  // frame after them is the same image.
  CHECK_FALSE(frame(shown));
  CHECK_FALSE(all(lit));
  const std::vector<uint32_t> shownImage = image;
  CHECK_FALSE(frame(away));
  CHECK(all(lit));
  CHECK(frame(away));
  CHECK_FALSE(frame(shown));
  CHECK(image == shownImage);
  CHECK_FALSE(frame(away));
  CHECK(frame(away));
  // Step 3: another background (the id mode's) or another size paints.
  clr::FrameSettings idAway = away;
  idAway.shadeMode = CLR_SHADE_ID;
  CHECK_FALSE(frame(idAway));
  CHECK(all(CLR_BACKGROUND_UNLIT));
  CHECK(frame(idAway));
  clr::FrameSettings smaller = test::keepingVis(idAway);  // (lines test against the depth plane)
  smaller.width = 32;
  CHECK_FALSE(frame(smaller));
  CHECK(image.size() == 32u * 48u);
  CHECK(all(CLR_BACKGROUND_UNLIT));
  // Step 4: lines drawn over the image make the next empty frame paint.
  CHECK(frame(smaller));
  pipeline.lines({LineSeg{}});
  CHECK_FALSE(frame(smaller));
  CHECK(all(CLR_BACKGROUND_UNLIT));
}

TEST_CASE("Tiles left as background are repainted only when the image changed under them", "[layout][resolve]")
{
  // A triangle moved between tiles, shade modes, sizes and a wireframe: every
  // frame of one pipeline equals the same frame from a fresh pipeline, so the
  // tiles resolve skips as already background (tileBlank) always are.
  test::Geometry g;
  g.addTriangle({-0.9f, -0.9f, 0.0f}, {-0.5f, -0.9f, 0.0f}, {-0.7f, -0.5f, 0.0f});
  clr::FrameSettings base = test::idSettings(96, 64);
  base.shadeMode = CLR_SHADE_LAMBERT;
  auto moved = [&](float dx, float dy) {
    clr::FrameSettings s = base;
    s.mvp = glm::translate(glm::mat4(1.0f), glm::vec3(dx, dy, 0.0f));
    return s;
  };
  std::vector<clr::FrameSettings> frames = {moved(0, 0), moved(1.2f, 0), moved(1.2f, 1.2f),
                                            moved(0, 0), moved(5, 0),    moved(0.6f, 0.6f)};
  clr::FrameSettings unlit = moved(1.2f, 0);
  unlit.shadeMode = CLR_SHADE_NORMAL;
  frames.push_back(unlit);
  frames.push_back(moved(0, 0));
  clr::FrameSettings wire = test::keepingVis(moved(0.6f, 0));
  wire.wireframe = CLR_WIREFRAME_OVERLAY;
  frames.push_back(wire);
  frames.push_back(test::keepingVis(moved(0, 1.2f)));
  clr::FrameSettings wider = moved(0, 0);
  wider.width = 128;
  frames.push_back(wider);
  frames.push_back(moved(1.2f, 1.2f));
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  for (size_t i = 0; i < frames.size(); ++i) {
    INFO("frame " << i);
    std::vector<uint32_t> image, fresh;
    pipeline.render(frames[i], image);
    clr::Pipeline once(test::context());
    once.uploadScene(g.mesh());
    once.render(frames[i], fresh);
    CHECK(image == fresh);
  }
}

TEST_CASE("A mesh moved into the upload renders as a borrowed one and its arrays are freed", "[layout][memory]")
{
  // Files without texture coordinates (their zeros are not laid out), with
  // textures and materials, and points only (positions kept for them);
  // shuffled, so that the layout reorders. The methods read the freed host
  // copies' replacements: normals and AOVs after the normals' upload, the
  // painter's indices read back, the id shading's file order.
  const std::string models = "/usr/share/assimp/models/";
  const std::string file = GENERATE(as<std::string>{}, "OFF/Wuson.off", "OBJ/spider.obj", "PLY/points.ply");
  INFO(file);
  const clr::Mesh loaded = clr::loadScene(models + file);
  const clr::Mesh mesh = loaded.numTris() > 1 ? clr::shuffledTriangles(loaded, 9) : loaded;
  clr::Pipeline borrowed(test::context()), consumed(test::context());
  borrowed.uploadScene(mesh);
  clr::Mesh moved = mesh;
  consumed.uploadScene(std::move(moved));
  for (const auto* array : {&moved.positions, &moved.normals, &moved.uvs, &moved.colors}) CHECK(array->capacity() == 0);
  for (const auto* array : {&moved.indices, &moved.triMaterial, &moved.lines, &moved.points})
    CHECK(array->capacity() == 0);
  const clr::Bounds bounds = clr::meshBounds(mesh);
  const clr::Camera camera = clr::frameCamera(clr::CameraArgs{}, bounds);
  const std::vector<std::vector<std::string>> methods = {{"--shade", "normal"},  {},
                                                         {"--shade", "texture"}, {"--visibility", "painter"},
                                                         {"--shade", "id"},      {"--wireframe"}};
  for (std::vector<std::string> words : methods) {
    std::string method = "default";
    for (size_t w = 0; w < words.size(); ++w) method = (w ? method + " " : std::string()) + words[w];
    INFO(method);
    words.insert(words.end(), {"-o", "x.png"});
    const clr::FrameSettings settings =
        test::keepingVis(clr::makeFrameSettings(clr::parseRenderArgs(words), camera, 160, 120, bounds));
    const size_t covered = sameFrame(borrowed, consumed, settings);  // (ids count triangles: points have none)
    CHECK((covered > 0 || mesh.numTris() == 0));
    if (settings.wireframe == CLR_WIREFRAME_OFF) {
      borrowed.aov();
      consumed.aov();
      CHECK(differing(consumed.readAov(), borrowed.readAov()) == 0);
    }
  }
}
