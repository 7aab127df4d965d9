// lines.cpp — host side of kernels/lines.cl: line segments from the setup
// triangles (the wireframe) or from the caller, binned into the triangles'
// tiles (count, scan, fill, as bin.cpp) and drawn per tile into the image
// after resolve, depth-tested against sample 0 of the visibility buffer.
//
// Constants of the method (README, "Wireframe and lines"): overlay lines are
// orange (255, 140, 0), lines alone white on the shading mode's background;
// the depth test's constant offset is 2^-16 in window depth, and its slope
// term reaches LineParams.reach + 0.75 pixels.
#include "pipeline/pipeline.h"

#include <cmath>

namespace clr {

namespace {

constexpr uint32_t kOverlayColour = 0xFF008CFFu;  // RGBA8, R in the low byte
constexpr uint32_t kOnlyColour = 0xFFFFFFFFu;
constexpr float kDepthBias = 1.0f / 65536.0f;

}  // namespace

void Pipeline::lines()
{
  // Step 1: three segments per setup record, edges of the input triangles only.
  const uint64_t n = 3ull * numSetup_;
  if (n > UINT32_MAX) throw Error("the frame has more than 2^32 wireframe segments");
  lineSegs_.reserve(n);
  if (numSetup_ > 0) {
    cl::Kernel& fromSetup = extraKernel(linesFromSetupKernel_, "lines_from_setup");
    LinesFromSetupArgs args;
    args.setup = setup_.get(), args.numSetup = numSetup_, args.source = setupSource_.get();
    args.clipBary = clipBary_.get(), args.segs = lineSegs_.get();
    setKernelArgs(fromSetup, args);
    launchLinear(fromSetup, numSetup_, "lines_from_setup");
  }
  drawLineSegments(uint32_t(n), settingsLinePass());
}

void Pipeline::lines(const std::vector<LineSeg>& segments)
{
  if (segments.size() > UINT32_MAX) throw Error("more than 2^32 line segments");
  lineSegs_.upload(segments);
  drawLineSegments(uint32_t(segments.size()), settingsLinePass());
}

Pipeline::LinePass Pipeline::settingsLinePass() const
{
  // Without a wireframe mode (caller's segments), lines are drawn over the image.
  const FrameSettings& s = settings_;
  const uint32_t mode = s.wireframe == CLR_WIREFRAME_OFF ? CLR_WIREFRAME_OVERLAY : s.wireframe;
  return {mode, s.lineMethod, s.lineWidth, mode == CLR_WIREFRAME_ONLY ? kOnlyColour : kOverlayColour};
}

void Pipeline::drawLineSegments(uint32_t n, const LinePass& pass)
{
  blankImage_ = tileBlankImage_ = BlankImage{};  // lines and points draw on the image
  // Step 1: the line constants.
  const FrameSettings& s = settings_;
  if (!params_.visAttributes)
    throw Error("lines: the frame has no depth plane to test against (set FrameSettings.keepVisAttributes)");
  if (pass.method > CLR_LINE_BRESENHAM || pass.mode > CLR_WIREFRAME_ONLY)
    throw Error("unknown line method or wireframe mode");
  if (!(pass.width > 0.0f && pass.width <= 16.0f)) throw Error("line width must lie in (0, 16] pixels");
  LineParams lp{};
  lp.mode = pass.mode;
  lp.method = pass.method;
  lp.width = pass.width;
  // Bresenham pixels lie within half a pixel (along the minor axis) of the
  // line between the end pixels' centres; an anti-aliased pixel with any
  // coverage has its centre within half a diagonal of the rectangle.
  lp.reach = pass.method == CLR_LINE_BRESENHAM ? 0.75f : 0.5f * pass.width + 0.7072f;
  lp.depthBias = kDepthBias;
  lp.colour = pass.colour;
  lp.background = CLR_BACKGROUND(s.shadeMode);  // resolve's, so the mode looks the same without its triangles
  lp.numSegments = n;
  lineParams_.upload({lp});

  // Step 2: count the segments near each tile and scan into offsets.
  std::vector<cl::Event> fills;
  lineTileCount_.zero(numTiles_ + 1, &fills);
  lineSegs_.reserve(n);
  if (n > 0) {
    cl::Kernel& binCount = extraKernel(linesBinCountKernel_, "lines_bin_count");
    LinesBinCountArgs args;
    args.params = paramsBuf_.get(), args.lp = lineParams_.get(), args.segs = lineSegs_.get();
    args.tileCount = lineTileCount_.get();
    setKernelArgs(binCount, args);
    launchLinear(binCount, n, "lines_bin_count");
  }
  const uint64_t entries = scan(lineTileCount_, numTiles_, "lines_bin_scan");
  if (entries > UINT32_MAX)
    throw Error("the frame needs " + std::to_string(entries) + " line bin entries, more than 2^32");
  lineBinEntries_.reserve(entries);

  // Step 3: fill the bins.
  lineTileCursor_.zero(numTiles_, &fills);
  if (n > 0) {
    cl::Kernel& binFill = extraKernel(linesBinFillKernel_, "lines_bin_fill");
    LinesBinFillArgs args;
    args.params = paramsBuf_.get(), args.lp = lineParams_.get(), args.segs = lineSegs_.get();
    args.tileOffset = lineTileCount_.get(), args.tileCursor = lineTileCursor_.get();
    args.binEntries = lineBinEntries_.get();
    setKernelArgs(binFill, args);
    launchLinear(binFill, n, "lines_bin_fill");
  }

  // Step 4: one work-item per tile draws and blends.
  cl::Kernel& draw = extraKernel(linesDrawKernel_, "lines_draw");
  LinesDrawArgs args;
  args.params = paramsBuf_.get(), args.lp = lineParams_.get(), args.segs = lineSegs_.get();
  args.lineTileOffset = lineTileCount_.get(), args.lineBinEntries = lineBinEntries_.get();
  args.triTileOffset = tileCount_.get(), args.visIndex = visIndex_.get(), args.visAttr = visAttr_.get();
  args.setup = setup_.get(), args.image = image_.get(), args.tileSlot = tileSlot_.get(), args.visPlane = visPlane();
  setKernelArgs(draw, args);
  launch(draw, cl::NDRange(params_.tilesX, params_.tilesY), cl::NDRange(1, 1), "lines_draw");
}

}  // namespace clr
