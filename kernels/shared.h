/* shared.h — the plain structs and buffer contract shared by host and kernels.
 *
 * Compiled twice: as C++ by the host (with static_asserts on every size) and
 * as OpenCL C, where it follows fixed.h in the program sources. Every device
 * buffer of a frame is listed below with its writer, its readers and its
 * size, so a reader can follow data through the pipeline
 *   transform -> setup (count, with bin counts) -> scan -> [clip]
 *   -> bin (scan) -> setup emit (with bin fill) -> raster -> resolve.
 */
#ifndef CLR_SHARED_H
#define CLR_SHARED_H

#ifndef __OPENCL_VERSION__
#include <cstdint>
#include "fixed.h"
typedef uint32_t uint;
#endif

#ifdef __OPENCL_VERSION__
/* Kernel helpers. In the GPU shape (CLR_LANES 1) every helper is inlined:
 * a call left inside PoCL's work-item loop stops it from vectorising that
 * loop across work-items. In the CPU shape a work-item runs alone in its
 * work-group, a call costs vectorisation nothing, and the compiler chooses,
 * but for the hot helpers of raster's and resolve's inner loops (CLR_HOT),
 * whose calls cost both kernels about 10% on yxa_1 filling 1080p. Forcing
 * every helper inline made PoCL's build of the frame program longer for no
 * faster frame (the front end optimises each inlined copy): on the 2-core
 * machine the build took 1.39 s with all helpers forced, 1.12 s with the hot
 * ones, 0.98 s with none (medians of eight), and a cold start 2.94 -> 2.59 s
 * (six alternated, in a slow spell of the host), with the same frame times
 * (the 1M sphere near 28.9 ms either way over ten alternated pairs). */
#if CLR_LANES == 1
#define CLR_INLINE inline __attribute__((always_inline))
#else
#define CLR_INLINE inline
#endif
#define CLR_HOT inline __attribute__((always_inline))
/* The few large helpers of resolve are called, not inlined: the CPU shape
 * runs it with one work-item per work-group, where a call costs nothing to
 * vectorisation, and inlining them at each call site made its first
 * compile take most of a cold start. */
#define CLR_CALLED __attribute__((noinline))
/* A kernel's body, as a function the kernel calls. PoCL emits each kernel's
 * code three times (the kernel and its two work-group launchers: `nm` on the
 * cached shared object), so a body inlined into the kernel is optimised and
 * compiled three times; called, once. Measured at cold starts on the 2-core
 * development machine (four alternated), with the same frame times: code
 * generation of setup 0.29-0.32 s -> 0.17-0.20 s, raster 0.15-0.16 ->
 * 0.08-0.09, resolve_lambert 0.27-0.39 -> 0.14-0.16. The GPU shape
 * (CLR_LANES 1) inlines it: there a call inside PoCL's work-item loop would
 * stop its vectorisation. */
#if CLR_LANES == 1
#define CLR_KERNEL_BODY CLR_INLINE
#else
#define CLR_KERNEL_BODY CLR_CALLED
#endif
/* Keeps a loop rolled where unrolling costs compile time and buys nothing
 * (clang's pragma; other compilers ignore it). */
#define CLR_NO_UNROLL _Pragma("nounroll")
/* The sources build two programs (host device.cpp). CLR_EXTRAS 0, the
 * frame program, built at start: every kernel of a default frame (setup,
 * scan, binning, raster, both resolve kernels, the transform kernel).
 * CLR_EXTRAS 1, the extras program, built when a frame first needs one of
 * its kernels: the other raster variants (hierarchical traversal, float
 * edges), lines and AOVs. Each file compiles only its own kernels and the
 * helpers they call into each, so a cold start parses and optimises only
 * what a default frame runs. */
#ifndef CLR_EXTRAS
#define CLR_EXTRAS 0
#endif
#endif

/* Marks "no triangle" in a visibility sample. */
#define CLR_NONE 0xFFFFFFFFu

/* ClipBary.flags bits. */
#define CLR_FLAG_BACKFACING 1u /* wound clockwise on screen (vertices swapped) */
#define CLR_FLAG_DEAD 2u       /* unused slot of a clipped triangle; its record is never binned */

