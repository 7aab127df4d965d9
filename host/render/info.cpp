// info.cpp — the `info` command (see info.h).
#include "render/info.h"

#include "render/camera.h"
#include "base/error.h"
#include "base/warnings.h"
#include "render/flags.h"
#include "io/scene.h"

#include <nlohmann/json.hpp>

#include <climits>
#include <cstdio>
#include <cstdlib>

namespace clr {

namespace {

using Json = nlohmann::json;

std::string formatFloat(float v)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", double(v));
  return text;
}

std::string formatVec3(glm::vec3 v)
{
  return formatFloat(v.x) + "," + formatFloat(v.y) + "," + formatFloat(v.z);
}

// A JSON number that prints as %.9g does: parsed back from that text.
Json jsonFloat(float v)
{
  return Json::parse(formatFloat(v));
}

Json jsonVec3(glm::vec3 v)
{
  return Json::array({jsonFloat(v.x), jsonFloat(v.y), jsonFloat(v.z)});
}

std::string normalsText(const MeshFacts& f)
{
  if (!f.normalsInFile) return "computed (none in file)";
  if (f.normalsRepaired == 0) return "from file";
  return "from file, " + std::to_string(f.normalsRepaired) + " repaired (zero, NaN or missing)";
}

}  // namespace

int infoCommand(const std::vector<std::string>& args)
{
  // Step 1: arguments: one MESH, --fov, --json, --assets.
  std::string path, assets;
  CameraArgs cameraArgs;
  bool json = false, fovGiven = false;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--json") {
      json = true;
    } else if (args[i] == "--assets") {
      assets = flagValue(args, i);
      if (assets.empty()) throw Error("--assets: empty path (a directory, or 'any')");
    } else if (args[i] == "--fov") {
      cameraArgs.fovDegrees = parseFloat("--fov", flagValue(args, i));
      fovGiven = true;
    } else {
      takeScenePath(args[i], path);
    }
  }
  if (path.empty()) throw Error("info: missing MESH (clraster info MESH [--fov DEG] [--json])");
  checkCameraArgs(cameraArgs);
  // Step 2: the mesh and its default camera, as `render` frames it.
  const Mesh mesh = loadScene(path, assets);
  const Bounds bounds = meshBounds(mesh);
  const Camera cam = frameCamera(cameraArgs, bounds);
  const glm::vec3 centre = 0.5f * (bounds.min + bounds.max);
  const float radius = 0.5f * glm::length(bounds.max - bounds.min);
  std::string flags = "--eye " + formatVec3(cam.eye) + " --target " + formatVec3(cam.target) + " --up " +
                      formatVec3(cam.up) + " --near " + formatFloat(cam.zNear) + " --far " + formatFloat(cam.zFar);
  if (fovGiven) flags += " --fov " + formatFloat(cam.fovDegrees);
  const MeshFacts& f = mesh.facts;
  const size_t textures = mesh.textures.size();
  // Step 3: the report.
  if (json) {
    Json j;
    j["file"] = path;
    j["triangles"] = mesh.numTris();
    j["vertices"] = mesh.numVerts();
    j["lines"] = mesh.lines.size() / 2;
    j["points"] = mesh.points.size();
    j["bounds"] = {{"min", jsonVec3(bounds.min)},
                   {"max", jsonVec3(bounds.max)},
                   {"centre", jsonVec3(centre)},
                   {"radius", jsonFloat(radius)}};
    j["materials"] = mesh.materials.size();
    j["textures"] = textures;
    std::vector<std::string> listed;  // the first ones, within the warnings' bound; then the count of all
    size_t bytes = 0;
    for (const std::string& m : f.missingTextures)
      if ((bytes += m.size()) <= Warnings::kMaxBytes) listed.push_back(m);
    j["missing_textures"] = listed;
    j["missing_textures_total"] = f.missingTextures.size();
    j["normals"] = {{"in_file", f.normalsInFile}, {"repaired", f.normalsRepaired}};
    j["uvs"] = {{"in_file", f.uvsInFile}};
    j["camera"] = {{"eye", jsonVec3(cam.eye)},   {"target", jsonVec3(cam.target)},
                   {"up", jsonVec3(cam.up)},     {"near", jsonFloat(cam.zNear)},
                   {"far", jsonFloat(cam.zFar)}, {"fov", jsonFloat(cam.fovDegrees)}};
    j["render_flags"] = flags;
    j["warnings"] = mesh.warnings.lines();
    std::printf("%s\n", j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
    return 0;
  }
  std::printf("file       %s\n", userText(path, PATH_MAX).c_str());
  std::printf("triangles  %zu\nvertices   %zu\nlines      %zu\npoints     %zu\n", mesh.numTris(), mesh.numVerts(),
              mesh.lines.size() / 2, mesh.points.size());
  std::printf("bounds     min %s  max %s\n", formatVec3(bounds.min).c_str(), formatVec3(bounds.max).c_str());
  std::printf("           centre %s  radius %s\n", formatVec3(centre).c_str(), formatFloat(radius).c_str());
  std::printf("materials  %zu, textures %zu loaded, %zu missing\n", mesh.materials.size(), textures,
              f.missingTextures.size());
  Warnings missing;  // bounded as warnings are
  for (const std::string& m : f.missingTextures) missing.add("missing texture: " + userText(m));
  for (const std::string& line : missing.lines()) std::printf("  %s\n", line.c_str());
  std::printf("normals    %s\n", normalsText(f).c_str());
  std::printf("uvs        %s\n", f.uvsInFile ? "from file" : "none (texture coordinates read 0,0)");
  for (const std::string& w : mesh.warnings.lines()) std::printf("warning    %s\n", w.c_str());
  std::printf("default camera (paste into clraster render):\n  %s\n", flags.c_str());
  return 0;
}

}  // namespace clr
