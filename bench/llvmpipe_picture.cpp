// llvmpipe_picture.cpp — clraster_llvmpipe_picture: llvmpipe's time to picture, the peer column of bench/load.sh.
//
//   clraster_llvmpipe_picture FILE OUT.png [--size WxH]
//
// One picture of a mesh file as a plain program around Mesa llvmpipe would make it: the file read by assimp
// (aiProcess_Triangulate only, the meshes concatenated with their node transforms), smooth vertex normals
// (computeSmoothNormals, the same weld as clraster's), clraster's default framing, one lambert frame (per-pixel
// shading, llvmpipe_render.h) with no warm-up, and the image written as a PNG (image_io.h). None of clraster's
// checks or direct readers: only the renderer's own work. Prints one JSON line: read_ms (the read and the
// import), prepare_ms (normals and framing), frame_ms (context, upload and the frame), encode_ms and total_ms.
// Failures are one line on stderr and exit status 1.
#include "base/error.h"
#include "io/image_io.h"
#include "io/scene.h"
#include "llvmpipe_render.h"
#include "render/camera.h"
#include "render/flags.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>

using namespace clr;

namespace {

double msSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void append(Mesh& out, const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent)
{
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[i]];
    const uint32_t base = uint32_t(out.numVerts());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = transform * mesh.mVertices[v];
      out.positions.insert(out.positions.end(), {p.x, p.y, p.z});
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f)
      if (mesh.mFaces[f].mNumIndices == 3)
        for (unsigned k = 0; k < 3; ++k) out.indices.push_back(base + mesh.mFaces[f].mIndices[k]);
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) append(out, scene, *node.mChildren[c], transform);
}

}  // namespace

int main(int argc, char** argv)
{
  const auto start = std::chrono::steady_clock::now();
  try {
    if (argc != 3 && !(argc == 5 && std::strcmp(argv[3], "--size") == 0))
      throw Error("usage: clraster_llvmpipe_picture FILE OUT.png [--size WxH]");
    uint32_t width = 1920, height = 1080;
    if (argc == 5 && (std::sscanf(argv[4], "%ux%u", &width, &height) != 2 || width == 0 || height == 0 ||
                      width > 16384 || height > 16384))
      throw Error("--size " + userText(argv[4]) + ": expected WxH, each 1..16384");
    bench::fixHeapTrimThreshold();
    // Step 1: the file, read and imported.
    Mesh mesh;
    {
      Assimp::Importer importer;
      const aiScene* scene = importer.ReadFile(argv[1], aiProcess_Triangulate);
      if (!scene || !scene->mRootNode)
        throw Error(userText(argv[1]) + ": cannot import (" + userText(importer.GetErrorString()) + ")");
      append(mesh, *scene, *scene->mRootNode, aiMatrix4x4());
    }
    if (mesh.indices.empty()) throw Error(userText(argv[1]) + ": no triangles");
    const double readMs = msSince(start);
    // Step 2: normals and the camera.
    const auto prepareStart = std::chrono::steady_clock::now();
    computeSmoothNormals(mesh);
    const Camera camera = frameCamera(CameraArgs{}, meshBounds(mesh));
    const double prepareMs = msSince(prepareStart);
    // Step 3: one frame, context and upload included.
    const auto frameStart = std::chrono::steady_clock::now();
    const bench::LlvmpipeFrames frames =
        bench::renderLlvmpipeLambert(mesh, width, height, camera.viewProjection(width, height), camera.lightDirection(),
                                     bench::LambertShading::perPixel, 0, 1);
    const double frameMs = msSince(frameStart);
    // Step 4: the PNG.
    const auto encodeStart = std::chrono::steady_clock::now();
    writePng(argv[2], width, height, frames.image.data());
    const double encodeMs = msSince(encodeStart);
    std::printf(
        "{\"renderer\":\"%s\",\"triangles\":%zu,\"read_ms\":%.3f,\"prepare_ms\":%.3f,\"frame_ms\":%.3f,"
        "\"encode_ms\":%.3f,\"total_ms\":%.3f}\n",
        jsonEscape(frames.renderer).c_str(), mesh.numTris(), readMs, prepareMs, frameMs, encodeMs, msSince(start));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "clraster_llvmpipe_picture: %s\n", e.what());
    return 1;
  }
}
