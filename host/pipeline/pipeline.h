// pipeline.h — the frame pipeline: buffers, stages and per-frame statistics.
//
// A Pipeline owns every device buffer of a scene and runs the stages in
// order: (transform) -> setup -> setup_emit and bin -> raster -> resolve, where setup
// transforms the vertices it reads, so a frame needs no clip-position
// buffer (transform() writes one for tests and the painter's sort). Each
// stage is a member function defined in the host file named after its
// kernel file (host/pipeline/transform.cpp runs kernels/transform.cl, and so on), so
// tests can run and inspect one stage at a time. Buffers grow to the counts
// of the current frame (see buffer.h); nothing is dropped, and a size the
// device cannot hold is a clr::Error.
#pragma once

#include "pipeline/buffer.h"
#include "pipeline/device.h"
#include "pipeline/device_scene.h"
#include "pipeline/frame_settings.h"
#include "pipeline/kernel_args.h"
#include "io/scene.h"

#include "kernels/shared.h"

#include <glm/glm.hpp>

#include <chrono>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace clr {

// How scan_chunks (scan.cl) splits n counts: at most CLR_SCAN_MAX_CHUNKS
// chunks of at least CLR_SCAN_MIN_CHUNK counts each (shared.h), and the work-items of its reduce and apply phases:
// a work-group of CLR_SCAN_GROUP(1) per chunk in the GPU shape (lanes 1),
// one work-item per chunk in the CPU shape. (Pipeline's scans; a kernel
// test launches the phases the same way.)
struct ScanChunks {
  uint32_t size, count;
};
ScanChunks scanChunks(uint32_t n);
cl::NDRange scanChunkItems(int lanes, uint32_t chunks);

// The work shapes of raster and resolve over tilesX × tilesY tiles, as
// Pipeline launches them: raster one
// work-item per pixel sample in the GPU shape (lanes 1), per tile and sample
// index in the CPU shape; resolve one work-item per row of lanes, a tile per
// work-group, or per tile when a row of lanes spans the tile.
struct WorkShape {
  cl::NDRange global, local;
};
WorkShape rasterShape(int lanes, uint32_t tilesX, uint32_t tilesY, uint32_t samples);
WorkShape resolveShape(int lanes, uint32_t tilesX, uint32_t tilesY);

// Whether a frame takes resolve's lean lambert kernel (resolve_lambert.cl)
// rather than the general one: lambert, one sample, perspective
// interpolation, no point light, and no textures or vertex colours bound
// (sceneFlags, FrameParams).
bool resolveIsLean(uint32_t shadeMode, uint32_t samples, uint32_t interpMode, bool pointLightOn, uint32_t sceneFlags);

// Whether resolve may gain by fetching the setup records, vertex indices
// and normals of later rows ahead (resolve_prefetch, resolve.cl): a frame
// of small triangles (at most two bin entries each on average) that gives
// resolve more than 2 MB to gather, beyond a core's second-level cache.
// Whether it does gain depends on the mesh's memory order as much as on
// its size (resolve.cpp), so PrefetchChooser measures it.
bool resolveMayPrefetch(const FrameParams& params, uint32_t numSetup, uint64_t numBinEntries);

// Chooses, by timing, whether resolve prefetches the frames of one case
// (a scene at one viewport and resolve kernel) that resolveMayPrefetch
// admits. A case's first frame prefetches and is not timed (it also pays
// the first touch of its buffers); the next four take turns, on, off, off,
// on; after them the setting with the faster of its two resolve times holds
// until the case changes. The choice never changes a pixel, only the time.
class PrefetchChooser {
 public:
  // What makes a case: the scene (Pipeline's count of uploads), the
  // viewport, the shading mode, the samples and the resolve kernel.
  struct Case {
    uint64_t scene = 0;
    uint32_t width = 0, height = 0, shadeMode = 0, samples = 0;
    bool lean = false;
    bool operator==(const Case& o) const
    {
      return scene == o.scene && width == o.width && height == o.height && shadeMode == o.shadeMode &&
             samples == o.samples && lean == o.lean;
    }
  };
  // Whether the next frame of case c prefetches.
  bool next(const Case& c);
  // The resolve time of the frame next() answered for.
  void report(double resolveMs);

 private:
  static constexpr int kTrials = 4;
  bool started_ = false;
  Case case_;
  int frames_ = 0;                             // frames reported for this case
  double onMs_ = INFINITY, offMs_ = INFINITY;  // the fastest resolve of each setting
  bool current_ = false;                       // the last next() answer
};

