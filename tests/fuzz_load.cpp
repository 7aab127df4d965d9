// fuzz_load.cpp — libFuzzer target for model loading, through the same
// clr::loadScene() the command line calls, then the camera framing the
// command line runs next.
//
// An input is one selector byte and the file's bytes. The selector picks the
// file name extension: 'o' .obj, 'p' .ply, 'f' .off, 'g' .gltf, 'b' .glb,
// 's' .stl, 'm' an MTL library (input.mtl, named by a fixed OBJ model,
// input.obj, which is what loads); any other byte picks by its value modulo 10 among those and
// names that assimp reads by content (.txt, .vrm, .dat, none), so the
// checks must follow the reader assimp chooses, not the extension. The rest
// is written to a file with that extension in the folder model/ of a scratch
// folder (FUZZ_LOAD_TMPDIR, else a fresh one under /tmp), so a crash input
// minus its first byte is a file the CLI reproduces it with. Beside the model
// lie files it may name (in.bin, in.mtl, in.png) and links to files outside
// its folder (link.bin, link.mtl, link.png to ../secret.*), whose contents
// are marked: a position of 4242, a colour of (0.125, 0.25, 0.375), a 3×5
// texture.
//
// Each input must either load, giving a mesh that keeps the loader's
// contract and holds nothing of the secret files, or fail with clr::Error
// whose message is one line starting with the file's path. Anything else
// aborts, which libFuzzer reports as a crash.
#include "render/camera.h"
#include "pipeline/cl.h"
#include "io/scene.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

namespace {

std::string gDir;  // the model's folder, model/ of the scratch folder
constexpr float kSecretPosition = 4242.0f;
// The model of an 'm' input: its library, two materials of it, one unknown.
const char* const kLibraryModel =
    "mtllib input.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nf 1/1 2/2 3/1\n"
    "usemtl a\nf 3/1 2/2 1/1\nusemtl z\nf 1/2 3/1 2/2\n";

[[noreturn]] void fail(const std::string& path, const std::string& what)
{
  std::fprintf(stderr, "fuzz_load: %s: %s\n", path.c_str(), what.c_str());
  std::fflush(stderr);
  std::abort();
}

void writeFile(const std::string& path, const std::string& bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  if (!out) fail(path, "cannot write the scratch file");
}

// An uncompressed w×h TGA of one grey.
std::string tga(int w, int h)
{
  std::string t(18, '\0');
  t[2] = 2;
  t[12] = char(w), t[14] = char(h), t[16] = 24;
  return t + std::string(size_t(3 * w * h), '\x80');
}

// The files beside the model and outside its folder (see the contract).
void makeFolders(const std::string& scratch)
{
  gDir = scratch + "/model";
  mkdir(gDir.c_str(), 0700);
  std::string positions, secret;
  for (float v : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 1.0f, 1.0f, 0.0f})
    positions.append(reinterpret_cast<const char*>(&v), sizeof v);
  for (int i = 0; i < 64; ++i) secret.append(reinterpret_cast<const char*>(&kSecretPosition), sizeof kSecretPosition);
  writeFile(gDir + "/in.bin", positions);
  writeFile(gDir + "/in.mtl", "newmtl m\nKd 1 0 0\nmap_Kd in.png\n");
  writeFile(gDir + "/in.png", tga(1, 1));
  writeFile(scratch + "/secret.bin", secret);
  std::string library;
  for (const char* name : {"m", "a", "b", "default", "DefaultMaterial"})
    library += std::string("newmtl ") + name + "\nKd 0.125 0.25 0.375\n";
  writeFile(scratch + "/secret.mtl", library);
  writeFile(scratch + "/secret.png", tga(3, 5));
  for (const char* ext : {"bin", "mtl", "png"}) {
    const std::string link = gDir + "/link." + ext;
    unlink(link.c_str());
    if (symlink((std::string("../secret.") + ext).c_str(), link.c_str()) != 0) fail(link, "cannot make the link");
  }
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
  // The model-folder rule (asset_root.h): nothing of ../secret.* is read.
  for (const float p : mesh.positions)
    if (p == kSecretPosition) fail(path, "a position from a buffer outside the model's folder");
  for (const Material& m : mesh.materials)
    if (m.baseColor[0] == 0.125f && m.baseColor[1] == 0.25f && m.baseColor[2] == 0.375f)
      fail(path, "a material from a library outside the model's folder");
  for (const clr::Texture& t : mesh.textures)
    if (t.width == 3 && t.height == 5) fail(path, "a texture from outside the model's folder");
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
    makeFolders(dir);
  } else {
    char templ[] = "/tmp/fuzz_load.XXXXXX";
    if (!mkdtemp(templ)) std::abort();
    makeFolders(templ);
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
    case 'm': ext = ".obj"; break;
  }
  const std::string path = gDir + "/input" + ext;
  const std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  if (data[0] == 'm') {
    writeFile(gDir + "/input.mtl", bytes);
    writeFile(path, kLibraryModel);
  } else {
    writeFile(path, bytes);
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