/* A setup record's source word (setupSource, below): who the record came
 * from. The scan lists each record's input triangle; the emit pass adds
 * CLR_SOURCE_BACKFACING to an unclipped record's, and bin_fill_clipped
 * replaces a clipped triangle's by CLR_SOURCE_CLIPPED | its ClipBary slot
 * (a padding record's slot is flagged CLR_FLAG_DEAD). An input triangle's index
 * is below 2^30 (the host limits a scene to 2^32 / CLR_MAX_SUBTRIS
 * triangles, pipeline.cpp) and a slot below CLR_MAX_CLIP_SLOTS (the host's
 * limit on clipped triangles, setup.cpp), so the bits never collide. Until
 * bin_fill_clipped runs, a clipped triangle's reserved records hold
 * CLR_SOURCE_CLIPPED | its input triangle, which keeps the listing sorted
 * for setup_clip's search. */
#define CLR_SOURCE_CLIPPED 0x80000000u    /* clipped: the low 31 bits are the ClipBary slot */
#define CLR_SOURCE_BACKFACING 0x40000000u /* unclipped: wound clockwise (vertices 1, 2 swapped) */
#define CLR_SOURCE_TRIANGLE 0x3FFFFFFFu   /* unclipped: the input triangle */
#define CLR_MAX_CLIP_SLOTS 0x7FFFFFFFu    /* ClipBary slots a frame may have */

/* The clip slot of a record that was not clipped (clr_source_clip_slot). */
#define CLR_NOT_CLIPPED 0xFFFFFFFFu

/* Shading modes (FrameParams.shadeMode). */
#define CLR_SHADE_LAMBERT 0u
#define CLR_SHADE_NORMAL 1u
#define CLR_SHADE_DEPTH 2u
#define CLR_SHADE_ID 3u
#define CLR_SHADE_UV 4u       /* texture coordinates (u, v) as red, green */
#define CLR_SHADE_CHECKER 5u  /* an 8×8 checkerboard per unit of (u, v) */
#define CLR_SHADE_COLOR 6u    /* the vertex colour (mColors[0]), white without one */
#define CLR_SHADE_FLAT 7u     /* Blinn-Phong with the face normal, lit once per triangle */
#define CLR_SHADE_GOURAUD 8u  /* Blinn-Phong per vertex, the light interpolated */
#define CLR_SHADE_PHONG 9u    /* Blinn-Phong per pixel (interpolated normal and position) */
#define CLR_SHADE_TEXTURE 10u /* the unlit base colour: factor × texture × vertex colour */
#define CLR_NUM_SHADE_MODES 11u

/* What a shading mode reads of the input vertices (besides positions for
 * transform). Host and kernel share these: the host uploads only what the
 * frame's mode reads (Pipeline::bindAttributes). Modes that use the albedo
 * also read materials, and texture coordinates with textures, and vertex
 * colours when the scene has them. */
#define CLR_USES_ALBEDO(mode)                                                                \
  ((mode) == CLR_SHADE_LAMBERT || (mode) == CLR_SHADE_FLAT || (mode) == CLR_SHADE_GOURAUD || \
   (mode) == CLR_SHADE_PHONG || (mode) == CLR_SHADE_TEXTURE)
#define CLR_NEEDS_NORMALS(mode)                                                                \
  ((mode) == CLR_SHADE_LAMBERT || (mode) == CLR_SHADE_NORMAL || (mode) == CLR_SHADE_GOURAUD || \
   (mode) == CLR_SHADE_PHONG)
#define CLR_NEEDS_UVS(mode) ((mode) == CLR_SHADE_UV || (mode) == CLR_SHADE_CHECKER)
#define CLR_NEEDS_COLORS(mode) ((mode) == CLR_SHADE_COLOR || CLR_USES_ALBEDO(mode))
/* The colour of a pixel no triangle covers, RGBA8 (R in the low byte):
 * dark blue-grey in the modes that light or colour, black otherwise; resolve
 * paints it under the triangles and wireframe-only frames under their lines
 * (lines.cpp), so a mode's background is the same with and without them. */
#define CLR_BACKGROUND_LIT 0xFF261F1Au
#define CLR_BACKGROUND_UNLIT 0xFF000000u
#define CLR_BACKGROUND(mode) \
  ((CLR_USES_ALBEDO(mode) || (mode) == CLR_SHADE_COLOR) ? CLR_BACKGROUND_LIT : CLR_BACKGROUND_UNLIT)
/* World positions in resolve: face normals, view vectors, the point light. */
#define CLR_NEEDS_POSITIONS(mode, pointLightOn)                                            \
  ((mode) == CLR_SHADE_FLAT || (mode) == CLR_SHADE_GOURAUD || (mode) == CLR_SHADE_PHONG || \
   ((mode) == CLR_SHADE_LAMBERT && (pointLightOn)))