// A setup record as tests and tools read it back (Pipeline::readSetup):
// the record's geometry with what its source word and ClipBary slot hold
// (shared.h), decoded.
struct SetupRecord {
  int x[3], y[3];
  float z[3], invW[3];
  float invArea2;     // clr_inv_area2 of the record
  uint32_t triId;     // the input triangle
  uint32_t clipSlot;  // its ClipBary slot, or CLR_NOT_CLIPPED
  uint32_t flags;     // CLR_FLAG_BACKFACING, CLR_FLAG_DEAD (padding of a clipped triangle)
};

// Fills the per-frame constant block (guard band, tiles, viewport matrix).
FrameParams makeFrameParams(const FrameSettings& settings, size_t numVerts, size_t numTris);

// A frame's RGBA8 image where the device left it (Pipeline::render with a
// view): width·height pixels, top row first, as render() copies them.
struct ImageView {
  const uint32_t* pixels = nullptr;
  uint32_t width = 0, height = 0;
};

struct FrameStats {
  std::map<std::string, double> stageMs;  // from OpenCL profiling events
  // From the first kernel's start to the last one's end, the time in no
  // kernel: launches, fills, reads and the host's waits between them.
  double deviceIdleMs = 0;
  uint64_t trianglesIn = 0;
  uint64_t trianglesClipped = 0;  // input triangles that needed clipping
  uint64_t trianglesCulled = 0;   // input triangles that produced no pixel
  uint64_t setupTriangles = 0;    // screen triangles after clipping
  uint64_t binEntries = 0;
  bool leanResolve = false;      // resolve ran its lean lambert kernel (resolve_lambert.cl)
  bool resolvePrefetch = false;  // resolve fetched rows ahead (PrefetchChooser)
  bool imageKept = false;        // nothing binned, and the image was already this frame's background: no resolve
  uint32_t microMax = 0;         // the micro path's size limit this frame took (micro.cpp), 0 off
  // Sized from the last frame's totals, without a wait mid-frame (Pipeline::runFrame); and whether such a try did
  // not fit and the frame ran again, waiting.
  bool speculative = false, speculationMissed = false;
};

// The frame driver over a DeviceScene (device_scene.h): the frame's
// buffers, the stages in order, speculation, and the read-backs of each
// stage's output for tests, tools and the API.
class Pipeline : public DeviceScene {
 public:
  explicit Pipeline(ClContext& cl);
  ~Pipeline();
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  // Lays the scene out (layout.h), uploads positions and indices and keeps
  // a copy of the laid-out scene; the other attributes are uploaded when a
  // frame first reads them (bindAttributes). Everything a caller reads back
  // (readSetup's and readClipBary's triangles, readClipPositions' order,
  // paintOrder, the id shading and AOV) speaks of the file's order.
  void uploadScene(const Mesh& mesh);
  // The same from a mesh the upload may consume (layOutScene's Mesh&&
  // form): the caller's arrays are freed as they are laid out.
  void uploadScene(Mesh&& mesh);
  // The same from a scene laid out already (layOutScene, say on another
  // thread while the program builds; setLayout does not apply): the uploads.
  void uploadScene(SceneLayout&& laidOut);
  // Whether render() may size a frame from the last one's totals (default;
  // see runFrame). Off, every frame waits for its counts mid-frame.
  void setSpeculation(bool on) { speculationOn_ = on; }

  // The library's rasterize (api.cpp), on a ClContext built with clipInput:
  // clip-space positions (4 floats per vertex) and triangles whose indices
  // the caller has checked against numVerts. A frame's mvp is then unused.
  void uploadClipScene(const float* positions, size_t numVerts, const uint32_t* indices, size_t numTris);
  // After raster of a frame that kept its visibility attributes: nvdiffrast's
  // rasterize outputs (rast_outputs.cl: rast always, the exact ids and the
  // derivatives when asked), then their read into the caller's arrays of
  // width·height float4s (rast, db) and uint32s (ids), bottom row first;
  // null skips one. A batched frame (FrameSettings::imageTris) reads its
  // images one after another, each width·imageHeight, padding rows left out.
  void rastOutputs(bool ids, bool derivatives);
  void readRastOutputs(float* rast, uint32_t* ids, float* db) const;
  // After setup and bin of a clip-input frame: one depth-peeling layer
  // (diff_peel.cl, peel.cpp) into the caller's width·height float4s (rast,
  // db: null skips it), behind floor (window depth per pixel, -inf for the
  // first layer); next gets this layer's depths (+inf where none).
  void peelLayer(const float* floor, float* rast, float* db, float* next);

