/* shared.h — the plain structs, constants and buffer contract shared by host and kernels.
 *
 * Compiled as C++ by the host (static_asserts pin every struct size) and as OpenCL C after fixed.h. Each buffer
 * and struct below names its writer, its readers and its size. Data flow of a frame:
 *   transform -> setup (count, with bin counts) -> scan -> [clip]
 *   -> bin (scan) -> setup emit (with bin fill; micro triangles' fragments, micro.h) -> raster -> resolve.
 */
#ifndef CLR_SHARED_H
#define CLR_SHARED_H

#ifndef __OPENCL_VERSION__
#include <cstdint>
#include "fixed.h"
typedef uint32_t uint;
#endif

#ifdef __OPENCL_VERSION__
/* Inlining. GPU shape (CLR_LANES 1): every helper inline, since a call inside PoCL's work-item loop stops it
 * vectorising across work-items. CPU shape: the compiler chooses, except the hot inner-loop helpers (CLR_HOT);
 * forcing more only lengthens the program build (bench/ab.sh). */
#if CLR_LANES == 1
#define CLR_INLINE inline __attribute__((always_inline))
#else
#define CLR_INLINE inline
#endif
#define CLR_HOT inline __attribute__((always_inline))
/* Large resolve helpers stay calls: one work-item per group in the CPU shape, so a call costs no vectorisation. */
#define CLR_CALLED __attribute__((noinline))
/* A kernel's body as a called function: PoCL emits each kernel three times (kernel and two work-group launchers),
 * so a called body is compiled once. The GPU shape inlines it (see CLR_INLINE). */
#if CLR_LANES == 1
#define CLR_KERNEL_BODY CLR_INLINE
#else
#define CLR_KERNEL_BODY CLR_CALLED
#endif
/* Keeps a loop rolled where unrolling costs compile time and buys nothing (clang; others ignore it). */
#define CLR_NO_UNROLL _Pragma("nounroll")
/* Two programs (host device.cpp): CLR_EXTRAS 0, built at start, holds every kernel of a default frame;
 * CLR_EXTRAS 1, built on first need, holds hierarchical/float-edge raster, lines and AOVs. */
#ifndef CLR_EXTRAS
#define CLR_EXTRAS 0
#endif
#endif

/* Marks "no triangle" in a visibility sample. */
#define CLR_NONE 0xFFFFFFFFu

/* ClipBary.flags bits. */
#define CLR_FLAG_BACKFACING 1u /* wound clockwise on screen (vertices swapped) */
#define CLR_FLAG_DEAD 2u       /* unused slot of a clipped triangle; its record is never binned */

/* A setup record's source word (setupSource): the scan lists each record's input triangle; emit adds
 * CLR_SOURCE_BACKFACING, bin_fill_clipped replaces a clipped one's by CLR_SOURCE_CLIPPED | ClipBary slot.
 * Bits never collide: triangles < 2^30 (pipeline.cpp limits a scene to 2^32 / CLR_MAX_SUBTRIS) and slots
 * < CLR_MAX_CLIP_SLOTS (setup.cpp). Until bin_fill_clipped, clipped records hold CLR_SOURCE_CLIPPED | input
 * triangle, keeping the listing sorted for setup_clip's search. */
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

/* What a mode reads of the vertices besides positions; the host uploads only that (Pipeline::bindAttributes).
 * Albedo modes also read materials, uvs with textures, and colours when the scene has them. */
#define CLR_USES_ALBEDO(mode)                                                                \
  ((mode) == CLR_SHADE_LAMBERT || (mode) == CLR_SHADE_FLAT || (mode) == CLR_SHADE_GOURAUD || \
   (mode) == CLR_SHADE_PHONG || (mode) == CLR_SHADE_TEXTURE)
#define CLR_NEEDS_NORMALS(mode)                                                                \
  ((mode) == CLR_SHADE_LAMBERT || (mode) == CLR_SHADE_NORMAL || (mode) == CLR_SHADE_GOURAUD || \
   (mode) == CLR_SHADE_PHONG)