/* FrameParams.texFilter: how base-colour textures are sampled (texture.cl). */
#define CLR_FILTER_NEAREST 0u
#define CLR_FILTER_BILINEAR 1u
#define CLR_FILTER_TRILINEAR 2u /* bilinear in the two nearest mip levels, blended */

/* TextureDesc.wrapS/wrapT (assimp's aiTextureMapMode, glTF's sampler). */
#define CLR_WRAP_REPEAT 0u
#define CLR_WRAP_CLAMP 1u
#define CLR_WRAP_MIRROR 2u

/* Most mip levels of a texture: a 16384-texel side has 15. */
#define CLR_MAX_MIP_LEVELS 16

/* FrameParams.sceneFlags: which optional attributes the frame binds. */
#define CLR_SCENE_COLORS 1u    /* the colours buffer holds vertex colours */
#define CLR_SCENE_MATERIALS 2u /* triMaterial and materials hold the scene's materials */
#define CLR_SCENE_TEXTURES 4u  /* texDescs, texels and uvs hold the base-colour textures */

/* Most samples per pixel (FrameParams.samples). */
#define CLR_MAX_SAMPLES 16

/* FrameParams.edgeMode: how raster evaluates the three edge functions. */
#define CLR_EDGES_FIXED 0u /* 64-bit integers on the snapped grid: exact (fixed.h) */
#define CLR_EDGES_FLOAT 1u /* 32-bit floats in pixel units: rounds, cracks when large */

/* FrameParams.interpMode: how resolve interpolates attributes. */
#define CLR_INTERP_PERSPECTIVE 0u /* the 1/w rule of the notes */
#define CLR_INTERP_AFFINE 1u      /* screen-space barycentrics as they are */

/* FrameParams.traversal: which tiles and samples a triangle is tested on. */
#define CLR_TRAVERSAL_BBOX 0u         /* every tile and row of its bounding box */
#define CLR_TRAVERSAL_HIERARCHICAL 1u /* tiles outside an edge rejected, tiles inside all edges accepted */

/* FrameParams.depthMode: the depth buffer's format and compare. Every mode
 * keeps the earlier triangle on an exact tie. */
#define CLR_DEPTH_FLOAT32 0u /* window z = z_ndc/2 + 1/2 in [0, 1], LESS, clear 1 */
#define CLR_DEPTH_UNORM24 1u /* the same z quantised to rint(z·(2^24 − 1)) before the compare, as GL depth24 */
#define CLR_DEPTH_REVERSED                                                                                             \
  2u                                      /* reversed-Z float: window z = z_ndc (near 1, far 0), GREATER, clear 0; the \
                                           * host builds a reversed projection and the near plane is z <= w */
#define CLR_DEPTH_UNORM24_MAX 16777215.0f /* 2^24 − 1 */

/* FrameParams.visibility: how raster picks the visible fragment. */
#define CLR_VISIBILITY_ZBUFFER 0u /* the depth test of depthMode */
#define CLR_VISIBILITY_PAINTER                                                     \
  1u /* no depth test between triangles: the one latest in the host's far-to-near  \
      * order (the paintRank buffer) wins; fragments beyond the far plane (failing \
      * the test against the clear value) are still dropped */

/* Work-group size of setup_triangles: 64 work-items on a GPU; one on a CPU,
 * where each handles 16 triangles in vector types and a bigger group only
 * adds a work-item loop for PoCL to compile. */
#define CLR_SETUP_GROUP(lanes) ((lanes) == 1 ? 64 : 1)

/* Setup's clusters (CPU work shape only): the bounds of the vertices of each
 * run of CLR_CLUSTER_TRIS consecutive input triangles, as 6 floats (min x,
 * y, z, max x, y, z; NaN for a run without a finite vertex). Written by the
 * host when a scene is uploaded (Pipeline::uploadScene), read by the count
 * pass, which skips a batch whose cluster lies wholly beside the view
 * (setup_cluster_outside, setup.cl): 24 bytes per 256 triangles. */
#define CLR_CLUSTER_TRIS 256

/* Work-group size of scan_chunks (scan.cl): 64 on a GPU, one on a CPU,
 * for the same reason (PoCL compiled it in 120 ms with 64, 81 ms with 1). */
#define CLR_SCAN_GROUP(lanes) ((lanes) == 1 ? 64 : 1)