  // Runs a whole frame and reads the RGBA8 image (top row first) back.
  FrameStats render(const FrameSettings& settings, std::vector<uint32_t>& rgba);
  // The same frame without the copy: `view` shows the image buffer mapped
  // for reading, which on a CPU device is the device's memory itself (on a
  // GPU the driver copies). The view stays valid until the next frame
  // begins or the pipeline goes; as OSMesa renders into its caller's buffer,
  // so the bench times both renderers up to an image the host can read.
  FrameStats render(const FrameSettings& settings, ImageView& view);

  // The stages, in order (each defined in its own host file).
  void beginFrame(const FrameSettings& settings);
  void transform();  // optional: fills readClipPositions()
  void setup();      // counts, lists and clips (setup.cpp)
  void setupEmit();  // the tile scans, setup_emit's records and bins, the clipped bins (setup.cpp, bin.cpp)
  void raster();     // with the painter's algorithm, sorts the triangles first (paintOrder)
  void resolve();
  // After resolve: draws the edges of the setup triangles (lines.cpp), or
  // the caller's segments, into the image with FrameSettings' line method.
  void lines();
  void lines(const std::vector<LineSeg>& segments);
  // After resolve (and the wireframe): the scene's own lines and points
  // (Mesh::lines, Mesh::points), projected and clipped here and drawn by the
  // lines stage (file_primitives.cpp). runStages calls it when there are any.
  void filePrimitives();
  // After raster: the visibility-buffer outputs, CLR_AOV_CHANNELS planes of
  // width·height floats, bottom row first (aov.cpp).
  void aov();
  std::vector<float> readAov() const;
  FrameStats finishFrame();  // waits, gathers profiling times and counters

  // Read-backs for tests and tools.
  std::vector<cl_float4> readClipPositions() const;
  std::vector<SetupRecord> readSetup() const;
  // Every ClipBary slot of the frame, CLR_MAX_SUBTRIS per clipped triangle
  // (unused ones flagged CLR_FLAG_DEAD).
  std::vector<ClipBary> readClipBary() const;
  std::vector<uint32_t> readTileOffsets() const;  // tiles + 1
  std::vector<uint32_t> readBinEntries() const;
  // One sample plane; empty tiles read as CLR_NONE. Depth, b1 and b2 are NaN
  // unless the frame kept them (FrameSettings.keepVisAttributes).
  std::vector<VisSample> readVis(uint32_t sample = 0) const;
  std::vector<uint32_t> readImage() const;
  void readImage(std::vector<uint32_t>& rgba) const;  // the same, into rgba's memory
  // The painter's draw order of the last painter frame: input triangle
  // indices, farthest first (empty after a z-buffer frame).
  const std::vector<uint32_t>& paintOrder() const { return paintOrder_; }

  const FrameParams& params() const { return params_; }
  // Bytes per pixel of the per-sample buffers and the image of this frame:
  // per sample of a covered tile 2, 3 or 4 (the visibility buffer's setup
  // index, visIndexBits), 12 more with its depth and barycentric planes,
  // and 4 for the image.
  double bytesPerPixel() const
  {
    const double pixels = double(params_.width) * params_.height;
    const double perSample = params_.visIndexBits / 8.0 + (params_.visAttributes ? 12.0 : 0.0);
    return perSample * params_.samples * usedVisSlots_ * CLR_TILE_SIZE * CLR_TILE_SIZE / pixels + 4.0;
  }
  uint32_t visPlane() const { return numVisSlots_ * CLR_TILE_SIZE * CLR_TILE_SIZE; }

