// device_scene.h — a scene on the device: its laid-out host copy and the
// buffers of its vertices, triangles, materials and textures.
//
// DeviceScene places a scene (layout.h's order, positions, indices and the
// setup clusters' bounds at once) or the library's clip-space input, and
// uploads the other attributes when a frame's shading first reads them
// (bindAttributes). It owns the context's memory account, so deviceBytes
// counts the frame's buffers too (Pipeline, pipeline.h, derives from it).
#pragma once

#include "pipeline/buffer.h"
#include "pipeline/device.h"
#include "pipeline/frame_settings.h"
#include "pipeline/layout.h"
#include "io/scene.h"

#include "kernels/shared.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace clr {

class DeviceScene {
 public:
  explicit DeviceScene(ClContext& cl);
  DeviceScene(const DeviceScene&) = delete;
  DeviceScene& operator=(const DeviceScene&) = delete;

  // Whether a scene is laid out (default); tests compare with the file's own order.
  void setLayout(bool on) { layoutOn_ = on; }
  // The milliseconds of the last uploadScene: the layout, the cluster bounds
  // and the uploads (--stats prepare_ms).
  double prepareMs() const { return prepareMs_; }

  // What is on the device now, kResident* bits (for tests).
  enum : uint32_t {
    kResidentNormals = 1,
    kResidentUvs = 2,
    kResidentColors = 4,
    kResidentMaterials = 8,  // the materials, and each triangle's unless they are all one
    kResidentTextures = 16,  // descriptors and texels, once per scene
  };
  uint32_t resident() const { return resident_; }
  size_t deviceBytes() const { return memory_.bytesAllocated; }
  DeviceMemory& memory() { return memory_; }  // its limits (buffer.h)
  const ClContext& cl() const { return cl_; }

 protected:
  // Lays a checked mesh out and uploads its positions, indices and cluster
  // bounds; the other attributes wait for bindAttributes.
  void placeScene(const Mesh& mesh);
  // The same from a mesh it may consume (layOutScene's Mesh&& form).
  void placeScene(Mesh&& mesh);
  // Both placeScenes' upload of the laid-out scene.
  void placeLaidOut(SceneLayout&& layout);
  // The library's clip-space positions (4 floats a vertex) and triangles, in the caller's order, no clusters.
  void placeClipScene(const float* positions, size_t numVerts, const uint32_t* indices, size_t numTris);
  // Uploads what this frame's shading reads and is not resident yet, and
  // returns the FrameParams.sceneFlags it binds.
  uint32_t bindAttributes(const FrameSettings& settings);
  // FrameParams.clusterMargin for the view of `mvp`: 0 (no cluster test)
  // for an empty scene or one whose clip coordinates overflow.
  float clusterMargin(const glm::mat4& mvp) const;

  ClContext& cl_;
  DeviceMemory memory_;
  // Host copy, laid out: lazy uploads read it. Its indices, its positions
  // (unless it has lines or points), a triMaterial of one material and,
  // once uploaded, its normals are freed: the device holds them
  // (sceneVerts_ and sceneTris_ count them).
  Mesh scene_;
  size_t sceneVerts_ = 0, sceneTris_ = 0;
  bool layoutOn_ = true;
  double prepareMs_ = 0;
  uint64_t sceneUploads_ = 0;                       // counts placed scenes: part of PrefetchChooser's case
  std::vector<uint32_t> fileTriHost_, laidVertex_;  // the layout's maps (layout.h)
  bool fileOrder_ = false;                          // fileTriHost_ is the identity: fileTri_ is not bound
  uint32_t resident_ = 0;                           // kResident* bits
  bool triMaterials_ = false;                       // the scene came with a material per triangle (bindAttributes)
  bool oneMaterial_ = true;                         // all of them firstMaterial_ (scene_.triMaterial then freed)
  uint32_t firstMaterial_ = 0;
  DeviceBuffer<float> positions_, normals_, uvs_, colors_;
  DeviceBuffer<float> clusterBounds_;    // setup's clusters (shared.h), CPU work shape; one dummy bound on a GPU
  DeviceBuffer<uint32_t> clusterCount_;  // their setup counts' sums (shared.h), CPU work shape; else a dummy
  // The bounds of the scene's finite vertices (empty: min > max), for
  // FrameParams.clusterMargin.
  glm::vec3 sceneMin_{0.0f}, sceneMax_{-1.0f};
  DeviceBuffer<uint32_t> indices_, triMaterial_;
  DeviceBuffer<uint32_t> fileTri_;  // each laid-out triangle's index in the file (shared.h)
  DeviceBuffer<Material> materials_;
  DeviceBuffer<TextureDesc> texDescs_;
  DeviceBuffer<uint32_t> texels_;
};

}  // namespace clr