/* The pass argument of setup_triangles (setup.cl). */
#define CLR_SETUP_PASS_COUNT 0u /* count screen triangles and tiles */
#define CLR_SETUP_PASS_EMIT 1u  /* write setup records and bin entries */

/* The phase argument of scan_chunks (scan.cl). */
#define CLR_SCAN_REDUCE 0u   /* a sum per chunk */
#define CLR_SCAN_PARTIALS 2u /* one work-group scans the chunk sums */
#define CLR_SCAN_APPLY 1u    /* each chunk rescanned from its offset */

/* Indices into the frame's counter buffer, zeroed as a frame begins.
 * CULLED_TRIS counts only the clipped triangles that produce nothing
 * (setup_clip); the host adds the count pass's culls, which it derives from
 * the scan's total (Pipeline::setup). The three scans before the host's
 * wait copy their 64-bit totals there (low word, then high), so that one
 * read returns them with the clip list's length. */
#define CLR_COUNTER_CLIPPED_TRIS 0 /* input triangles that needed clipping (clip list length) */
#define CLR_COUNTER_CULLED_TRIS 1  /* clipped input triangles that produced nothing */
#define CLR_COUNTER_DEAD_RECORDS 2 /* padding records written by setup_clip */
#define CLR_COUNTER_SETUP_TOTAL 3  /* 2 words: setup records (the setup counts' scan) */
#define CLR_COUNTER_SLOT_TOTAL 5   /* 2 words: visibility-buffer tile slots (bin_scan's non-zero counts) */
#define CLR_COUNTER_BIN_TOTAL 7    /* 2 words: bin entries (bin_scan) */
#define CLR_NUM_COUNTERS 9
#define CLR_SCAN_NO_TOTAL 0xFFFFFFFFu /* scan_chunks' totalAt: no copy among the counters */

/* Per-frame constants. Written by the host once per frame; read by every
 * kernel. One struct, 368 bytes. */
typedef struct FrameParams {
  float mvp[16];     /* column-major, clip = mvp · (x, y, z, 1) */
  float lightDir[4]; /* world space, unit, towards the light */
  float guardX;      /* guard-band clip factor g_x (see fixed.h) */
  float guardY;
  float halfWidth; /* viewport matrix: x_s = x_ndc·W/2 + W/2 */
  float halfHeight;
  float zNear;
  float zFar;
  uint width;
  uint height;
  uint tilesX;
  uint tilesY;
  uint numVerts;
  uint numTris;
  uint cullBack;         /* 1: cull clockwise (back-facing) triangles */
  uint shadeMode;        /* CLR_SHADE_* */
  uint samples;          /* samples per pixel: 1, 2, 4, 8 or 16 */
  uint shadeEverySample; /* 0: MSAA, shade once per pixel and triangle; 1: SSAA */
  uint edgeMode;         /* CLR_EDGES_* */
  uint interpMode;       /* CLR_INTERP_* */
  uint traversal;        /* CLR_TRAVERSAL_* */
  /* Extent of the sample offsets below, for bounds: min and max over k. */
  int sampleMinX, sampleMaxX, sampleMinY, sampleMaxY;
  uint depthMode; /* CLR_DEPTH_* */
  /* Lighting (shade.cl): the eye for the view vector, an optional point
   * light at pointLight.xyz with attenuation 1 / (1 + (d / pointLight.w)²). */
  float eye[4];
  float pointLight[4];
  uint pointLightOn;  /* 1: the point light shines (besides lightDir) */
  uint texFilter;     /* CLR_FILTER_* */
  uint sceneFlags;    /* CLR_SCENE_*: what the host bound for this frame */
  uint visAttributes; /* 1: raster also writes the depth and barycentric planes */
  /* Sample k of a pixel lies at its centre + (sampleX[k], sampleY[k]) in
   * fixed-point units (y up); the host fills them (host/aa.cpp). */
  int sampleX[CLR_MAX_SAMPLES];
  int sampleY[CLR_MAX_SAMPLES];
  uint visibility; /* CLR_VISIBILITY_* */
  uint visIndex16; /* 1: the visibility buffer's index planes are 16 bits wide (shared.h) */
  /* 1: setup culls a small triangle that covers none of the pixel centres
   * in its bounds (setup_covers_a_sample, setup.cl); the host sets it for
   * frames of one sample, fixed edges and no wireframe. */
  uint cullSampleFree;
  /* > 0: the count pass tests setup's clusters against the view with this
   * margin in clip units (setup_cluster_outside, setup.cl); the host sets
   * it on a CPU device when the scene's bounds reach well beyond the view, 0
   * otherwise, so that frames of a scene about the size of the view skip
   * the test (Pipeline::clusterMargin). */
  float clusterMargin;
  /* 1: the scene's triangles lie in the file's order (host layout.h), so
   * fileTri is the identity and not bound: readers take the index itself. */
  uint fileOrder;
} FrameParams;

