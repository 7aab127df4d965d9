// api_impl.h — what the public API's classes hold (their Impl structs) and
// guarded(), which every public entry point runs its body in: a
// clraster::Error passes as it is; an OpenCL failure, exhausted memory or
// another standard exception becomes a clraster::Error with the CLI's line
// (failureMessage, flags.h), so no other exception leaves the library.
#pragma once

#include "base/memory.h"
#include "render/flags.h"
#include "pipeline/device.h"
#include "pipeline/diff.h"
#include "pipeline/pipeline.h"
#include "io/scene.h"

#include <clraster/clraster.hpp>

#include <memory>
#include <new>
#include <string>

namespace clraster {

template <typename F>
auto guarded(F&& body) -> decltype(body())
{
  try {
    return body();
  } catch (const Error&) {
    throw;
  } catch (const std::exception&) {
    throw Error(clr::failureMessage());
  }
}

// Host memory --aov takes beyond the frame's, checked before the planes are
// computed: the planes read back, tinyexr's copy of them and its output
// (each up to CLR_AOV_CHANNELS floats a pixel), and on a CPU device the
// planes' device buffer as well.
inline void checkAovMemory(const std::string& path, uint32_t width, uint32_t height, const clr::ClContext& cl)
{
  const uint64_t plane = uint64_t(CLR_AOV_CHANNELS) * sizeof(float) * width * height;
  clr::checkHostMemory("--aov " + clr::userText(path) + " at " + std::to_string(width) + "x" + std::to_string(height),
                       (cl.info.type == "CPU" ? 4 : 3) * plane);
}

// The device, and two contexts built when first needed: one whose programs
// take clip-space positions (rasterize), one for scene frames (Renderer).
// The pipelines are declared after their contexts, so they go first.
struct Context::Impl {
  std::string selector;
  DeviceInfo info;
  uint64_t memoryLimit = 0;  // 0: none
  std::unique_ptr<clr::ClContext> clip;
  std::unique_ptr<clr::Pipeline> clipPipeline;
  std::unique_ptr<clr::ClContext> frames;
  std::unique_ptr<clr::DiffKernels> diff;  // the backward passes, on clip (api_diff.cpp)
  clr::Pipeline& rasterPipeline();
  clr::ClContext& frameContext();
  clr::DiffKernels& diffKernels();
};

struct Scene::Impl {
  clr::Mesh mesh;
};

struct RenderOptions::Impl {
  std::vector<std::string> flags;  // as given
  clr::RenderArgs args;            // as parsed (flags.h)
};

}  // namespace clraster
