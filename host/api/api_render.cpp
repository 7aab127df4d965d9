// api_render.cpp — the public API's scene level (clraster.hpp): Scene,
// RenderOptions, Renderer, writePng and render, the `clraster render`
// command's steps as calls. RenderOptions keeps the flags and parses them
// with the CLI's parser (flags.h), the one place that decides what a flag
// means; a Renderer frames its camera, chooses the methods and renders as
// the command does (camera.h, frame_request.h, quality.h).
#include "pipeline/aov.h"
#include "api/api_impl.h"
#include "render/camera.h"
#include "render/frame_request.h"
#include "io/image_io.h"
#include "render/quality.h"
#include "pipeline/pipeline.h"

#include <glm/glm.hpp>

#include <algorithm>

namespace clraster {

// ---- Scene ----

Scene::Scene(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

Scene Scene::load(const std::string& path, const std::string& assets)
{
  return guarded([&] {
    auto impl = std::make_unique<Impl>();
    impl->mesh = clr::loadScene(path, assets);
    return Scene(std::move(impl));
  });
}

Scene Scene::builtin()
{
  return guarded([&] {
    auto impl = std::make_unique<Impl>();
    impl->mesh = clr::defaultScene();
    return Scene(std::move(impl));
  });
}

size_t Scene::numVertices() const
{
  return impl().mesh.numVerts();
}
size_t Scene::numTriangles() const
{
  return impl().mesh.numTris();
}
const std::vector<std::string>& Scene::warnings() const
{
  return impl().mesh.warnings.lines();
}

// ---- RenderOptions ----

namespace {

// render() and Renderer::render draw one view; a views file is renderCommand's.
void checkOneView(const std::string& viewsPath)
{
  if (!viewsPath.empty()) throw Error("--views: render() draws one view; renderCommand draws a views file");
}

}  // namespace

RenderOptions::RenderOptions() : impl_(std::make_unique<Impl>())
{
  impl_->args = clr::parseRenderArgs({}, false);
}
RenderOptions::~RenderOptions() = default;
RenderOptions::RenderOptions(const RenderOptions& o) : impl_(std::make_unique<Impl>(*o.impl_)) {}
RenderOptions& RenderOptions::operator=(const RenderOptions& o)
{
  *impl_ = *o.impl_;
  return *this;
}

RenderOptions RenderOptions::parse(const std::vector<std::string>& flags)
{
  return guarded([&] {
    RenderOptions o;
    o.impl_->args = clr::parseRenderArgs(flags, false);
    o.impl_->flags = flags;
    return o;
  });
}

RenderOptions RenderOptions::parseCommandLine(const std::vector<std::string>& args)
{
  return guarded([&] {
    RenderOptions o;
    o.impl_->args = clr::parseRenderArgs(args);
    o.impl_->flags = args;
    return o;
  });
}

RenderOptions& RenderOptions::set(const std::string& flag, const std::string& value)
{
  return guarded([&]() -> RenderOptions& {
    // One flag, and its value taken by it: parsed alone, the pair names no scene.
    if (flag.empty() || flag[0] != '-')
      throw Error("RenderOptions::set: '" + clr::userText(flag) + "' is not a flag (--size, --shade, ...)");
    std::vector<std::string> pair{flag};
    if (!value.empty()) pair.push_back(value);
    if (!clr::parseRenderFlags(pair).scenePath.empty())
      throw Error(clr::userText(flag) + ": takes no value, given '" + clr::userText(value) + "'");
    std::vector<std::string> flags = impl_->flags;
    flags.insert(flags.end(), pair.begin(), pair.end());
    impl_->args = clr::parseRenderArgs(flags, false);
    impl_->flags = std::move(flags);
    return *this;
  });
}

uint32_t RenderOptions::width() const
{
  return impl_->args.width;
}
uint32_t RenderOptions::height() const
{
  return impl_->args.height;
}
const std::string& RenderOptions::scenePath() const
{
  return impl_->args.scenePath;
}
const std::string& RenderOptions::outputPath() const
{
  return impl_->args.outPath;
}
const std::string& RenderOptions::aovPath() const
{
  return impl_->args.aovPath;
}
const std::string& RenderOptions::viewsPath() const
{
  return impl_->args.viewsPath;
}
const std::string& RenderOptions::device() const
{
  return impl_->args.device;
}
uint32_t RenderOptions::frames() const
{
  return impl_->args.frames;
}
bool RenderOptions::stats() const
{
  return impl_->args.stats;
}
bool RenderOptions::idShading() const
{
  return impl_->args.shadeMode == CLR_SHADE_ID;
}

// ---- Renderer ----

struct Renderer::Impl {
  explicit Impl(clr::ClContext& cl) : cl(cl), pipeline(cl) {}
  clr::ClContext& cl;
  clr::Pipeline pipeline;
  clr::Bounds bounds;
  bool aovKept = false;
};

Renderer::Renderer(Context& ctx, const Scene& scene)
{
  guarded([&] {
    impl_ = std::make_unique<Impl>(ctx.impl().frameContext());
    const clr::Mesh& mesh = scene.impl().mesh;
    impl_->pipeline.uploadScene(mesh);
    impl_->bounds = clr::meshBounds(mesh);
  });
}
Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

Image Renderer::render(const RenderOptions& options, FrameStats* stats)
{
  return guarded([&] {
    // Step 1: camera, depth format and methods, as the render command.
    Impl& impl = *Error::live(impl_.get(), "clraster::Renderer");
    const clr::RenderArgs& args = options.impl().args;
    checkOneView(args.viewsPath);
    clr::checkCameraArgs(args.camera);
    const clr::Camera camera = clr::frameCamera(args.camera, impl.bounds);
    clr::FrameSettings settings = clr::makeFrameSettings(args, camera, args.width, args.height, impl.bounds);
    if (args.aa == "auto" || args.qualityAuto)
      clr::chooseAutomatically(impl.pipeline, settings, args.aa == "auto" || args.aa.empty(), args.qualityAuto);
    // Step 2: the frame.
    Image image;
    image.width = settings.width;
    image.height = settings.height;
    const clr::FrameStats s = impl.pipeline.render(settings, image.rgba);
    impl.aovKept = settings.keepVisAttributes;
    if (stats) {
      stats->stageMs = s.stageMs;
      stats->deviceIdleMs = s.deviceIdleMs;
      stats->trianglesIn = s.trianglesIn;
      stats->trianglesClipped = s.trianglesClipped;
      stats->trianglesCulled = s.trianglesCulled;
      stats->setupTriangles = s.setupTriangles;
      stats->binEntries = s.binEntries;
    }
    return image;
  });
}

void Renderer::writeAov(const std::string& path)
{
  guarded([&] {
    Impl& impl = *Error::live(impl_.get(), "clraster::Renderer");
    clr::checkExtension("--aov", path, ".exr");
    if (!impl.aovKept) throw Error("--aov: the last frame was rendered without --aov");
    const FrameParams& p = impl.pipeline.params();
    checkAovMemory(path, p.width, p.height, impl.cl);
    impl.pipeline.aov();
    clr::writeAovExr(path, p.width, p.height, impl.pipeline.readAov());
  });
}

void writePng(const std::string& path, const Image& image)
{
  guarded([&] {
    clr::checkExtension("-o", path, ".png");
    if (image.width == 0 || image.height == 0) throw Error(userText(path) + ": the image is empty (0 pixels)");
    if (image.rgba.size() != size_t(image.width) * image.height)
      throw Error(userText(path) + ": image holds " + std::to_string(image.rgba.size()) + " pixels, not " +
                  std::to_string(image.width) + "x" + std::to_string(image.height));
    clr::writePng(path, image.width, image.height, image.rgba);
  });
}

Image render(Context& ctx, const RenderOptions& options)
{
  return guarded([&] {
    checkOneView(options.viewsPath());
    // Outputs are checked before any device work, as the CLI does.
    if (!options.outputPath().empty()) clr::checkWritable(options.outputPath());
    if (!options.aovPath().empty()) clr::checkWritable(options.aovPath());
    const Scene scene =
        options.scenePath().empty() ? Scene::builtin() : Scene::load(options.scenePath(), options.impl().args.assets);
    Renderer renderer(ctx, scene);
    Image image = renderer.render(options);
    if (!options.outputPath().empty()) writePng(options.outputPath(), image);
    if (!options.aovPath().empty()) renderer.writeAov(options.aovPath());
    return image;
  });
}

}  // namespace clraster