#define CLR_NEEDS_UVS(mode) ((mode) == CLR_SHADE_UV || (mode) == CLR_SHADE_CHECKER)
#define CLR_NEEDS_COLORS(mode) ((mode) == CLR_SHADE_COLOR || CLR_USES_ALBEDO(mode))
/* Background RGBA8 (R low byte): lit/coloured modes dark blue-grey, others black; painted by resolve, and by
 * lines.cpp in wireframe-only frames, so a mode's background is the same either way. */
#define CLR_BACKGROUND_LIT 0xFF261F1Au
#define CLR_BACKGROUND_UNLIT 0xFF000000u
#define CLR_BACKGROUND(mode) \
  ((CLR_USES_ALBEDO(mode) || (mode) == CLR_SHADE_COLOR) ? CLR_BACKGROUND_LIT : CLR_BACKGROUND_UNLIT)
/* World positions in resolve: face normals, view vectors, the point light. */
#define CLR_NEEDS_POSITIONS(mode, pointLightOn)                                            \
  ((mode) == CLR_SHADE_FLAT || (mode) == CLR_SHADE_GOURAUD || (mode) == CLR_SHADE_PHONG || \
   ((mode) == CLR_SHADE_LAMBERT && (pointLightOn)))

/* FrameParams.texFilter: how base-colour textures are sampled (texture.h). */
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
#define CLR_SCENE_MATERIALS 2u /* materials holds the scene's materials (else albedo is grey) */
#define CLR_SCENE_TEXTURES 4u  /* texDescs, texels and uvs hold the base-colour textures */
/* triMaterial holds each triangle's material; without it every triangle has material 0 (one material). */
#define CLR_SCENE_TRI_MATERIALS 8u

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
#define CLR_TRAVERSAL_SPANS 2u        /* each row's first and last sample from the fixed edges: exact */
#define CLR_TRAVERSAL_SPANS_FLOAT 3u  /* the classic float edge walk of the notes: rounds, cracks */

/* FrameParams.depthMode: the depth buffer's format and compare; every mode keeps the earlier triangle on a tie. */
#define CLR_DEPTH_FLOAT32 0u  /* window z = z_ndc/2 + 1/2 in [0, 1], LESS, clear 1 */
#define CLR_DEPTH_UNORM24 1u  /* the same z quantised to rint(z·(2^24 − 1)) before the compare, as GL depth24 */
#define CLR_DEPTH_REVERSED 2u /* reversed-Z float: z = z_ndc (near 1, far 0), GREATER, clear 0 */
#define CLR_DEPTH_UNORM24_MAX 16777215.0f /* 2^24 − 1 */

/* FrameParams.visibility: how raster picks the visible fragment. */
#define CLR_VISIBILITY_ZBUFFER 0u /* the depth test of depthMode */
#define CLR_VISIBILITY_PAINTER 1u /* latest in far-to-near paintRank wins; beyond-far fragments still dropped */

/* Work-group size of the kernels launched over a plain count (transform_vertices, setup_clip, bin_fill_clipped,
 * lines_from_setup, lines_bin_count, lines_bin_fill; host Pipeline::launchLinear), and of setup_triangles and
 * scan_chunks in the GPU shape. */
#define CLR_LINEAR_GROUP 64

/* Work-group size of setup_triangles: CLR_LINEAR_GROUP on a GPU; 1 on a CPU, where a work-item takes 16 triangles
 * in vectors. */
#define CLR_SETUP_GROUP(lanes) ((lanes) == 1 ? CLR_LINEAR_GROUP : 1)

/* Setup clusters (CPU shape): 6 floats of vertex bounds (min xyz, max xyz; NaN if one is not finite) per
 * CLR_CLUSTER_TRIS input triangles. Host writes (Pipeline::uploadScene); the count pass reads
 * (setup_cluster_place). Size 24 bytes per 256 triangles. */
#define CLR_CLUSTER_TRIS 256

/* Work-group size of scan_chunks (scan.cl): as CLR_SETUP_GROUP. */
#define CLR_SCAN_GROUP(lanes) ((lanes) == 1 ? CLR_LINEAR_GROUP : 1)
/* How scan_chunks splits n counts (host scanChunks): at most CLR_SCAN_MAX_CHUNKS chunks, which its partials phase
 * scans in one work-group, of at least CLR_SCAN_MIN_CHUNK counts each. */
#define CLR_SCAN_MAX_CHUNKS 4096
#define CLR_SCAN_MIN_CHUNK 64