 private:
  // uploadScene's checks of a mesh's arrays against one another, and its
  // bookkeeping once the scene is placed (prepareMs from `start`).
  void checkScene(const Mesh& mesh) const;
  void afterUpload(std::chrono::steady_clock::time_point start);
  // beginFrame to resolve (and lines): the frame of both render()s.
  void runStages(const FrameSettings& settings);
  // The frame of both render()s, its image mapped (view) or read (rgba):
  // sized from the last frame's totals where speculationPays, else waiting
  // for its counts; a speculative frame that did not fit is run again so.
  void runFrame(const FrameSettings& settings, ImageView* view, std::vector<uint32_t>* rgba);
  // Whether this frame may be sized from the last one's: a frame of this
  // scene without clipping, lines or points came before, and the buffers hold
  // some records, bins and tile slots. Sets the capacities (specCaps_).
  bool speculationPays(const FrameSettings& settings);
  // The visibility buffer's index width for this frame's setup records: 16, 24 or 32 (shared.h, visIndex).
  uint32_t visIndexBits(const FrameSettings& settings) const;
  // After a speculative frame's image: whether it fitted (then its totals
  // become the frame's, as a waiting frame reads them).
  bool takeSpeculativeTotals();
  // Unmaps the image an ImageView showed (before any kernel may write it).
  void unmapImage();
  // Exclusive in-place scan of data[0..n) (see scan.cl); returns the total,
  // or, given totalAt (a CLR_COUNTER_* index, shared.h), copies it among the
  // frame's counters for a later read and returns 0 without waiting.
  uint64_t scan(DeviceBuffer<uint32_t>& data, uint32_t n, const char* stage, uint32_t totalAt = CLR_SCAN_NO_TOTAL);
  // scan() with totalAt, which in the same launches also writes how many of
  // data[0 .. i) are non-zero into nonZero[i] (nonZero[n] the count, also
  // copied to the counters at nonZeroTotalAt).
  void scanWithNonZero(DeviceBuffer<uint32_t>& data, DeviceBuffer<uint32_t>& nonZero, uint32_t n, const char* stage,
                       uint32_t totalAt, uint32_t nonZeroTotalAt);
  // The scan of the setup counts (triCount_, one byte per input triangle,
  // or clusterCount_ where listsClusters), which lists the input triangle
  // behind each setup record into setupSource_, in two calls: Begin sums
  // the chunks and copies the total to the counters at
  // CLR_COUNTER_SETUP_TOTAL; Finish sizes setupSource_ to it and lists.
  // Other scans may run between the two.
  void scanListingBegin(const char* stage);
  void scanListingFinish(uint64_t total, const char* stage);
  // scan_chunks' arguments (scan.cl): src into dst, with alsoNonZero the
  // non-zero counts into `second` too; a listing reads the byte counts
  // `bytes` and writes the sources into `second`; the totals go to the
  // counters at totalAt and nonZeroTotalAt unless CLR_SCAN_NO_TOTAL.
  struct ScanJob {
    const cl::Buffer& src;
    const cl::Buffer& dst;
    const cl::Buffer& second;
    const cl::Buffer& bytes;
    uint32_t alsoNonZero, listing;  // listing: CLR_SCAN_LIST_*
    uint32_t totalAt, nonZeroTotalAt;
    uint32_t listEnd = 0;  // CLR_SCAN_LIST_CLUSTERS: the input triangles
  };
  ScanJob listingJob() const;  // the listing's arguments (scanListingBegin)
  // Whether setup's listing scans the clusters' totals (CPU shape, scene
  // input: the count pass runs a work-item per cluster), and over how many
  // values (clusters, else input triangles).
  bool listsClusters() const { return cl_.lanes > 1 && !cl_.clipInput; }
  uint32_t listingItems() const
  {
    return listsClusters() ? uint32_t((uint64_t(params_.numTris) + CLR_CLUSTER_TRIS - 1) / CLR_CLUSTER_TRIS)
                           : params_.numTris;
  }
  // scan_chunks' phases: the chunk sums and their scan into `partials`,
  // then the rescan of every chunk.
  void scanSums(const ScanJob& job, uint32_t n, DeviceBuffer<cl_ulong>& partials, const char* stage);
  void scanApply(const ScanJob& job, uint32_t n, const DeviceBuffer<cl_ulong>& partials, const char* stage);
  // scan_chunks' arguments for one phase (CLR_SCAN_REDUCE, _PARTIALS, _APPLY) of job over n counts.
  ScanChunksArgs scanArgs(const ScanJob& job, uint32_t n, const DeviceBuffer<cl_ulong>& partials, uint32_t phase) const;
  // setup_triangles' arguments for one pass (CLR_SETUP_PASS_COUNT, _EMIT) over numSetup records (setup.cpp).
  SetupTrianglesArgs setupTrianglesArgs(uint32_t numSetup, uint32_t pass) const;
  // setupEmit()'s scan of the tile counts: the offsets in place, and the
  // visibility slots (the non-zero counts) in the same launches, their
  // totals copied to the counters (CLR_COUNTER_BIN_TOTAL, SLOT_TOTAL).
  void enqueueBinScans();
  // The clipped triangles' bins (bin_fill_clipped, bin.cl), after setup_emit.
  void binClipped();
  // The frame's counters (shared.h, CLR_COUNTER_*), read with a wait for
  // every command enqueued before; counterTotal joins a total's two words.
  std::vector<uint32_t> readCounters() const { return counters_.download(CLR_NUM_COUNTERS); }
  static uint64_t counterTotal(const std::vector<uint32_t>& counters, uint32_t at)
  {
    return counters[at] | uint64_t(counters[at + 1]) << 32;
  }
  // The tile scans' totals (enqueueBinScans) from a read of the counters.
  void takeBinTotals(const std::vector<uint32_t>& counters)
  {
    slotTotal_ = counterTotal(counters, CLR_COUNTER_SLOT_TOTAL);
    binTotal_ = counterTotal(counters, CLR_COUNTER_BIN_TOTAL);
  }
  // How one pass of the lines stage draws: CLR_WIREFRAME_* mode, CLR_LINE_*
  // method, anti-aliased width in pixels, RGBA8 colour (R in the low byte).
  struct LinePass {
    uint32_t mode, method;
    float width;
    uint32_t colour;
  };
  // The pass FrameSettings' wireframe and line flags ask for (lines.cpp).
  LinePass settingsLinePass() const;
  // Bins and draws the first n segments of lineSegs_ (lines.cpp).
  void drawLineSegments(uint32_t n, const LinePass& pass);
  void record(const char* stage, const cl::Event& event) { events_.push_back({stage, event}); }
  // n work-items rounded up to whole CLR_LINEAR_GROUP work-groups.
  static cl::NDRange linear(uint64_t n);
  // Launches kernel over global in groups of local and records its event as stage; launchLinear over n
  // work-items in CLR_LINEAR_GROUP groups, launchPixels over the tiles' pixels in a group per tile.
  void launch(cl::Kernel& kernel, const cl::NDRange& global, const cl::NDRange& local, const char* stage);
  void launchLinear(cl::Kernel& kernel, uint64_t n, const char* stage);
  void launchPixels(cl::Kernel& kernel, const char* stage);
  // A kernel of the extras program (ClContext::extras), created in `kernel`
  // at its first use.
  cl::Kernel& extraKernel(cl::Kernel& kernel, const char* name);
  // The painter's algorithm's host-side sort (raster.cpp): fills paintOrder_
  // and uploads each triangle's rank to paintRank_.
  void sortForPainter();
  // The micro path (micro.cpp): this frame's size limit, 0 where it is off;
  // microKey_ sized for `slots` micro slots and all ones, and microCap_.
  void initMicro();
  uint32_t microMaxFor(const FrameSettings& settings) const;
  void reserveMicroKeys(uint32_t slots);