/* The image pixel (x, y) of screen space (y up; pixel (0, 0) at the bottom
 * left): the RGBA8 image is stored top row first, width pixels a row.
 * Written by resolve and lines_draw. */
#ifdef __OPENCL_VERSION__
CLR_INLINE __global uint* clr_image_pixel(__constant FrameParams* params, __global uint* image, uint x, uint y)
{
  return &image[(params->height - 1 - y) * params->width + x];
}
#endif

/* One screen-space triangle after clipping, snapping and orientation to
 * counter-clockwise (y up): its geometry only, 48 bytes. Its input
 * triangle, winding and clip slot are in its source word (setupSource,
 * CLR_SOURCE_*); its 1 / (2·area) is recomputed where needed
 * (clr_inv_area2). Written by setup_triangles' emit pass and setup_clip,
 * read by bin_fill_clipped, raster, resolve, lines_from_setup and aov.
 * Array size: the scanned setup count (records whose ClipBary slot is
 * flagged CLR_FLAG_DEAD are padding). */
typedef struct TriSetup {
  int x[3];      /* snapped fixed-point screen x, CLR_SUBPIXEL_BITS */
  int y[3];      /* snapped fixed-point screen y */
  float z[3];    /* window depth in [0, 1] (reversed with CLR_DEPTH_REVERSED) */
  float invW[3]; /* 1 / w_clip, for the perspective correction */
} TriSetup;

/* 1 / (2·signed area) of a counter-clockwise setup triangle, in fixed
 * units⁻²: the scale from edge functions to screen barycentrics. Setup
 * computes it to cull; the readers recompute it from the record instead of
 * storing it (16 bytes a record with the source's fields). The doubled
 * area is exact in 64 bits (fixed.h) and its conversion to float and the
 * division are correctly rounded, so every stage gets the same float. */
#ifdef __OPENCL_VERSION__
CLR_INLINE float clr_inv_area2(int x0, int y0, int x1, int y1, int x2, int y2)
{
  const long area2 = (long)(x1 - x0) * (long)(y2 - y0) - (long)(x2 - x0) * (long)(y1 - y0);
  return 1.0f / (float)area2;
}
#else
inline float clr_inv_area2(int x0, int y0, int x1, int y1, int x2, int y2)
{
  const int64_t area2 = int64_t(x1 - x0) * int64_t(y2 - y0) - int64_t(x2 - x0) * int64_t(y1 - y0);
  return 1.0f / float(area2);
}
#endif
/* clr_inv_area2 of setup record t (a TriSetup, or a record read back with
 * its fields). */
#define CLR_RECORD_INV_AREA2(t) clr_inv_area2((t).x[0], (t).y[0], (t).x[1], (t).y[1], (t).x[2], (t).y[2])
/* The bounds of setup record t's snapped vertices, fixed units, as an
 * int4 (min x, min y, max x, max y); kernels only. */
#define CLR_RECORD_BOUNDS(t)                                                              \
  ((int4)(min((t).x[0], min((t).x[1], (t).x[2])), min((t).y[0], min((t).y[1], (t).y[2])), \
          max((t).x[0], max((t).x[1], (t).x[2])), max((t).y[0], max((t).y[1], (t).y[2]))))

/* Barycentrics of a clipped sub-triangle's vertices with respect to its
 * input triangle (w[i][j] is the weight of input vertex j in sub-vertex i),
 * and the input triangle with the sub-triangle's winding. Written by
 * setup_clip, read by bin_fill_clipped, resolve, lines_from_setup and aov.
 * Array size: CLR_MAX_SUBTRIS per clipped input triangle; clipList entry
 * i owns slots i·CLR_MAX_SUBTRIS + k, its unused ones flagged
 * CLR_FLAG_DEAD. */
typedef struct ClipBary {
  float w[3][3];
  uint triId; /* the input triangle */
  uint flags; /* CLR_FLAG_* */
} ClipBary;

/* A setup record's clip slot from its source word, or CLR_NOT_CLIPPED
 * (host and kernels). */