/* The pass argument of setup_triangles (setup.cl). */
#define CLR_SETUP_PASS_COUNT 0u /* count screen triangles and tiles */
#define CLR_SETUP_PASS_EMIT 1u  /* write setup records and bin entries */

/* The phase argument of scan_chunks (scan.cl). */
#define CLR_SCAN_REDUCE 0u   /* a sum per chunk */
#define CLR_SCAN_PARTIALS 2u /* one work-group scans the chunk sums */
#define CLR_SCAN_APPLY 1u    /* each chunk rescanned from its offset */
/* The listSources argument of scan_chunks: no listing, the setup counts' bytes (one per input triangle), or the
 * clusters' totals (setup.cl, CPU shape), whose listing reads the bytes of non-empty clusters only. */
#define CLR_SCAN_LIST_NONE 0u
#define CLR_SCAN_LIST_BYTES 1u
#define CLR_SCAN_LIST_CLUSTERS 2u

/* counters: uint[CLR_NUM_COUNTERS], zeroed per frame; setup kernels and the scans write, the host reads at its
 * wait (one read), or after the image in a frame sized from the last one's totals (speculative, Pipeline::beginFrame,
 * which writes the capacities). The host adds the count pass's culls, derived from the scan total (Pipeline::setup). */
#define CLR_COUNTER_CLIPPED_TRIS 0 /* input triangles that needed clipping (clip list length) */
#define CLR_COUNTER_CULLED_TRIS 1  /* clipped input triangles that produced nothing */
#define CLR_COUNTER_DEAD_RECORDS 2 /* padding records written by setup_clip */
#define CLR_COUNTER_SETUP_TOTAL 3  /* 2 words: setup records (the setup counts' scan) */
#define CLR_COUNTER_SLOT_TOTAL 5   /* 2 words: visibility-buffer tile slots (bin_scan's non-zero counts) */
#define CLR_COUNTER_BIN_TOTAL 7    /* 2 words: bin entries (bin_scan) */
#define CLR_COUNTER_SPECULATIVE 9  /* host: 1 when the frame is sized from the last one's totals */
#define CLR_COUNTER_CAP_RECORDS 10 /* host, speculative: the most setup records the buffers and emit's launch hold */
#define CLR_COUNTER_CAP_BINS 11    /* host, speculative: binEntries' capacity */
#define CLR_COUNTER_CAP_SLOTS 12   /* host, speculative: the tile slots of the visibility buffer's stride */
#define CLR_COUNTER_OVERFLOW 13    /* bin_scan, speculative: 1 when the frame does not fit (scan.cl); host redoes it */
#define CLR_COUNTER_MICRO_TILES 14 /* setup count pass: micro-path tile slots claimed (micro.h) */
#define CLR_NUM_COUNTERS 15
#define CLR_SCAN_NO_TOTAL 0xFFFFFFFFu /* scan_chunks' totalAt: no copy among the counters */

/* FrameParams[1], 376 bytes: the host writes it per frame; every kernel reads it. */
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
  /* Eye for the view vector; point light at pointLight.xyz, attenuation 1 / (1 + (d / pointLight.w)²). */
  float eye[4];
  float pointLight[4];
  uint pointLightOn;  /* 1: the point light shines (besides lightDir) */
  uint texFilter;     /* CLR_FILTER_* */
  uint sceneFlags;    /* CLR_SCENE_*: what the host bound for this frame */
  uint visAttributes; /* 1: raster also writes the depth and barycentric planes */
  /* Sample k at the pixel centre + (sampleX[k], sampleY[k]), fixed units, y up (host/pipeline/aa.cpp). */
  int sampleX[CLR_MAX_SAMPLES];
  int sampleY[CLR_MAX_SAMPLES];
  uint visibility;   /* CLR_VISIBILITY_* */
  uint visIndexBits; /* 16, 24 or 32: the visibility buffer's index entries (visIndex below) */
  uint visEntries;   /* S·V, the index entries of all sample planes (the 24-bit entries' high bytes follow) */
  /* 1: setup culls a small triangle covering no pixel centre (setup_covers_a_sample); 1 sample, fixed, no lines. */
  uint cullSampleFree;
  /* > 0: clip-space margin of the cluster test (setup_cluster_place); 0 skips it (DeviceScene::clusterMargin). */
  float clusterMargin;
  /* 1: the scene's triangles lie in the file's order (host layout.h), so
   * fileTri is the identity and not bound: readers take the index itself. */
  uint fileOrder;
  /* Batched clip-input frames (api_diff.cpp): image k's imageTris input triangles draw into rows k·imageRows ..
   * + imageHeight − 1 (imageRows a tile multiple); imageTris 0: one image, imageHeight = height. */
  uint imageTris, imageRows, imageHeight;
} FrameParams;

