// fuzz_load.cpp — libFuzzer target for model loading, through the same
// clr::loadScene() the command line calls, then the camera framing the
// command line runs next.
//
// An input is one selector byte and the file's bytes. The selector picks the
// file name extension: 'o' .obj, 'p' .ply, 'f' .off, 'g' .gltf, 'b' .glb,
// 's' .stl; any other byte picks by its value modulo 10 among those and
// names that assimp reads by content (.txt, .vrm, .dat, none), so the
// checks must follow the reader assimp chooses, not the extension. The
// rest is written to a file with that extension in a scratch
// folder (FUZZ_LOAD_TMPDIR, else a fresh one under /tmp), so a crash input
// minus its first byte is a file the CLI reproduces it with.
//
// Each input must either load, giving a mesh that keeps the loader's
// contract, or fail with clr::Error whose message is one line starting with
// the file's path. Anything else aborts, which libFuzzer reports as a crash.
#include "render/camera.h"
#include "pipeline/cl.h"
#include "io/scene.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include <unistd.h>

namespace {

std::string gDir;

[[noreturn]] void fail(const std::string& path, const std::string& what)
{
  std::fprintf(stderr, "fuzz_load: %s: %s\n", path.c_str(), what.c_str());
  std::fflush(stderr);
  std::abort();
}

void checkMesh(const std::string& path, const clr::Mesh& mesh)
{
  if (mesh.numTris() == 0 && mesh.lines.empty() && mesh.points.empty())
    fail(path, "loaded without triangles, lines or points");
  if (mesh.positions.size() % 3 || mesh.indices.size() % 3 || mesh.lines.size() % 2) fail(path, "ragged arrays");
  if (mesh.normals.size() != mesh.positions.size()) fail(path, "normals and positions differ in length");
  for (const std::vector<uint32_t>* list : {&mesh.indices, &mesh.lines, &mesh.points})
    for (const uint32_t i : *list)
      if (i >= mesh.numVerts()) fail(path, "index " + std::to_string(i) + " out of range");
  for (const float p : mesh.positions)
    if (!std::isfinite(p)) fail(path, "non-finite position accepted");
  for (const float n : mesh.normals)
    if (!std::isfinite(n)) fail(path, "non-finite normal");
  // The CLI frames the camera on the bounds next; with default arguments that
  // must succeed for every mesh the loader accepts.
  try {
    (void)clr::frameCamera(clr::CameraArgs{}, clr::meshBounds(mesh));
  } catch (const std::exception& e) {
    fail(path, std::string("default camera framing failed: ") + e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  if (const char* dir = std::getenv("FUZZ_LOAD_TMPDIR")) {
    gDir = dir;
  } else {
    char templ[] = "/tmp/fuzz_load.XXXXXX";
    if (!mkdtemp(templ)) std::abort();
    gDir = templ;
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  if (size == 0) return 0;
  static const char* const kExtensions[] = {".obj", ".ply", ".off", ".gltf", ".glb",
                                            ".stl", ".txt", ".vrm", ".dat",  ""};
  const char* ext = kExtensions[data[0] % 10];
  switch (data[0]) {
    case 'o': ext = ".obj"; break;
    case 'p': ext = ".ply"; break;
    case 'f': ext = ".off"; break;
    case 'g': ext = ".gltf"; break;
    case 'b': ext = ".glb"; break;
    case 's': ext = ".stl"; break;
  }
  const std::string path = gDir + "/input" + ext;
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
    if (!out) fail(path, "cannot write the scratch file");
  }
  try {
    checkMesh(path, clr::loadScene(path));
  } catch (const clr::Error& e) {
    const std::string message = e.what();
    if (message.rfind(path + ": ", 0) != 0) fail(path, "error does not start with the path: " + message);
    if (message.size() <= path.size() + 2) fail(path, "error names no problem: " + message);
    for (const char c : message)
      if (static_cast<unsigned char>(c) < 0x20) fail(path, "error is not one line: " + message);
  } catch (const std::exception& e) {
    fail(path, std::string("exception other than clr::Error: ") + e.what());
  }
  return 0;
}