  FrameParams params_{};
  FrameSettings settings_{};  // of the current frame
  uint32_t numTiles_ = 0;
  uint32_t numSetup_ = 0;
  bool leanResolve_ = false;  // this frame's resolve kernel was resolve_lambert
  // The size and background of an image that resolve left all background
  // and nothing drew on since (width 0: none); a frame with nothing binned
  // that would paint the same leaves it as it is (resolve.cpp).
  struct BlankImage {
    uint32_t width = 0, height = 0, background = 0;
    bool operator==(const BlankImage& o) const
    {
      return width == o.width && height == o.height && background == o.background;
    }
  } blankImage_;
  // The size and background tileBlank_'s flags were set under; width 0 (none) once anything but resolve drew on
  // the image.
  BlankImage tileBlankImage_;
  bool resolveSkipped_ = false;   // this frame's image was such a blank one
  bool timedPrefetch_ = false;    // this frame's resolve time goes to prefetchChooser_
  bool resolvePrefetch_ = false;  // this frame's resolve fetched rows ahead
  PrefetchChooser prefetchChooser_;
  uint32_t numClipped_ = 0;          // input triangles clipped this frame (clip list length)
  uint32_t numCulledUnclipped_ = 0;  // input triangles the count pass culled (from the scan's total)
  uint64_t numBinEntries_ = 0;
  uint32_t numVisSlots_ = 0;   // tile slots of the visibility buffer's stride: its non-empty tiles, or more (shared.h)
  uint32_t usedVisSlots_ = 0;  // the frame's non-empty tiles (bytesPerPixel)
  // Speculative frames (runFrame): on, this frame's, whether one of this
  // scene ran and its capacities (the CLR_COUNTER_SPECULATIVE words:
  // flag, records, bins, slots), the counters read after its image, and
  // the last frame's outcome (FrameStats).
  bool speculationOn_ = true, speculate_ = false, framedScene_ = false, speculated_ = false, missed_ = false;
  // The CLR_COUNTER_SPECULATIVE .. CLR_COUNTER_CAP_SLOTS words, in order.
  struct SpecCaps {
    uint32_t on, records, bins, slots;
  } specCaps_{};
  std::vector<uint32_t> endCounters_;
  std::vector<std::pair<const char*, cl::Event>> events_;