/* The first row of input triangle tri's image (0 unless batched); offsets stay below CLR_MAX_VIEWPORT (fixed.h). */
#ifdef __OPENCL_VERSION__
CLR_INLINE int clr_image_row(__constant FrameParams* params, uint tri)
{
  return params->imageTris ? (int)(tri / params->imageTris * params->imageRows) : 0;
}
#endif

/* The image pixel (x, y) of screen space (y up, (0, 0) bottom left); image is stored top row first. */
#ifdef __OPENCL_VERSION__
CLR_INLINE __global uint* clr_image_pixel(__constant FrameParams* params, __global uint* image, uint x, uint y)
{
  return &image[(params->height - 1 - y) * params->width + x];
}
#endif

/* TriSetup[scanned setup count], 36 bytes: one clipped, snapped, counter-clockwise screen triangle. Written by
 * setup emit and setup_clip; read by bin_fill_clipped, raster, resolve, lines_from_setup, aov. Source, winding and
 * clip slot live in setupSource; 1 / (2·area) is recomputed (clr_inv_area2), and so is w_clip from the input vertices
 * (record_clip_w, transform.cl; a clipped record's ClipBary slot holds it). Dead-slot records are padding. */
typedef struct TriSetup {
  int x[3];   /* snapped fixed-point screen x, CLR_SUBPIXEL_BITS */
  int y[3];   /* snapped fixed-point screen y */
  float z[3]; /* window depth in [0, 1] (reversed with CLR_DEPTH_REVERSED) */
} TriSetup;

/* 1 / (2·signed area), fixed units⁻²: edge functions to barycentrics. 2·area is exact in 64 bits (fixed.h) and the
 * conversion and division round correctly, so every stage recomputes the same float. */
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
/* Clip coordinate `row` (0 x .. 3 w): row of the column-major mvp times (x, y, z, 1), summed left to right: the one
 * formula of transform.cl's functions and the host's readback of 1/w (Pipeline::readSetup), which agree bit for bit
 * (contraction off on both sides). */
#define CLR_TRANSFORM_ROW(m, row, x, y, z) \
  ((m)[row] * (x) + (m)[4 + (row)] * (y) + (m)[8 + (row)] * (z) + (m)[12 + (row)])
/* clr_inv_area2 of setup record t (a TriSetup, or a record read back with its fields). */
#define CLR_RECORD_INV_AREA2(t) clr_inv_area2((t).x[0], (t).y[0], (t).x[1], (t).y[1], (t).x[2], (t).y[2])
/* Setup record t's snapped bounds as int4 (min x, min y, max x, max y), fixed units; kernels only. */
#define CLR_RECORD_BOUNDS(t)                                                              \
  ((int4)(min((t).x[0], min((t).x[1], (t).x[2])), min((t).y[0], min((t).y[1], (t).y[2])), \
          max((t).x[0], max((t).x[1], (t).x[2])), max((t).y[0], max((t).y[1], (t).y[2]))))

/* ClipBary[CLR_MAX_SUBTRIS per clipped triangle], 56 bytes: w[i][j] = weight of input vertex j in sub-vertex i.
 * Written by setup_clip (clipList entry i owns slots i·CLR_MAX_SUBTRIS + k, unused ones CLR_FLAG_DEAD); read by
 * bin_fill_clipped, resolve, lines_from_setup and aov. */
typedef struct ClipBary {
  float w[3][3];
  float clipW[3]; /* w_clip of each sub-vertex (its record's vertex i) */
  uint triId;     /* the input triangle */
  uint flags;     /* CLR_FLAG_* */
} ClipBary;

