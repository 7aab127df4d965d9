// api_helper.cpp — what the Python tests (tests/python) need from C++ that
// the library does not offer, as one small program:
//   api_helper oracle-ids IN OUT
//     IN: uint32 width, height, V, T; V·4 float clip positions; T·3 uint32
//     indices. OUT: width·height uint32, the scalar oracle's (reference_raster.h)
//     triangle index + 1 per pixel (0: none), bottom row first.
//   api_helper scene-dump OUT RENDER-FLAGS...
//     The scene and camera `clraster render RENDER-FLAGS` would use, as the
//     CLI loads and frames them: uint32 V, T; V·3 float positions; T·3
//     uint32 indices; the 16 floats of its mvp (column-major).
// Errors: one line on stderr, exit status 1 (runProgram).
#include "render/camera.h"
#include "render/flags.h"
#include "render/frame_request.h"
#include "reference_raster.h"
#include "io/scene.h"

#include <cstdio>
#include <fstream>

using namespace clr;

namespace {

template <typename T>
void readInto(std::ifstream& in, std::vector<T>& v, size_t n)
{
  v.resize(n);
  if (n && !in.read(reinterpret_cast<char*>(v.data()), std::streamsize(n * sizeof(T))))
    throw Error("oracle-ids: input too short");
}

template <typename T>
void write(std::ofstream& out, const T* data, size_t n)
{
  out.write(reinterpret_cast<const char*>(data), std::streamsize(n * sizeof(T)));
}

int oracleIds(const std::string& inPath, const std::string& outPath)
{
  std::ifstream in(inPath, std::ios::binary);
  std::vector<uint32_t> header;
  readInto(in, header, 4);
  std::vector<float> clip;
  std::vector<uint32_t> indices;
  readInto(in, clip, size_t(header[2]) * 4);
  readInto(in, indices, size_t(header[3]) * 3);
  ref::Options options;
  options.width = header[0];
  options.height = header[1];
  const ref::Result r = ref::rasterizeClip(clip, indices, options);
  std::vector<uint32_t> ids(r.triId.size());
  for (size_t p = 0; p < ids.size(); ++p) ids[p] = r.triId[p] == ref::kNone ? 0u : r.triId[p] + 1;
  std::ofstream out(outPath, std::ios::binary);
  write(out, ids.data(), ids.size());
  if (!out) throw Error(outPath + ": cannot write");
  return 0;
}

int sceneDump(const std::string& outPath, const std::vector<std::string>& flags)
{
  const RenderArgs args = parseRenderArgs(flags);
  const Mesh mesh = args.scenePath.empty() ? defaultScene() : loadScene(args.scenePath);
  const Camera camera = frameCamera(args.camera, meshBounds(mesh));
  const FrameSettings s = makeFrameSettings(args, camera, args.width, args.height, meshBounds(mesh));
  std::ofstream out(outPath, std::ios::binary);
  const uint32_t counts[2] = {uint32_t(mesh.numVerts()), uint32_t(mesh.numTris())};
  write(out, counts, 2);
  write(out, mesh.positions.data(), mesh.positions.size());
  write(out, mesh.indices.data(), mesh.indices.size());
  write(out, &s.mvp[0][0], 16);
  if (!out) throw Error(outPath + ": cannot write");
  return 0;
}

}  // namespace

int main(int argc, char** argv)
{
  const std::vector<std::string> args(argv + 1, argv + argc);
  return runProgram("api_helper", [&] {
    if (args.size() == 3 && args[0] == "oracle-ids") return oracleIds(args[1], args[2]);
    if (args.size() >= 2 && args[0] == "scene-dump") return sceneDump(args[1], {args.begin() + 2, args.end()});
    throw Error("usage: api_helper oracle-ids IN OUT | scene-dump OUT RENDER-FLAGS...");
  });
}