#ifdef __OPENCL_VERSION__
CLR_INLINE uint clr_source_clip_slot(uint source)
#else
inline uint clr_source_clip_slot(uint source)
#endif
{
  return (source & CLR_SOURCE_CLIPPED) ? source & ~CLR_SOURCE_CLIPPED : CLR_NOT_CLIPPED;
}

#ifdef __OPENCL_VERSION__
/* A binned setup record's input triangle and winding, from its source word
 * (and its ClipBary slot when clipped). */
CLR_INLINE uint clr_source_triangle(uint source, __global const ClipBary* clipBary)
{
  const uint slot = clr_source_clip_slot(source);
  return slot != CLR_NOT_CLIPPED ? clipBary[slot].triId : source & CLR_SOURCE_TRIANGLE;
}
CLR_INLINE bool clr_source_backfacing(uint source, __global const ClipBary* clipBary)
{
  const uint slot = clr_source_clip_slot(source);
  return slot != CLR_NOT_CLIPPED ? (clipBary[slot].flags & CLR_FLAG_BACKFACING) != 0
                                 : (source & CLR_SOURCE_BACKFACING) != 0;
}
#endif

/* A material's base colour: factor (RGBA, linear in the 8-bit values) times
 * the texture's texel when texture >= 0. Written by the host (scene upload),
 * read by resolve. Array size: the scene's material count. */
typedef struct Material {
  float baseColor[4];
  int texture; /* index into texDescs, or -1 */
  uint pad[3];
} Material;

/* One texture in the texels buffer: level l (0 = full size) is
 * max(1, width >> l) × max(1, height >> l) RGBA8 texels (R in the low byte),
 * rows bottom first (v = 0 is row 0), from texels[levelOffset[l]]. Written
 * by the host (host/texture.cpp), read by resolve. Array size: the scene's
 * texture count. */
typedef struct TextureDesc {
  uint width, height, levels;
  uint wrapS, wrapT; /* CLR_WRAP_* for u and v */
  uint pad[3];
  uint levelOffset[CLR_MAX_MIP_LEVELS];
} TextureDesc;

/* The visibility buffer: the nearest fragment of each pixel sample. Only
 * tiles that hold a triangle have room in it: tile t, when its bin is not
 * empty, owns slot tileSlot[t] (an exclusive scan over the non-empty tiles,
 * host bin.cpp), a block of CLR_TILE_SIZE² entries in row order, so a row of a
 * tile is one vector load or store and memory follows the covered tiles,
 * not the viewport. With S = FrameParams.samples and the plane size
 * V = slots · CLR_TILE_SIZE² (the kernels' visPlane argument), sample k of
 * pixel (x, y) in tile t is, with a = vis_address(tileSlot[t], x, y),
 *  visIndex uint[S·V]     at k·V + a: setup index, or CLR_NONE; as ushort
 *                         (0xFFFF for none) when FrameParams.visIndex16
 *  visAttr  float[3·S·V]  at (3k + c)·V + a: c = 0 window depth, 1 b1, 2 b2
 * (the depth plane holds the depth as its format stores it: unorm24 reads
 * back as q / (2^24 − 1); with CLR_VISIBILITY_PAINTER it holds the paint
 * rank of the visible triangle, as uint bits).
 * visIndex is written by raster and read by resolve, lines_draw and aov
 * (through vis_index_at and its kin in raster.cl): 2 bytes per sample of a
 * covered tile when the frame has fewer than 2^16 − 1 setup records (the
 * host sets visIndex16 once setup has counted them), else 4. The visAttr
 * planes exist only when FrameParams.visAttributes is 1 (the host sets it
 * for frames whose readers need them: lines, AOVs, float edges,
 * Pipeline::readVis's depth and barycentrics); raster then writes them, 12
 * more bytes per sample. Without them resolve recomputes b1 and b2 from
 * the setup record at the sample (vis_barycentrics in raster.cl), the same
 * integers and floats raster computed. Entries of a tile's block outside
 * the viewport are written but never read.
 * VisSample is one sample as Pipeline::readVis() returns it. */
#ifdef __OPENCL_VERSION__
CLR_INLINE uint vis_address(uint slot, uint x, uint y)
#else
inline uint vis_address(uint slot, uint x, uint y)
#endif
{
  return slot * (CLR_TILE_SIZE * CLR_TILE_SIZE) + (y % CLR_TILE_SIZE) * CLR_TILE_SIZE + x % CLR_TILE_SIZE;
}