/* A setup record's clip slot from its source word, or CLR_NOT_CLIPPED (host and kernels). */
#ifdef __OPENCL_VERSION__
CLR_INLINE uint clr_source_clip_slot(uint source)
#else
inline uint clr_source_clip_slot(uint source)
#endif
{
  return (source & CLR_SOURCE_CLIPPED) ? source & ~CLR_SOURCE_CLIPPED : CLR_NOT_CLIPPED;
}

#ifdef __OPENCL_VERSION__
/* A binned record's input triangle and winding, from its source word (and ClipBary slot when clipped). */
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

/* Material[numMaterials], 32 bytes: base colour = factor × texel when texture >= 0. Host writes; resolve reads. */
typedef struct Material {
  float baseColor[4];
  int texture; /* index into texDescs, or -1 */
  uint pad[3];
} Material;

/* TextureDesc[numTextures], 96 bytes: level l is max(1, w >> l) × max(1, h >> l) RGBA8 texels, rows bottom first,
 * at texels[levelOffset[l]]. Host writes (host/io/texture.cpp); resolve reads. */
typedef struct TextureDesc {
  uint width, height, levels;
  uint wrapS, wrapT; /* CLR_WRAP_* for u and v */
  uint pad[3];
  uint levelOffset[CLR_MAX_MIP_LEVELS];
} TextureDesc;

/* The visibility buffer, one sample per entry, only for tiles with a non-empty bin: tile t owns slot tileSlot[t],
 * a row-major block of CLR_TILE_SIZE² entries. With S samples and V = slots·CLR_TILE_SIZE² (visPlane), sample k of
 * pixel (x, y) at a = vis_address(tileSlot[t], x, y):
 *  visIndex entry k·V + a: the setup index or CLR_NONE; raster writes; resolve, lines_draw, aov read (vis_index_at,
 *           raster.cl). By visIndexBits (Pipeline::visIndexBits: the fewest that hold every record of the frame):
 *           32 uint[S·V]; 16 ushort[S·V], 0xFFFF none; 24 ushort[S·V] low halves, then uchar[S·V] high bytes,
 *           0xFFFFFF none
 *  visAttr  float[3·S·V], only when visAttributes  at (3k + c)·V + a: c = 0 depth (as stored; paint rank bits with
 *           CLR_VISIBILITY_PAINTER), 1 b1, 2 b2; raster writes; without it resolve recomputes b1, b2 (vis_barycentrics)
 * Entries of a block outside the viewport are written but never read. */
#ifdef __OPENCL_VERSION__
CLR_INLINE uint vis_address(uint slot, uint x, uint y)
#else
inline uint vis_address(uint slot, uint x, uint y)
#endif
{
  return slot * (CLR_TILE_SIZE * CLR_TILE_SIZE) + (y % CLR_TILE_SIZE) * CLR_TILE_SIZE + x % CLR_TILE_SIZE;
}

/* One sample as Pipeline::readVis() returns it, 16 bytes. */
typedef struct VisSample {
  uint setupIndex; /* index into TriSetup, or CLR_NONE */
  float depth;     /* window depth of the fragment (see visAttr) */
  float b1;        /* screen-space barycentric of vertex 1 */
  float b2;        /* screen-space barycentric of vertex 2 */
} VisSample;