  cl::Kernel transformKernel_, setupCountKernel_, setupEmitKernel_, setupClipKernel_, scanReduceKernel_,
      scanPartialsKernel_, scanApplyKernel_, binFillClippedKernel_, rasterKernel_, rasterHierarchicalKernel_,
      rasterFloatKernel_, rasterSpansKernel_, rasterSpansFloatKernel_, resolveKernel_, resolveLambertKernel_,
      linesFromSetupKernel_, linesBinCountKernel_, linesBinFillKernel_, linesDrawKernel_, aovKernel_,
      rastOutputsKernel_, peelKernel_;

  DeviceBuffer<FrameParams> paramsBuf_;
  DeviceBuffer<cl_float4> clipPos_;
  DeviceBuffer<uint8_t> triCount_;  // setup counts, see shared.h
  DeviceBuffer<uint32_t> counters_;
  DeviceBuffer<uint32_t> clipList_;
  DeviceBuffer<TriSetup> setup_;
  DeviceBuffer<uint32_t> setupSource_;  // each setup record's source word (shared.h)
  DeviceBuffer<ClipBary> clipBary_;
  DeviceBuffer<uint32_t> tileCount_, tileCursor_, tileSlot_, binEntries_;
  DeviceBuffer<uint32_t> tileBlank_;  // resolve: a tile already background (shared.h)
  DeviceBuffer<cl_ulong> scanPartials_, listingPartials_;
  // The tile scans' totals; binScanned_: setup() enqueued the scans before
  // its wait, as it does when the previous frame clipped nothing
  // (clippedLastFrame_), so that a frame without clipping waits once.
  cl_ulong binTotal_ = 0, slotTotal_ = 0;
  bool binScanned_ = false, clippedLastFrame_ = false;
  DeviceBuffer<uint32_t> visIndex_;  // visibility planes, see shared.h
  DeviceBuffer<float> visAttr_;
  DeviceBuffer<uint32_t> image_;
  void* mappedImage_ = nullptr;       // image_ mapped for an ImageView, unmapped when the next frame begins
  DeviceBuffer<uint32_t> paintRank_;  // see shared.h
  // The micro path (kernels/micro.h): tile flags, fragments, records by rank.
  DeviceBuffer<uint32_t> tileMicro_, microRecord_;
  DeviceBuffer<cl_ulong> microKey_;
  bool microAtomics_ = false;  // the device has cl_khr_int64_extended_atomics
  int32_t microEnv_ = -1;      // CLRASTER_MICRO_MAX, -1 unset
  uint32_t microMax_ = 0;      // this frame's limit (microMaxFor)
  uint32_t microCap_ = 0;      // the micro slots the count pass may claim (micro.h)
  uint32_t microTiles_ = 0;    // the slots the last counted frame claimed
  bool microDirty_ = true;     // microKey_ may hold fragments: refill before use
  std::vector<uint32_t> paintOrder_;
  DeviceBuffer<LineParams> lineParams_;
  DeviceBuffer<LineSeg> lineSegs_;
  DeviceBuffer<uint32_t> lineTileCount_, lineTileCursor_, lineBinEntries_;
  DeviceBuffer<float> aov_;
  DeviceBuffer<cl_float4> rastOut_, rastDb_;
  DeviceBuffer<uint32_t> rastIds_;
  DeviceBuffer<float> peelFloor_, peelNext_;  // peelLayer's depths (peel.cpp)
  bool rastIdsWritten_ = false, rastDbWritten_ = false;
};

}  // namespace clr
