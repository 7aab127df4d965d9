// pipeline.cpp — frame orchestration: constants, the scene upload, the
// whole-frame driver, profiling and read-backs. The stages themselves live
// in transform.cpp, setup.cpp, scan.cpp, bin.cpp, raster.cpp, resolve.cpp.
#include "pipeline/pipeline.h"

#include "pipeline/aa.h"
#include "pipeline/layout.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

namespace clr {

FrameParams makeFrameParams(const FrameSettings& s, size_t numVerts, size_t numTris)
{
  if (s.width == 0 || s.height == 0 || s.width > CLR_MAX_VIEWPORT || s.height > CLR_MAX_VIEWPORT)
    throw Error("viewport " + std::to_string(s.width) + "x" + std::to_string(s.height) + " outside 1.." +
                std::to_string(CLR_MAX_VIEWPORT));
  FrameParams p{};
  p.visIndexBits = 32;  // until raster sizes the visibility buffer
  std::memcpy(p.mvp, glm::value_ptr(s.mvp), sizeof p.mvp);
  const glm::vec3 light = glm::normalize(s.lightDir);
  p.lightDir[0] = light.x;
  p.lightDir[1] = light.y;
  p.lightDir[2] = light.z;
  // Guard band: |x_s| <= CLR_GUARD_BAND_PIXELS (derivation in fixed.h).
  p.guardX = 2.0f * CLR_GUARD_BAND_PIXELS / float(s.width) - 1.0f;
  if (s.imageTris && (s.imageRows % CLR_TILE_SIZE || s.imageHeight == 0 || s.imageHeight > s.imageRows))
    throw Error("batched frame: image rows " + std::to_string(s.imageRows) + " not a tile multiple holding " +
                std::to_string(s.imageHeight));
  const uint32_t viewHeight = s.imageTris ? s.imageHeight : s.height;  // one image's viewport
  p.imageTris = s.imageTris;
  p.imageRows = s.imageTris ? s.imageRows : 0;
  p.imageHeight = viewHeight;
  p.guardY = 2.0f * CLR_GUARD_BAND_PIXELS / float(viewHeight) - 1.0f;
  p.halfWidth = 0.5f * float(s.width);
  p.halfHeight = 0.5f * float(viewHeight);
  p.zNear = s.zNear;
  p.zFar = s.zFar;
  p.width = s.width;
  p.height = s.height;
  p.tilesX = (s.width + CLR_TILE_SIZE - 1) / CLR_TILE_SIZE;
  p.tilesY = (s.height + CLR_TILE_SIZE - 1) / CLR_TILE_SIZE;
  p.numVerts = uint32_t(numVerts);
  p.numTris = uint32_t(numTris);
  p.cullBack = s.cullBack ? 1u : 0u;
  if (s.shadeMode >= CLR_NUM_SHADE_MODES || s.texFilter > CLR_FILTER_TRILINEAR)
    throw Error("unknown shading mode or texture filter");
  p.shadeMode = s.shadeMode;
  p.texFilter = s.texFilter;
  for (int k = 0; k < 3; ++k) {
    p.eye[k] = s.eye[k];
    p.pointLight[k] = s.pointLight[k];
  }
  if (s.pointLightOn && !(s.pointLightRange > 0.0f && std::isfinite(s.pointLightRange)))
    throw Error("point light range must be a positive finite number");
  p.pointLightOn = s.pointLightOn ? 1u : 0u;
  p.pointLight[3] = s.pointLightRange;
  // Samples: the standard positions, in fixed-point units.
  const std::vector<SampleOffset>& offsets = samplePositions(s.samples);
  p.samples = s.samples;
  p.shadeEverySample = s.shadeEverySample ? 1u : 0u;
  p.sampleMinX = p.sampleMinY = INT32_MAX;
  p.sampleMaxX = p.sampleMaxY = INT32_MIN;
  for (uint32_t k = 0; k < s.samples; ++k) {
    p.sampleX[k] = offsets[k].x * (CLR_FIXED_ONE / 16);
    p.sampleY[k] = offsets[k].y * (CLR_FIXED_ONE / 16);
    p.sampleMinX = std::min(p.sampleMinX, p.sampleX[k]);
    p.sampleMaxX = std::max(p.sampleMaxX, p.sampleX[k]);
    p.sampleMinY = std::min(p.sampleMinY, p.sampleY[k]);
    p.sampleMaxY = std::max(p.sampleMaxY, p.sampleY[k]);
  }
  if (s.edgeMode > CLR_EDGES_FLOAT || s.interpMode > CLR_INTERP_AFFINE || s.traversal > CLR_TRAVERSAL_SPANS_FLOAT)
    throw Error("unknown edge, interpolation or traversal method");
  if (s.edgeMode == CLR_EDGES_FLOAT && s.traversal >= CLR_TRAVERSAL_SPANS)
    throw Error("float edges and span traversal each decide coverage: use one of them");
  p.edgeMode = s.edgeMode;
  p.interpMode = s.interpMode;
  p.traversal = s.traversal;
  if (s.depthMode > CLR_DEPTH_REVERSED || s.visibility > CLR_VISIBILITY_PAINTER)
    throw Error("unknown depth format or visibility method");
  p.depthMode = s.depthMode;
  p.visibility = s.visibility;
  // Tiny triangles that cover no sample are culled in setup only where no
  // reader could tell: one sample (the test knows one sample position),
  // exact coverage (raster's own integers: not float edges or the float
  // walk) and no wireframe (which draws the setup triangles' edges).
  p.cullSampleFree = s.cullSampleFree && s.samples == 1 && s.edgeMode == CLR_EDGES_FIXED &&
                             s.traversal != CLR_TRAVERSAL_SPANS_FLOAT && s.wireframe == CLR_WIREFRAME_OFF
                         ? 1u
                         : 0u;
  // The depth and barycentric planes of the visibility buffer, only for the
  // frames whose readers need them (shared.h): lines test against the depth
  // plane, and resolve recomputes only the fixed edges' barycentrics.
  p.visAttributes = s.keepVisAttributes || s.wireframe != CLR_WIREFRAME_OFF || s.edgeMode == CLR_EDGES_FLOAT ? 1u : 0u;
  return p;
}

Pipeline::Pipeline(ClContext& cl)
    : DeviceScene(cl),
      paramsBuf_(memory_, "frame parameters"),
      clipPos_(memory_, "clip-space positions"),
      triCount_(memory_, "setup counts"),
      counters_(memory_, "counters"),
      clipList_(memory_, "clip list"),
      setup_(memory_, "setup triangles"),
      setupSource_(memory_, "setup record sources"),
      clipBary_(memory_, "clipped-triangle barycentrics"),
      tileCount_(memory_, "tile counts"),
      tileCursor_(memory_, "tile cursors"),
      tileSlot_(memory_, "tile slots"),
      binEntries_(memory_, "bin entries"),
      tileBlank_(memory_, "tile background flags"),
      scanPartials_(memory_, "scan partial sums"),
      listingPartials_(memory_, "setup scan partial sums"),
      visIndex_(memory_, "visibility buffer (triangles)"),
      visAttr_(memory_, "visibility buffer (depth, barycentrics)"),
      image_(memory_, "image"),
      paintRank_(memory_, "paint ranks"),
      tileMicro_(memory_, "micro-triangle tile flags"),
      microRecord_(memory_, "micro-triangle records"),
      microKey_(memory_, "micro-triangle fragments"),
      lineParams_(memory_, "line parameters"),
      lineSegs_(memory_, "line segments"),
      lineTileCount_(memory_, "line tile counts"),
      lineTileCursor_(memory_, "line tile cursors"),
      lineBinEntries_(memory_, "line bin entries"),
      aov_(memory_, "visibility-buffer outputs"),
      rastOut_(memory_, "rasterize output"),
      rastDb_(memory_, "rasterize derivatives"),
      rastIds_(memory_, "rasterize triangle ids"),
      peelFloor_(memory_, "depth peeling floor"),
      peelNext_(memory_, "depth peeling layer depth")
{
  transformKernel_ = cl::Kernel(cl.program, "transform_vertices");
  setupCountKernel_ = cl::Kernel(cl.program, "setup_triangles");  // its two passes, each with its own arguments
  setupEmitKernel_ = cl::Kernel(cl.program, "setup_triangles");
  setupClipKernel_ = cl::Kernel(cl.program, "setup_clip");
  scanReduceKernel_ = cl::Kernel(cl.program, "scan_chunks");  // its three phases, each with its own arguments
  scanPartialsKernel_ = cl::Kernel(cl.program, "scan_chunks");
  scanApplyKernel_ = cl::Kernel(cl.program, "scan_chunks");
  binFillClippedKernel_ = cl::Kernel(cl.program, "bin_fill_clipped");
  rasterKernel_ = cl::Kernel(cl.program, "raster");
  resolveKernel_ = cl::Kernel(cl.program, "resolve");
  resolveLambertKernel_ = cl::Kernel(cl.program, "resolve_lambert");
  paramsBuf_.reserve(1);
  counters_.reserve(CLR_NUM_COUNTERS);
  clipList_.reserve(1024);
  tileSlot_.reserve(1);
  microKey_.reserve(1);
  microRecord_.reserve(1);
  initMicro();
}

void Pipeline::uploadScene(const Mesh& mesh)
{
  const auto start = std::chrono::steady_clock::now();
  checkScene(mesh);
  placeScene(mesh);
  afterUpload(start);
}

void Pipeline::uploadScene(Mesh&& mesh)
{
  const auto start = std::chrono::steady_clock::now();
  checkScene(mesh);
  placeScene(std::move(mesh));
  afterUpload(start);
}

void Pipeline::uploadScene(SceneLayout&& laidOut)
{
  const auto start = std::chrono::steady_clock::now();
  checkScene(laidOut.mesh);
  placeLaidOut(std::move(laidOut));
  afterUpload(start);
}

void Pipeline::checkScene(const Mesh& mesh) const
{
  // The optional attributes against the vertices.
  if (cl_.clipInput) throw Error("uploadScene: this context's programs take clip-space positions (uploadClipScene)");
  if (mesh.numTris() > UINT32_MAX / CLR_MAX_SUBTRIS) throw Error("scene has too many triangles");
  if (mesh.normals.size() != mesh.positions.size() || (!mesh.uvs.empty() && mesh.uvs.size() != 2 * mesh.numVerts()) ||
      (!mesh.colors.empty() && mesh.colors.size() != 4 * mesh.numVerts()))
    throw Error("scene's normals, texture coordinates or colours do not match its vertices");
  if (!mesh.triMaterial.empty() && mesh.triMaterial.size() != mesh.numTris())
    throw Error("scene's triangle materials do not match its triangles");
  for (uint32_t m : mesh.triMaterial)
    if (m >= mesh.materials.size()) throw Error("scene's triangle material " + std::to_string(m) + " out of range");
  for (uint32_t v : mesh.lines)
    if (v >= mesh.numVerts()) throw Error("scene's line vertex " + std::to_string(v) + " out of range");
  for (uint32_t v : mesh.points)
    if (v >= mesh.numVerts()) throw Error("scene's point vertex " + std::to_string(v) + " out of range");
  for (const Material& m : mesh.materials)
    if (m.texture >= int64_t(mesh.textures.size())) throw Error("scene's material texture out of range");
}

void Pipeline::afterUpload(std::chrono::steady_clock::time_point start)
{
  // The layout and what every mode reads are placed (placeScene); the rest waits for a frame that reads it.
  framedScene_ = false;
  paintOrder_.clear();
  triCount_.reserve(sceneTris_, true);
  params_.numVerts = uint32_t(sceneVerts_);
  params_.numTris = uint32_t(sceneTris_);
  cl_.queue.finish();
  prepareMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

cl::Kernel& Pipeline::extraKernel(cl::Kernel& kernel, const char* name)
{
  if (!kernel()) kernel = cl::Kernel(cl_.extras(), name);
  return kernel;
}

cl::NDRange Pipeline::linear(uint64_t n)
{
  const uint64_t group = CLR_LINEAR_GROUP;
  return cl::NDRange(size_t((n + group - 1) / group * group));
}

void Pipeline::launch(cl::Kernel& kernel, const cl::NDRange& global, const cl::NDRange& local, const char* stage)
{
  cl::Event event;
  cl_.queue.enqueueNDRangeKernel(kernel, cl::NullRange, global, local, nullptr, &event);
  record(stage, event);
}

void Pipeline::launchLinear(cl::Kernel& kernel, uint64_t n, const char* stage)
{
  launch(kernel, linear(n), cl::NDRange(CLR_LINEAR_GROUP), stage);
}

void Pipeline::launchPixels(cl::Kernel& kernel, const char* stage)
{
  launch(kernel, cl::NDRange(params_.tilesX * CLR_TILE_SIZE, params_.tilesY * CLR_TILE_SIZE),
         cl::NDRange(CLR_TILE_SIZE, CLR_TILE_SIZE), stage);
}

Pipeline::~Pipeline()
{
  try {
    unmapImage();
    cl_.queue.finish();
  } catch (...) {  // a destructor must not throw; the context goes anyway
  }
}

void Pipeline::unmapImage()
{
  if (!mappedImage_) return;
  cl_.queue.enqueueUnmapMemObject(image_.get(), mappedImage_);  // ordered before any later kernel
  mappedImage_ = nullptr;
}

void Pipeline::beginFrame(const FrameSettings& settings)
{
  unmapImage();  // kernels must not write a mapped buffer
  params_ = makeFrameParams(settings, params_.numVerts, params_.numTris);
  params_.sceneFlags = bindAttributes(settings);
  if (!scene_.lines.empty() || !scene_.points.empty()) params_.visAttributes = 1;  // their depth test reads it
  params_.clusterMargin = clusterMargin(settings.mvp);
  params_.fileOrder = fileOrder_ ? 1u : 0u;
  microMax_ = microMaxFor(settings);
  settings_ = settings;
  events_.clear();
  numTiles_ = params_.tilesX * params_.tilesY;
  cl_.queue.enqueueWriteBuffer(paramsBuf_.get(), CL_FALSE, 0, sizeof params_, &params_);
  std::vector<cl::Event> fills;
  counters_.zero(CLR_NUM_COUNTERS, &fills);
  speculate_ = speculate_ && speculationPays(settings);
  speculated_ = missed_ = false;  // (runFrame sets them after the frame)
  if (speculate_)
    cl_.queue.enqueueWriteBuffer(counters_.get(), CL_FALSE, CLR_COUNTER_SPECULATIVE * sizeof(uint32_t),
                                 sizeof specCaps_, &specCaps_);
}

bool Pipeline::speculationPays(const FrameSettings& settings)
{
  // Step 1: a frame of this scene came before, which neither clipped nor drew lines: setup_clip, bin_fill_clipped
  // and the lines stage are launched from totals. (A frame with nothing in view waits: it is cheap already.)
  if (!speculationOn_ || !framedScene_ || clippedLastFrame_ || settings.wireframe != CLR_WIREFRAME_OFF ||
      !scene_.lines.empty() || !scene_.points.empty() || numSetup_ == 0 || numBinEntries_ == 0)
    return false;
  // Step 2: the capacities. Emit is launched over the last total and a quarter more; the visibility indices keep the
  // last frame's width (raster.cpp), and the listing needs a spare entry per scan chunk (scan.cl).
  const uint64_t chunks = scanChunks(listingItems()).count;
  uint64_t records = std::min<uint64_t>(setup_.capacity(),
                                        setupSource_.capacity() - std::min<uint64_t>(setupSource_.capacity(), chunks));
  records = std::min<uint64_t>(records, uint64_t(numSetup_) + numSetup_ / 4 + 1024);
  const uint64_t bits = visIndexBits(settings);
  if (bits < 32) records = std::min<uint64_t>(records, (uint64_t(1) << bits) - 2);
  const uint64_t tileSamples = uint64_t(CLR_TILE_SIZE) * CLR_TILE_SIZE * params_.samples;
  uint64_t slots = visIndex_.capacity() * 32 / bits / tileSamples;
  if (params_.visAttributes) slots = std::min<uint64_t>(slots, visAttr_.capacity() / (3 * tileSamples));
  slots = std::min<uint64_t>(slots, numTiles_);
  const uint64_t bins = std::min<uint64_t>(binEntries_.capacity(), UINT32_MAX);
  if (records == 0 || slots == 0) return false;
  static_assert(sizeof(SpecCaps) == 4 * sizeof(uint32_t) && CLR_COUNTER_CAP_SLOTS == CLR_COUNTER_SPECULATIVE + 3,
                "specCaps_ is written over the counters from CLR_COUNTER_SPECULATIVE");
  specCaps_ = {1u, uint32_t(records), uint32_t(bins), uint32_t(slots)};
  return true;
}

bool Pipeline::takeSpeculativeTotals()
{
  const std::vector<uint32_t>& c = endCounters_;
  // Micro slots past microKey_'s binned their tiles' triangles (micro.h): right, but with other counts than a
  // waiting frame's, so the frame is redone as one, sized from this count.
  microTiles_ = c[CLR_COUNTER_MICRO_TILES];
  if (c[CLR_COUNTER_OVERFLOW] || microTiles_ > microCap_) return false;
  const uint64_t total = counterTotal(c, CLR_COUNTER_SETUP_TOTAL);
  numSetup_ = uint32_t(total);  // (scan.cl: within specCaps_)
  numCulledUnclipped_ = uint32_t(params_.numTris - total);
  takeBinTotals(c);
  numBinEntries_ = binTotal_;
  usedVisSlots_ = uint32_t(slotTotal_);  // numVisSlots_ stays the visibility buffer's stride
  // Nothing binned after all: resolve painted every tile background, as a waiting frame's would (resolve.cpp).
  if (numBinEntries_ == 0) blankImage_ = BlankImage{params_.width, params_.height, CLR_BACKGROUND(params_.shadeMode)};
  return true;
}

void Pipeline::runFrame(const FrameSettings& settings, ImageView* view, std::vector<uint32_t>* rgba)
{
  // Step 1: the frame, speculative where it pays: no wait between setup's
  // count and resolve.
  bool missed = false;
  for (bool speculate = true;; speculate = false) {
    speculate_ = speculate;
    try {
      runStages(settings);
    } catch (...) {
      speculate_ = false;  // the stages called one by one never speculate
      throw;
    }
    // Step 2: the image (the blocking map or read waits for every command).
    if (view) {
      const uint64_t bytes = uint64_t(params_.width) * params_.height * sizeof(uint32_t);
      mappedImage_ = cl_.queue.enqueueMapBuffer(image_.get(), CL_TRUE, CL_MAP_READ, 0, bytes);
      view->pixels = static_cast<const uint32_t*>(mappedImage_);
      view->width = params_.width;
      view->height = params_.height;
    } else {
      readImage(*rgba);
    }
    // Step 3: a speculative frame's counters, read once the queue is idle (an asynchronous read ahead of the
    // image slowed NVIDIA's driver, docs/gpu.md); one that did not fit runs again, waiting.
    if (speculate_) endCounters_ = readCounters();
    speculated_ = speculate_;
    if (!speculate_ || takeSpeculativeTotals()) break;
    missed = true;
    unmapImage();
  }
  speculate_ = false;
  missed_ = missed;
  framedScene_ = true;
}

void Pipeline::runStages(const FrameSettings& settings)
{
  beginFrame(settings);
  setup();  // transforms the vertices it reads (transform.cl)
  setupEmit();
  raster();
  resolve();
  if (settings.wireframe != CLR_WIREFRAME_OFF) lines();
  if (!scene_.lines.empty() || !scene_.points.empty()) filePrimitives();
}

FrameStats Pipeline::render(const FrameSettings& settings, std::vector<uint32_t>& rgba)
{
  runFrame(settings, nullptr, &rgba);
  return finishFrame();
}

FrameStats Pipeline::render(const FrameSettings& settings, ImageView& view)
{
  runFrame(settings, &view, nullptr);
  return finishFrame();
}

FrameStats Pipeline::finishFrame()
{
  // The image's blocking read or map has waited for every earlier command
  // of the in-order queue. Only setup_clip adds to the counters after
  // setup's read: a frame that clipped nothing reads them no more.
  std::vector<uint32_t> counters(CLR_NUM_COUNTERS, 0u);
  if (numClipped_ > 0) counters = readCounters();
  FrameStats stats;
  cl_ulong firstStart = UINT64_MAX, lastEnd = 0, busy = 0;
  for (const auto& [stage, event] : events_) {
    const cl_ulong start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
    const cl_ulong end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
    stats.stageMs[stage] += double(end - start) * 1e-6;
    firstStart = std::min(firstStart, start);
    lastEnd = std::max(lastEnd, end);
    busy += end - start;
  }
  if (resolveSkipped_) stats.stageMs["resolve"] += 0.0;  // the image was already the frame's (resolve.cpp)
  stats.imageKept = resolveSkipped_;
  stats.speculative = speculated_;
  stats.speculationMissed = missed_;
  stats.microMax = microMax_;
  if (!events_.empty()) stats.deviceIdleMs = double(lastEnd - firstStart - std::min(busy, lastEnd - firstStart)) * 1e-6;
  stats.trianglesIn = params_.numTris;
  stats.trianglesClipped = counters[CLR_COUNTER_CLIPPED_TRIS];
  stats.trianglesCulled = uint64_t(numCulledUnclipped_) + counters[CLR_COUNTER_CULLED_TRIS];
  stats.setupTriangles = numSetup_ - counters[CLR_COUNTER_DEAD_RECORDS];
  stats.binEntries = numBinEntries_;
  stats.leanResolve = leanResolve_;
  stats.resolvePrefetch = resolvePrefetch_;
  if (timedPrefetch_) prefetchChooser_.report(stats.stageMs["resolve"]);
  return stats;
}

std::vector<cl_float4> Pipeline::readClipPositions() const
{
  const std::vector<cl_float4> laidOut = clipPos_.download(params_.numVerts);
  if (laidVertex_.empty()) return laidOut;  // a clip-space scene: no layout
  std::vector<cl_float4> out(laidVertex_.size());
  for (size_t v = 0; v < out.size(); ++v) out[v] = laidOut[laidVertex_[v]];
  return out;
}
std::vector<SetupRecord> Pipeline::readSetup() const
{
  const std::vector<TriSetup> setup = setup_.download(numSetup_);
  const std::vector<uint32_t> source = setupSource_.download(numSetup_);
  const std::vector<ClipBary> clip = readClipBary();
  // 1/w, which records do not hold: record_clip_w (transform.cl) in the same float operations.
  const size_t stride = cl_.clipInput ? 4 : 3;
  const std::vector<float> positions = positions_.download(stride * params_.numVerts);
  const std::vector<uint32_t> indices = indices_.download(3 * uint64_t(params_.numTris));
  const float* m = params_.mvp;
  auto clipW = [&](uint32_t v) {
    const float* p = &positions[stride * v];
    return stride == 4 ? p[3] : CLR_TRANSFORM_ROW(m, 3, p[0], p[1], p[2]);
  };
  std::vector<SetupRecord> out(numSetup_);
  for (size_t s = 0; s < out.size(); ++s) {
    const TriSetup& t = setup[s];
    SetupRecord& r = out[s];
    for (int v = 0; v < 3; ++v) {
      r.x[v] = t.x[v];
      r.y[v] = t.y[v];
      r.z[v] = t.z[v];
    }
    r.invArea2 = CLR_RECORD_INV_AREA2(t);
    r.clipSlot = clr_source_clip_slot(source[s]);
    const bool clipped = r.clipSlot != CLR_NOT_CLIPPED;
    const uint32_t tri = source[s] & CLR_SOURCE_TRIANGLE;
    const bool back = (source[s] & CLR_SOURCE_BACKFACING) != 0;
    for (int v = 0; v < 3; ++v)  // (a back face's vertices 1 and 2 swapped, as setup_make swaps them)
      r.invW[v] = 1.0f / (clipped ? clip.at(r.clipSlot).clipW[v] : clipW(indices[3 * tri + (back && v ? 3 - v : v)]));
    r.triId = clipped ? clip.at(r.clipSlot).triId : fileTriHost_.empty() ? tri : fileTriHost_.at(tri);
    r.flags = clipped ? clip.at(r.clipSlot).flags : back ? CLR_FLAG_BACKFACING : 0u;
  }
  return out;
}
std::vector<ClipBary> Pipeline::readClipBary() const
{
  std::vector<ClipBary> slots = clipBary_.download(uint64_t(numClipped_) * CLR_MAX_SUBTRIS);
  for (ClipBary& c : slots)
    if (c.triId < fileTriHost_.size()) c.triId = fileTriHost_[c.triId];
  return slots;
}
std::vector<uint32_t> Pipeline::readTileOffsets() const
{
  return tileCount_.download(numTiles_ + 1);
}
std::vector<uint32_t> Pipeline::readBinEntries() const
{
  return binEntries_.download(numBinEntries_);
}
std::vector<VisSample> Pipeline::readVis(uint32_t sample) const
{
  // Step 1: the planes of the sample, and each tile's block in them.
  if (sample >= params_.samples) throw Error("readVis: no sample " + std::to_string(sample));
  const uint64_t n = uint64_t(params_.width) * params_.height, v = visPlane();
  std::vector<uint32_t> index(v);
  const uint32_t bits = params_.visIndexBits;
  if (bits == 32) {
    index = visIndex_.download(v, sample * v);
  } else {  // 16-bit low halves, then 24 bits' high bytes (shared.h); v is a whole number of tiles, so a word multiple
    const std::vector<uint32_t> low = visIndex_.download(v / 2, sample * v / 2);
    std::vector<uint32_t> high;
    if (bits == 24) high = visIndex_.download(v / 4, (2 * uint64_t(params_.visEntries) + sample * v) / 4);
    const uint32_t none = bits == 24 ? 0xFFFFFFu : 0xFFFFu;
    for (uint64_t i = 0; i < v; ++i) {
      uint32_t entry = (low[i / 2] >> (16 * (i % 2))) & 0xFFFFu;  // little-endian device
      if (bits == 24) entry |= ((high[i / 4] >> (8 * (i % 4))) & 0xFFu) << 16;
      index[i] = entry == none ? CLR_NONE : entry;
    }
  }
  const bool attributes = params_.visAttributes != 0;
  const std::vector<float> attr = attributes ? visAttr_.download(3 * v, 3 * sample * v) : std::vector<float>();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<uint32_t> offsets = readTileOffsets();
  const std::vector<uint32_t> slots = tileSlot_.download(numTiles_);
  // Step 2: samples; raster leaves empty tiles unwritten, so they read as empty.
  std::vector<VisSample> vis(n);
  for (uint32_t y = 0; y < params_.height; ++y)
    for (uint32_t x = 0; x < params_.width; ++x) {
      const size_t p = size_t(y) * params_.width + x;
      const uint32_t tile = (y / CLR_TILE_SIZE) * params_.tilesX + x / CLR_TILE_SIZE;
      const float clearDepth = params_.depthMode == CLR_DEPTH_REVERSED ? 0.0f : 1.0f;
      const size_t a = offsets[tile] == offsets[tile + 1] ? 0 : vis_address(slots[tile], x, y);
      if (offsets[tile] == offsets[tile + 1])
        vis[p] = attributes ? VisSample{CLR_NONE, clearDepth, 0.0f, 0.0f} : VisSample{CLR_NONE, nan, nan, nan};
      else
        vis[p] = attributes ? VisSample{index[a], attr[a], attr[v + a], attr[2 * v + a]}
                            : VisSample{index[a], nan, nan, nan};
    }
  return vis;
}

void Pipeline::readImage(std::vector<uint32_t>& rgba) const
{
  // Into the caller's vector, reusing its memory: a fresh 8 MB vector per
  // 1080p frame costs its page faults every frame.
  const uint64_t n = uint64_t(params_.width) * params_.height;
  rgba.resize(n);
  if (n) cl_.queue.enqueueReadBuffer(image_.get(), CL_TRUE, 0, n * sizeof(uint32_t), rgba.data());
}

std::vector<uint32_t> Pipeline::readImage() const
{
  return image_.download(uint64_t(params_.width) * params_.height);
}

}  // namespace clr