typedef struct VisSample {
  uint setupIndex; /* index into TriSetup, or CLR_NONE */
  float depth;     /* window depth of the fragment (see visAttr) */
  float b1;        /* screen-space barycentric of vertex 1 */
  float b2;        /* screen-space barycentric of vertex 2 */
} VisSample;

/* The remaining buffers of a frame, all typed:
 *  positions  float[3·numVerts]   host upload;  read by setup (which
 *                                 transforms them, transform.cl), resolve
 *                                 and transform_vertices
 * The next ones are uploaded only when a frame's shading reads them (host
 * pipeline.cpp, Pipeline::bindAttributes); otherwise a 1-element dummy is
 * bound and resolve never reads it:
 *  normals    float[3·numVerts]   host upload;  read by resolve
 *  uvs        float[2·numVerts]   host upload (zeros when the mesh has
 *                                 none); read by resolve
 *  colors     float[4·numVerts]   host upload (vertex colours); resolve
 *  triMaterial uint[numTris]      host upload (material per triangle); resolve
 *  materials  Material[numMaterials] host upload; read by resolve
 *  texDescs   TextureDesc[numTextures] host upload, once per scene; resolve
 *  texels     uint[all levels of all textures] host upload, once; resolve
 *  indices    uint[3·numTris]     host upload;  read by setup, resolve
 *  clipPos    float4[numVerts]    transform_vertices, only when the host
 *                                 sorts for the painter's algorithm (which
 *                                 reads it) or a test asks; not a frame's
 *  triCount   uchar[numTris]      setup_triangles' count pass writes the
 *                                 screen triangles each input triangle
 *                                 yields (0, 1 or CLR_MAX_SUBTRIS); read by
 *                                 the scan, which lists them (one byte per
 *                                 triangle: offsets live only in the listing)
 *  setupSource uint[numSetup + chunks] each setup record's source word
 *                                 (CLR_SOURCE_*): the scan of triCount
 *                                 (scan.cl, listSources) lists the input
 *                                 triangle behind each record, then a spare
 *                                 entry per scan chunk (at most 4096) that
 *                                 takes the culled ones' stores; setup_clip
 *                                 searches it; the emit pass and
 *                                 bin_fill_clipped complete it; read by
 *                                 raster (painter), resolve, lines_from_setup
 *                                 and aov
 *  clipList   uint[CLIPPED_TRIS]  the count pass lists triangles to clip (the
 *                                 host grows it and recounts if it was
 *                                 short); setup_clip reads each and replaces
 *                                 it with the index of the triangle's first
 *                                 reserved record; bin_fill_clipped reads that
 *  tileCount  uint[tiles + 1]     the count pass and setup_clip count each
 *                                 tile's triangles (bin.cl), then scanned to
 *                                 offsets; read by the emit pass,
 *                                 bin_fill_clipped, raster and resolve
 *  tileCursor uint[tiles]         the emit pass and bin_fill_clipped (atomic
 *                                 cursors)
 *  tileSlot   uint[tiles + 1]     scan_chunks counts the non-zero tile counts
 *                                 into visibility-buffer slots (last = slot
 *                                 count); read by raster, resolve,
 *                                 lines_draw and aov
 *  binEntries uint[total]         the emit pass and bin_fill_clipped write
 *                                 setup indices; raster reads
 *  scanPartials ulong[2 · (chunks + 1)] scan internals (chunks at most 4096)
 *  paintRank  uint[numTris]       host upload: with CLR_VISIBILITY_PAINTER
 *                                 the position of each input triangle in
 *                                 the far-to-near order, otherwise its index
 *                                 in the file (fileTri, the scene's layout,
 *                                 host layout.h: depth ties); read by raster
 *  fileTri    uint[numTris]       host upload: each input triangle's index
 *                                 in the file (one unused element when
 *                                 FrameParams.fileOrder); read by resolve
 *                                 (--shade id) and aov (triangle_id)
 *  counters   uint[CLR_NUM_COUNTERS] setup kernels and the scans' totals;
 *                                 host reads them at its wait, and at the
 *                                 frame's end for stats when it clipped
 *  image      uint[width·height]  resolve writes RGBA8, top row first
 *                                 (lines_draw then blends the lines in)
 *  lineParams LineParams[1]       host; read by the lines kernels
 *  lineSegs   LineSeg[segments]   lines_from_setup or host upload
 *  lineTileCount uint[tiles + 1]  lines_bin_count, scanned to offsets; read
 *                                 by lines_bin_fill and lines_draw
 *  lineTileCursor uint[tiles]     lines_bin_fill (atomic cursors)
 *  lineBinEntries uint[total]     lines_bin_fill writes segment indices;
 *                                 lines_draw reads
 *  aov        float[10·width·height] aov writes (CLR_AOV_*); host reads
 */

