// api_impl.h — what the public API's classes hold (their Impl structs) and
// guarded(), which every public entry point runs its body in: a
// clraster::Error passes as it is; an OpenCL failure, exhausted memory or
// another standard exception becomes a clraster::Error with the CLI's line
// (runProgram, flags.h), so no other exception leaves the library.
#pragma once

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
  } catch (const cl::Error& e) {
    throw Error(std::string("OpenCL call ") + e.what() + " failed: " + clr::clErrorName(e.err()) + " (" +
                std::to_string(e.err()) + ")");
  } catch (const std::bad_alloc&) {
    throw Error("out of host memory");
  } catch (const std::exception& e) {
    throw Error(e.what());
  }
}

// The device, and two contexts built when first needed: one whose programs
// take clip-space positions (rasterize), one for scene frames (Renderer).
// The pipelines are declared after their contexts, so they go first.
struct Context::Impl {
  std::string selector;
  DeviceInfo info;
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