/* The other buffers of a frame: type[size]  writer -> readers. Optional attributes (Pipeline::bindAttributes) are a
 * 1-element dummy when the frame's mode does not read them.
 *  positions float[3·numVerts], normals float[3·numVerts], uvs float[2·numVerts], colors float[4·numVerts]
 *                                           host -> setup, transform_vertices (positions); resolve (all;
 *                                           positions for 1/w), aov (positions for 1/w)
 *  triMaterial uint[numTris] (with CLR_SCENE_TRI_MATERIALS), materials, texDescs, texels uint[all levels]
 *                                           host -> resolve
 *  indices     uint[3·numTris]              host -> setup, resolve
 *  clipPos     float4[numVerts]             transform_vertices -> painter's sort, tests
 *  triCount    uchar[numTris]               setup count pass (0, 1 or CLR_MAX_SUBTRIS; CPU shape: a skipped
 *                                           cluster's bytes are not written) -> scan
 *  clusterCount uint[clusters]              setup count pass, CPU shape (the sum of the cluster's bytes) -> scan
 *  setupSource uint[numSetup + chunks]      scan, emit, bin_fill_clipped -> setup_clip, raster, resolve, lines, aov
 *  clipList    uint[CLIPPED_TRIS]           count pass (host grows and recounts), setup_clip -> bin_fill_clipped
 *  tileCount   uint[tiles + 1]              count pass, setup_clip; scanned -> emit, bin_fill_clipped, raster, resolve
 *  tileCursor  uint[tiles]                  emit, bin_fill_clipped (atomic cursors)
 *  tileSlot    uint[tiles + 1]              scan_chunks (last = slot count) -> raster, resolve, lines_draw, aov
 *  binEntries  uint[bin total]              emit, bin_fill_clipped -> raster
 *  scanPartials ulong[2·(chunks + 1)]       scan internals (chunks <= 4096)
 *  tileMicro   uint[tiles]                  host zeroes; count pass claims micro slots -> emit, raster (micro.h)
 *  microKey    ulong[micro slots·S·tile²]   emit atom_min (micro.h) -> raster, which resets it to all ones
 *  microRecord uint[numTris]                emit: setup index by paint rank (not fileOrder) -> raster
 *  paintRank   uint[numTris]                host: painter's far-to-near rank, else fileTri -> raster (depth ties)
 *  fileTri     uint[numTris]                host: each input triangle's index in the file (layout.h; 1 unused
 *                                           element when FrameParams.fileOrder) -> resolve, aov
 *  image       uint[width·height]           resolve, then lines_draw -> host
 *  tileBlank   uint[tiles]                  host zeroes (size, background, lines changed) -> resolve (CPU shape: 1
 *                                           = the tile is background since, so an empty tile is not repainted)
 *  lineParams LineParams[1], lineSegs LineSeg[segments], lineTileCount uint[tiles + 1], lineTileCursor uint[tiles],
 *  lineBinEntries uint[total]               lines kernels (below)
 *  aov         float[10·width·height]       aov -> host */

/* Lines (kernels/lines.cl): LineParams.mode and LineParams.method. */
#define CLR_WIREFRAME_OFF 0u     /* no lines */
#define CLR_WIREFRAME_OVERLAY 1u /* lines blended over the shaded image */
#define CLR_WIREFRAME_ONLY 2u    /* lines over the background only */
#define CLR_LINE_AA 0u           /* coverage from the perpendicular distance */
#define CLR_LINE_BRESENHAM 1u    /* integer decision variable, one pixel per step */

/* LineSeg.flags: the segment is not drawn (a clip-made edge, a dead record). */
#define CLR_LINE_SKIP 1u

/* LineSeg[segments], 32 bytes: lines_from_setup (edge e of a record: vertex e to (e + 1) % 3) or host writes;
 * lines_bin_count, lines_bin_fill, lines_draw read. */
typedef struct LineSeg {
  int x[2];   /* fixed-point screen x of the endpoints, CLR_SUBPIXEL_BITS */
  int y[2];   /* fixed-point screen y */
  float z[2]; /* window depth of the endpoints */
  uint triId; /* input triangle it came from (informational) */
  uint flags; /* CLR_LINE_* flags */
} LineSeg;

/* LineParams[1], 32 bytes: host writes (Pipeline::lines); the lines kernels read. */
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

/* AOV buffer float[CLR_AOV_CHANNELS·W·H]: plane c, pixel (i, j) at c·W·H + j·W + i, bottom row first. aov writes;
 * the host reads (Pipeline::readAov). */
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
static_assert(sizeof(FrameParams) == 388, "FrameParams layout must match the kernels");
static_assert(sizeof(TriSetup) == 36, "TriSetup layout must match the kernels");
static_assert(sizeof(ClipBary) == 56, "ClipBary layout must match the kernels");
static_assert(sizeof(VisSample) == 16, "VisSample layout must match the kernels");
static_assert(sizeof(Material) == 32, "Material layout must match the kernels");
static_assert(sizeof(TextureDesc) == 96, "TextureDesc layout must match the kernels");
static_assert(sizeof(LineSeg) == 32, "LineSeg layout must match the kernels");
static_assert(sizeof(LineParams) == 32, "LineParams layout must match the kernels");
#endif

#endif /* CLR_SHARED_H */