/* Lines (kernels/lines.cl): LineParams.mode and LineParams.method. */
#define CLR_WIREFRAME_OFF 0u     /* no lines */
#define CLR_WIREFRAME_OVERLAY 1u /* lines blended over the shaded image */
#define CLR_WIREFRAME_ONLY 2u    /* lines over the background only */
#define CLR_LINE_AA 0u           /* coverage from the perpendicular distance */
#define CLR_LINE_BRESENHAM 1u    /* integer decision variable, one pixel per step */

/* LineSeg.flags: the segment is not drawn (a clip-made edge, a dead record). */
#define CLR_LINE_SKIP 1u

/* One line segment in screen space. Written by lines_from_setup (three per
 * setup record, edge e from vertex e to vertex (e + 1) % 3) or uploaded by
 * the host (Pipeline::lines(segments)); read by lines_bin_count,
 * lines_bin_fill and lines_draw. Array size: the segment count. */
typedef struct LineSeg {
  int x[2];   /* fixed-point screen x of the endpoints, CLR_SUBPIXEL_BITS */
  int y[2];   /* fixed-point screen y */
  float z[2]; /* window depth of the endpoints */
  uint triId; /* input triangle it came from (informational) */
  uint flags; /* CLR_LINE_* flags */
} LineSeg;

/* Per-frame line constants. Written by the host (Pipeline::lines), read by
 * the lines kernels. One struct, 32 bytes. */
typedef struct LineParams {
  uint mode;        /* CLR_WIREFRAME_* */
  uint method;      /* CLR_LINE_* */
  float width;      /* anti-aliased line width in pixels, in (0, 16] */
  float reach;      /* pixels a drawn pixel centre may lie from the segment */
  float depthBias;  /* constant window-depth offset of the depth test */
  uint colour;      /* RGBA8 of the lines, R in the low byte */
  uint background;  /* RGBA8 under the lines in CLR_WIREFRAME_ONLY */
  uint numSegments; /* segments in the LineSeg buffer */
} LineParams;

/* Visibility-buffer outputs (kernels/aov.cl): plane c of the AOV buffer
 * float[CLR_AOV_CHANNELS · width · height], pixel (i, j) at c·P + j·W + i
 * (bottom row first). Written by aov, read by the host (Pipeline::readAov). */
#define CLR_AOV_TRIANGLE_ID 0 /* the triangle's index in the file as a float, −1 = none */
#define CLR_AOV_BARY_U 1      /* perspective-correct weight of input vertex 1 */
#define CLR_AOV_BARY_V 2      /* perspective-correct weight of input vertex 2 */
#define CLR_AOV_SCREEN_U 3    /* screen-space (affine) weight of input vertex 1 */
#define CLR_AOV_SCREEN_V 4    /* screen-space (affine) weight of input vertex 2 */
#define CLR_AOV_Z_W 5         /* window depth z/w mapped to [0, 1], 1 = none */
#define CLR_AOV_EYE_DEPTH 6   /* eye-space depth w_clip, +inf = none */
#define CLR_AOV_NORMAL_X 7    /* interpolated, normalised vertex normal */
#define CLR_AOV_NORMAL_Y 8
#define CLR_AOV_NORMAL_Z 9
#define CLR_AOV_CHANNELS 10

#ifndef __OPENCL_VERSION__
static_assert(sizeof(FrameParams) == 372, "FrameParams layout must match the kernels");
static_assert(sizeof(TriSetup) == 48, "TriSetup layout must match the kernels");
static_assert(sizeof(ClipBary) == 44, "ClipBary layout must match the kernels");
static_assert(sizeof(VisSample) == 16, "VisSample layout must match the kernels");
static_assert(sizeof(Material) == 32, "Material layout must match the kernels");
static_assert(sizeof(TextureDesc) == 96, "TextureDesc layout must match the kernels");
static_assert(sizeof(LineSeg) == 32, "LineSeg layout must match the kernels");
static_assert(sizeof(LineParams) == 32, "LineParams layout must match the kernels");
#endif

#endif /* CLR_SHARED_H */
