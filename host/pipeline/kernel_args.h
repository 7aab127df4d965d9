// kernel_args.h — the argument list of every kernel, one struct each, its
// fields named and visited in the order of the kernel's parameters.
//
// setKernelArgs sets a struct's fields as arguments 0, 1, 2, ... in the
// order its visit() names them; kernelArgNames lists those names. A test
// (tests/test_kernel_args.cpp) compares each list with the kernel's own
// parameter names (clGetKernelArgInfo on a program built with
// -cl-kernel-arg-info), so a parameter added, removed or moved in a .cl file
// fails there instead of shifting the arguments after it.
#pragma once

#include "pipeline/cl.h"

#include <string>
#include <vector>

namespace clr {

template <typename Args>
void setKernelArgs(cl::Kernel& kernel, const Args& args)
{
  cl_uint index = 0;
  args.visit([&](const char*, const auto& value) { kernel.setArg(index++, value); });
}

template <typename Args>
std::vector<std::string> kernelArgNames()
{
  std::vector<std::string> names;
  Args{}.visit([&](const char* name, const auto&) { names.emplace_back(name); });
  return names;
}

// transform_vertices (transform.cl).
struct TransformArgs {
  cl::Buffer positions, params, clipPos;
  template <typename V>
  void visit(V&& v) const
  {
    v("positions", positions), v("params", params), v("clipPos", clipPos);
  }
};

// setup_triangles (setup.cl), both passes.
struct SetupTrianglesArgs {
  cl::Buffer params, positions, indices, triCount, counters, clipList;
  cl_uint clipListCapacity = 0;
  cl::Buffer tileCount, setup, tileCursor, binEntries, source;
  cl_uint numSetup = 0, pass = 0;
  cl::Buffer clusterBounds, clusterCount;
  cl_uint microMax = 0, microCap = 0;  // the micro path (kernels/micro.h), 0 = off
  cl::Buffer tileMicro, microKey, microRecord, paintRank;
  template <typename V>
  void visit(V&& v) const
  {
    v("params", params), v("positions", positions), v("indices", indices), v("triCount", triCount);
    v("counters", counters), v("clipList", clipList), v("clipListCapacity", clipListCapacity);
    v("tileCount", tileCount), v("setup", setup), v("tileCursor", tileCursor), v("binEntries", binEntries);
    v("source", source), v("numSetup", numSetup), v("pass", pass), v("clusterBounds", clusterBounds);
    v("clusterCount", clusterCount), v("microMax", microMax), v("microCap", microCap), v("tileMicro", tileMicro);
    v("microKey", microKey), v("microRecord", microRecord), v("paintRank", paintRank);
  }
};

// setup_clip (setup.cl).
struct SetupClipArgs {
  cl::Buffer params, positions, indices, source;
  cl_uint numSetup = 0;
  cl::Buffer clipList, setup, clipBary, counters, tileCount;
  template <typename V>
  void visit(V&& v) const
  {
    v("params", params), v("positions", positions), v("indices", indices), v("source", source);
    v("numSetup", numSetup), v("clipList", clipList), v("setup", setup), v("clipBary", clipBary);
    v("counters", counters), v("tileCount", tileCount);
  }
};

// scan_chunks (scan.cl), every phase.
struct ScanChunksArgs {
  cl::Buffer src, dst;
  cl_uint n = 0, chunk = 0, numChunks = 0;
  cl::Buffer partials, second, byteCounts, counters;
  cl_uint totalAt = 0, nonZeroTotalAt = 0, phase = 0, alsoNonZero = 0, listSources = 0, listEnd = 0;
  template <typename V>
  void visit(V&& v) const
  {
    v("src", src), v("dst", dst), v("n", n), v("chunk", chunk), v("numChunks", numChunks);
    v("partials", partials), v("second", second), v("byteCounts", byteCounts), v("counters", counters);
    v("totalAt", totalAt), v("nonZeroTotalAt", nonZeroTotalAt), v("phase", phase);
    v("alsoNonZero", alsoNonZero), v("listSources", listSources), v("listEnd", listEnd);
  }
};

// bin_fill_clipped (bin.cl).
struct BinFillClippedArgs {
  cl::Buffer params, setup, clipBary, source, clipList;
  cl_uint numClipped = 0;
  cl::Buffer tileOffset, tileCursor, binEntries;
  template <typename V>
  void visit(V&& v) const
  {
    v("params", params), v("setup", setup), v("clipBary", clipBary), v("source", source), v("clipList", clipList);
    v("numClipped", numClipped), v("tileOffset", tileOffset), v("tileCursor", tileCursor);
    v("binEntries", binEntries);
  }
};

// raster and its variants (raster.cl).
struct RasterArgs {
  cl::Buffer params, setup, source, clipBary, tileOffset, binEntries, visIndex, visAttr, paintRank, tileSlot;
  cl_uint visPlane = 0;
  cl::Buffer tileMicro, microKey, microRecord;  // the micro path (kernels/micro.h)
  template <typename V>
  void visit(V&& v) const
  {
    v("params", params), v("setup", setup), v("source", source), v("clipBary", clipBary);
    v("tileOffset", tileOffset), v("binEntries", binEntries), v("visIndex", visIndex), v("visAttr", visAttr);
    v("paintRank", paintRank), v("tileSlot", tileSlot), v("visPlane", visPlane), v("tileMicro", tileMicro);
    v("microKey", microKey), v("microRecord", microRecord);
  }
};

// resolve and resolve_lambert (resolve.cl, resolve_lambert.cl).
struct ResolveArgs {
  cl::Buffer params, visIndex, visAttr, tileOffset, setup, source, clipBary, indices, positions, normals, uvs, colours,
      triMaterial, materials, texDescs, texels, image, tileSlot;
  cl_uint visPlane = 0, prefetchRows = 0;
  cl::Buffer fileTri, tileBlank;
  template <typename V>
  void visit(V&& v) const
  {
    v("params", params), v("visIndex", visIndex), v("visAttr", visAttr), v("tileOffset", tileOffset);
    v("setup", setup), v("source", source), v("clipBary", clipBary), v("indices", indices);
    v("positions", positions), v("normals", normals), v("uvs", uvs), v("colours", colours);
    v("triMaterial", triMaterial), v("materials", materials), v("texDescs", texDescs), v("texels", texels);
    v("image", image), v("tileSlot", tileSlot), v("visPlane", visPlane), v("prefetchRows", prefetchRows);
    v("fileTri", fileTri), v("tileBlank", tileBlank);
  }
};

// lines_from_setup (lines.cl).
struct LinesFromSetupArgs {
  cl::Buffer setup;
  cl_uint numSetup = 0;
  cl::Buffer source, clipBary, segs;
  template <typename V>
  void visit(V&& v) const
  {
    v("setup", setup), v("numSetup", numSetup), v("source", source), v("clipBary", clipBary), v("segs", segs);
  }
};

// lines_bin_count (lines.cl).
struct LinesBinCountArgs {
  cl::Buffer params, lp, segs, tileCount;
  template <typename V>
  void visit(V&& v) const
  {
    v("params", params), v("lp", lp), v("segs", segs), v("tileCount", tileCount);
  }
};

// lines_bin_fill (lines.cl).
struct LinesBinFillArgs {
  cl::Buffer params, lp, segs, tileOffset, tileCursor, binEntries;
  template <typename V>
  void visit(V&& v) const
  {
    v("params", params), v("lp", lp), v("segs", segs), v("tileOffset", tileOffset), v("tileCursor", tileCursor);
    v("binEntries", binEntries);
  }
};

// lines_draw (lines.cl).
struct LinesDrawArgs {
  cl::Buffer params, lp, segs, lineTileOffset, lineBinEntries, triTileOffset, visIndex, visAttr, setup, image, tileSlot;
  cl_uint visPlane = 0;
  template <typename V>
  void visit(V&& v) const
  {
    v("params", params), v("lp", lp), v("segs", segs), v("lineTileOffset", lineTileOffset);
    v("lineBinEntries", lineBinEntries), v("triTileOffset", triTileOffset), v("visIndex", visIndex);
    v("visAttr", visAttr), v("setup", setup), v("image", image), v("tileSlot", tileSlot), v("visPlane", visPlane);
  }
};

// aov (aov.cl).
struct AovArgs {
  cl::Buffer params, visIndex, visAttr, tileOffset, source, clipBary, indices, positions, normals, out, tileSlot;
  cl_uint visPlane = 0;
  cl::Buffer fileTri;
  template <typename V>
  void visit(V&& v) const
  {
    v("params", params), v("visIndex", visIndex), v("visAttr", visAttr), v("tileOffset", tileOffset);
    v("source", source), v("clipBary", clipBary), v("indices", indices), v("positions", positions);
    v("normals", normals), v("out", out), v("tileSlot", tileSlot), v("visPlane", visPlane), v("fileTri", fileTri);
  }
};

// rast_outputs (rast_outputs.cl).
struct RastOutputsArgs {
  cl::Buffer params, visIndex, visAttr, tileOffset, source, clipBary, indices, positions, tileSlot;
  cl_uint visPlane = 0;
  cl::Buffer rast, ids, db;
  cl_uint outputs = 0;  // CLR_RAST_OUT_* bits
  template <typename V>
  void visit(V&& v) const
  {
    v("params", params), v("visIndex", visIndex), v("visAttr", visAttr), v("tileOffset", tileOffset);
    v("source", source), v("clipBary", clipBary), v("indices", indices), v("positions", positions);
    v("tileSlot", tileSlot), v("visPlane", visPlane), v("rast", rast), v("ids", ids), v("db", db);
    v("outputs", outputs);
  }
};

// peel_layer (diff_peel.cl).
struct PeelArgs {
  cl::Buffer params, setup, tileOffset, binEntries, source, clipBary, indices, positions, floorDepth, rast, db;
  cl_uint withDb = 0;
  cl::Buffer nextFloor;
  template <typename V>
  void visit(V&& v) const
  {
    v("params", params), v("setup", setup), v("tileOffset", tileOffset), v("binEntries", binEntries);
    v("source", source), v("clipBary", clipBary), v("indices", indices), v("positions", positions);
    v("floorDepth", floorDepth), v("rast", rast), v("db", db), v("withDb", withDb), v("nextFloor", nextFloor);
  }
};

// rasterize_grad (diff.cl).
struct RasterizeGradArgs {
  cl::Buffer pos;
  cl_uint posStride = 0;  // floats per image of pos; 0: shared
  cl::Buffer tri;
  cl_uint numTriangles = 0, numVertices = 0;
  cl::Buffer rast, gradRast, gradDb;
  cl_uint withDb = 0, width = 0, height = 0, numPixels = 0;
  cl::Buffer gradPos;
  template <typename V>
  void visit(V&& v) const
  {
    v("pos", pos), v("posStride", posStride), v("tri", tri), v("numTriangles", numTriangles);
    v("numVertices", numVertices), v("rast", rast), v("gradRast", gradRast), v("gradDb", gradDb);
    v("withDb", withDb), v("width", width), v("height", height), v("numPixels", numPixels), v("gradPos", gradPos);
  }
};

// interpolate_grad (diff.cl).
struct InterpolateGradArgs {
  cl::Buffer attr;
  cl_uint attrStride = 0, numVertices = 0, numAttrs = 0;  // attrStride: floats per image of attr; 0: shared
  cl::Buffer rast, tri;
  cl_uint numTriangles = 0;
  cl::Buffer gradOut, db, gradDa, diff;
  cl_uint numDiff = 0, pixelsPerImage = 0, numPixels = 0;
  cl::Buffer gradAttr, gradRast, gradDb;
  template <typename V>
  void visit(V&& v) const
  {
    v("attr", attr), v("attrStride", attrStride), v("numVertices", numVertices), v("numAttrs", numAttrs);
    v("rast", rast), v("tri", tri), v("numTriangles", numTriangles), v("gradOut", gradOut), v("db", db);
    v("gradDa", gradDa), v("diff", diff), v("numDiff", numDiff), v("pixelsPerImage", pixelsPerImage);
    v("numPixels", numPixels), v("gradAttr", gradAttr), v("gradRast", gradRast), v("gradDb", gradDb);
  }
};

// TexParams of diff_texture.cl, passed by value.
struct TexParams {
  cl_uint filter = 0, boundary = 0, channels = 0, texImages = 0;
  cl_uint width = 0, height = 0, numPixels = 0, maxLevel = 0;  // output image size, B·H·W, deepest level used
  cl_uint hasUvDa = 0, hasBias = 0, pad0 = 0, pad1 = 0;
};

static_assert(sizeof(TexParams) == 48, "TexParams must match diff_texture.cl");

// texture_fwd (diff_texture.cl).
struct TextureFwdArgs {
  TexParams params;
  cl::Buffer tex, levelInfo, uv, uvDa, bias, out;
  template <typename V>
  void visit(V&& v) const
  {
    v("params", params), v("tex", tex), v("levelInfo", levelInfo), v("uv", uv), v("uvDa", uvDa), v("bias", bias);
    v("out", out);
  }
};

// texture_grad (diff_texture.cl).
struct TextureGradArgs {
  TexParams params;
  cl::Buffer tex, levelInfo, uv, uvDa, bias, gradOut, gradTex, gradUv, gradUvDa, gradBias;
  template <typename V>
  void visit(V&& v) const
  {
    v("params", params), v("tex", tex), v("levelInfo", levelInfo), v("uv", uv), v("uvDa", uvDa), v("bias", bias);
    v("gradOut", gradOut), v("gradTex", gradTex), v("gradUv", gradUv), v("gradUvDa", gradUvDa);
    v("gradBias", gradBias);
  }
};

// mip_build (diff_texture.cl): level `level` of the pyramid from level - 1.
struct MipBuildArgs {
  cl::Buffer tex, levelInfo;
  cl_uint level = 0, channels = 0, texImages = 0;
  template <typename V>
  void visit(V&& v) const
  {
    v("tex", tex), v("levelInfo", levelInfo), v("level", level), v("channels", channels), v("texImages", texImages);
  }
};

// mip_grad_down (diff_texture.cl): level `level`'s gradient into level - 1.
struct MipGradDownArgs {
  cl::Buffer grad, levelInfo;
  cl_uint level = 0, channels = 0, texImages = 0;
  template <typename V>
  void visit(V&& v) const
  {
    v("grad", grad), v("levelInfo", levelInfo), v("level", level), v("channels", channels), v("texImages", texImages);
  }
};

// antialias_fwd and antialias_grad (diff_antialias.cl): the shared head; the rest by kernel.
struct AntialiasArgs {
  cl::Buffer color, rast, pos;
  cl_uint posStride = 0;  // floats per image of pos; 0: shared
  cl::Buffer tri, opp;
  cl_uint numTriangles = 0, width = 0, height = 0, numPixels = 0, channels = 0;
  template <typename V>
  void visit(V&& v) const
  {
    v("color", color), v("rast", rast), v("pos", pos), v("posStride", posStride), v("tri", tri), v("opp", opp);
    v("numTriangles", numTriangles), v("width", width), v("height", height), v("numPixels", numPixels);
    v("channels", channels);
  }
};
struct AntialiasFwdArgs {
  AntialiasArgs head;
  cl::Buffer out;  // a copy of color on entry
  template <typename V>
  void visit(V&& v) const
  {
    head.visit(v), v("out", out);
  }
};
struct AntialiasGradArgs {
  AntialiasArgs head;
  cl::Buffer gradOut;
  cl_float posBoost = 1.0f;
  cl::Buffer gradColor, gradPos;  // gradColor a copy of gradOut on entry; gradPos zeroed
  template <typename V>
  void visit(V&& v) const
  {
    head.visit(v), v("gradOut", gradOut), v("posBoost", posBoost), v("gradColor", gradColor), v("gradPos", gradPos);
  }
};

}  // namespace clr
