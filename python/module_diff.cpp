// module_diff.cpp — the backward passes (include/clraster/diff.hpp) as
// functions of clraster._clraster, for python/clraster/torch.py, which
// checks its arguments first. These bindings check again what memory safety
// needs (shapes and contiguity: a wrong array is a ValueError); the GIL is
// released around the device work.
#include <clraster/diff.hpp>

#include "arrays.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <string>

namespace py = pybind11;

namespace {

using clraster_py::expectShape;
using clraster_py::FloatArray;
using clraster_py::IntArray;

clraster::ImageBatch batchOf(const FloatArray& rast)
{
  expectShape("rast", rast, {-1, -1, -1, 4});
  return {size_t(rast.shape(0)), uint32_t(rast.shape(2)), uint32_t(rast.shape(1))};
}

// pos [P, V, 4], tri [T, 3], rast and grad_rast [B, H, W, 4], grad_db the
// same or None: grad_pos [P, V, 4].
FloatArray rasterizeGrad(clraster::Context& ctx, const FloatArray& pos, const IntArray& tri, const FloatArray& rast,
                         const FloatArray& gradRast, std::optional<FloatArray> gradDb)
{
  expectShape("pos", pos, {-1, -1, 4});
  expectShape("tri", tri, {-1, 3});
  const clraster::ImageBatch b = batchOf(rast);
  expectShape("grad_rast", gradRast, {rast.shape(0), rast.shape(1), rast.shape(2), 4});
  if (gradDb) expectShape("grad_db", *gradDb, {rast.shape(0), rast.shape(1), rast.shape(2), 4});
  FloatArray out({pos.shape(0), pos.shape(1), py::ssize_t(4)});
  const float *p = pos.data(), *r = rast.data(), *gr = gradRast.data(), *gd = gradDb ? gradDb->data() : nullptr;
  const int32_t* t = tri.data();
  float* o = out.mutable_data();
  const size_t v = size_t(pos.shape(1)), images = size_t(pos.shape(0)), n = size_t(tri.shape(0));
  {
    py::gil_scoped_release release;
    clraster::rasterizeGrad(ctx, p, v, images, t, n, b, r, gr, gd, o);
  }
  return out;
}

// attr [A, V, C], rast [B, H, W, 4], tri [T, 3], grad_out [B, H, W, C],
// with diff: db [B, H, W, 4] and grad_da [B, H, W, 2·len(diff)]:
// (grad_attr [A, V, C], grad_rast [B, H, W, 4], grad_db [B, H, W, 4 or 0]).
py::tuple interpolateGrad(clraster::Context& ctx, const FloatArray& attr, const FloatArray& rast, const IntArray& tri,
                          const FloatArray& gradOut, std::optional<FloatArray> db, const std::vector<int>& diff,
                          std::optional<FloatArray> gradDa)
{
  expectShape("attr", attr, {-1, -1, -1});
  expectShape("tri", tri, {-1, 3});
  const clraster::ImageBatch b = batchOf(rast);
  const py::ssize_t n0 = rast.shape(0), n1 = rast.shape(1), n2 = rast.shape(2), c = attr.shape(2);
  expectShape("grad_out", gradOut, {n0, n1, n2, c});
  if (!diff.empty()) {
    if (!db || !gradDa) throw py::value_error("rast_db: needed with diff_attrs");
    expectShape("rast_db", *db, {n0, n1, n2, 4});
    expectShape("grad_da", *gradDa, {n0, n1, n2, py::ssize_t(2 * diff.size())});
  }
  FloatArray gradAttr({attr.shape(0), attr.shape(1), c});
  FloatArray gradRast({n0, n1, n2, py::ssize_t(4)});
  FloatArray gradDb({n0, n1, n2, py::ssize_t(diff.empty() ? 0 : 4)});
  const float *a = attr.data(), *r = rast.data(), *go = gradOut.data();
  const float *d = !diff.empty() ? db->data() : nullptr, *gda = !diff.empty() ? gradDa->data() : nullptr;
  const int32_t* t = tri.data();
  float *ga = gradAttr.mutable_data(), *gr = gradRast.mutable_data(), *gd = gradDb.mutable_data();
  const size_t images = size_t(attr.shape(0)), v = size_t(attr.shape(1)), n = size_t(tri.shape(0));
  {
    py::gil_scoped_release release;
    clraster::interpolateGrad(ctx, a, v, size_t(c), images, r, b, t, n, go, d, diff, gda, ga, gr, gd);
  }
  return py::make_tuple(gradAttr, gradRast, gradDb);
}

// tex [T, H, W, C]; uv [B, h, w, 2]; uv_da [B, h, w, 4] and bias [B, h, w]
// or None: the TextureSpec of a call.
clraster::TextureSpec textureSpec(const FloatArray& tex, const FloatArray& uv, bool hasUvDa, bool hasBias, int filter,
                                  int boundary, int maxMipLevel)
{
  expectShape("tex", tex, {-1, -1, -1, -1});
  expectShape("uv", uv, {-1, -1, -1, 2});
  if (filter < 0 || filter > 3) throw py::value_error("filter_mode: unknown");
  if (boundary < 0 || boundary > 2) throw py::value_error("boundary_mode: unknown");
  clraster::TextureSpec s;
  s.batch = {size_t(uv.shape(0)), uint32_t(uv.shape(2)), uint32_t(uv.shape(1))};
  s.texImages = size_t(tex.shape(0));
  s.texHeight = uint32_t(tex.shape(1));
  s.texWidth = uint32_t(tex.shape(2));
  s.channels = uint32_t(tex.shape(3));
  s.filter = clraster::TextureFilter(filter);
  s.boundary = clraster::TextureBoundary(boundary);
  s.maxMipLevel = maxMipLevel;
  s.hasUvDa = hasUvDa;
  s.hasBias = hasBias;
  return s;
}

void checkPixels(const FloatArray& uv, const std::optional<FloatArray>& uvDa, const std::optional<FloatArray>& bias)
{
  if (uvDa) expectShape("uv_da", *uvDa, {uv.shape(0), uv.shape(1), uv.shape(2), 4});
  if (bias) expectShape("mip_level_bias", *bias, {uv.shape(0), uv.shape(1), uv.shape(2)});
}

void checkMips(const clraster::TextureSpec& s, const std::optional<FloatArray>& mips)
{
  if (mips && size_t(mips->size()) != clraster::textureMipFloats(s))
    throw py::value_error("mip: built for another texture or max_mip_level");
}

// The mip levels 1.. of tex, flat (textureMipFloats floats).
FloatArray textureMips(clraster::Context& ctx, const FloatArray& tex, int maxMipLevel)
{
  expectShape("tex", tex, {-1, -1, -1, -1});
  FloatArray uv(std::vector<py::ssize_t>{tex.shape(0), 1, 1, 2});
  const clraster::TextureSpec s = textureSpec(tex, uv, true, false, 3, 0, maxMipLevel);
  FloatArray mips(py::ssize_t(clraster::textureMipFloats(s)));
  const float* t = tex.data();
  float* m = mips.mutable_data();
  {
    py::gil_scoped_release release;
    clraster::textureMips(ctx, s, t, m);
  }
  return mips;
}

FloatArray textureForward(clraster::Context& ctx, const FloatArray& tex, std::optional<FloatArray> mips,
                          const FloatArray& uv, std::optional<FloatArray> uvDa, std::optional<FloatArray> bias,
                          int filter, int boundary, int maxMipLevel)
{
  const clraster::TextureSpec s = textureSpec(tex, uv, bool(uvDa), bool(bias), filter, boundary, maxMipLevel);
  checkPixels(uv, uvDa, bias);
  checkMips(s, mips);
  FloatArray out({uv.shape(0), uv.shape(1), uv.shape(2), tex.shape(3)});
  const float *t = tex.data(), *m = mips ? mips->data() : nullptr, *u = uv.data();
  const float *d = uvDa ? uvDa->data() : nullptr, *b = bias ? bias->data() : nullptr;
  float* o = out.mutable_data();
  {
    py::gil_scoped_release release;
    clraster::texture(ctx, s, t, m, u, d, b, o);
  }
  return out;
}

// (grad_tex, grad_uv, grad_uv_da or None, grad_bias or None).
py::tuple textureGrad(clraster::Context& ctx, const FloatArray& tex, std::optional<FloatArray> mips,
                      const FloatArray& uv, std::optional<FloatArray> uvDa, std::optional<FloatArray> bias,
                      const FloatArray& gradOut, int filter, int boundary, int maxMipLevel)
{
  const clraster::TextureSpec s = textureSpec(tex, uv, bool(uvDa), bool(bias), filter, boundary, maxMipLevel);
  checkPixels(uv, uvDa, bias);
  checkMips(s, mips);
  expectShape("grad_out", gradOut, {uv.shape(0), uv.shape(1), uv.shape(2), tex.shape(3)});
  FloatArray gradTex({tex.shape(0), tex.shape(1), tex.shape(2), tex.shape(3)});
  FloatArray gradUv({uv.shape(0), uv.shape(1), uv.shape(2), py::ssize_t(2)});
  FloatArray gradUvDa({uv.shape(0), uv.shape(1), uv.shape(2), py::ssize_t(uvDa ? 4 : 0)});
  FloatArray gradBias({uv.shape(0), uv.shape(1), bias ? uv.shape(2) : py::ssize_t(0)});
  const float *t = tex.data(), *m = mips ? mips->data() : nullptr, *u = uv.data(), *g = gradOut.data();
  const float *d = uvDa ? uvDa->data() : nullptr, *b = bias ? bias->data() : nullptr;
  float *gt = gradTex.mutable_data(), *gu = gradUv.mutable_data();
  float *gd = uvDa ? gradUvDa.mutable_data() : nullptr, *gb = bias ? gradBias.mutable_data() : nullptr;
  {
    py::gil_scoped_release release;
    std::fill(gd, gd + (gd ? gradUvDa.size() : 0), 0.0f);
    std::fill(gb, gb + (gb ? gradBias.size() : 0), 0.0f);
    clraster::textureGrad(ctx, s, t, m, u, d, b, g, gt, gu, gd, gb);
  }
  return py::make_tuple(gradTex, gradUv, uvDa ? py::object(gradUvDa) : py::object(py::none()),
                        bias ? py::object(gradBias) : py::object(py::none()));
}

// color [B, H, W, C], rast [B, H, W, 4], pos [P, V, 4], tri and opp [T, 3].
void checkAntialias(const FloatArray& color, const FloatArray& rast, const FloatArray& pos, const IntArray& tri,
                    const IntArray& opp)
{
  const clraster::ImageBatch b = batchOf(rast);
  expectShape("color", color, {py::ssize_t(b.images), b.height, b.width, -1});
  expectShape("pos", pos, {-1, -1, 4});
  expectShape("tri", tri, {-1, 3});
  expectShape("topology_hash", opp, {tri.shape(0), 3});
}

FloatArray antialiasForward(clraster::Context& ctx, const FloatArray& color, const FloatArray& rast,
                            const FloatArray& pos, const IntArray& tri, const IntArray& opp)
{
  checkAntialias(color, rast, pos, tri, opp);
  const clraster::ImageBatch b = batchOf(rast);
  FloatArray out({color.shape(0), color.shape(1), color.shape(2), color.shape(3)});
  const float *c = color.data(), *r = rast.data(), *p = pos.data();
  const int32_t *t = tri.data(), *o = opp.data();
  float* d = out.mutable_data();
  const uint32_t channels = uint32_t(color.shape(3));
  const size_t v = size_t(pos.shape(1)), images = size_t(pos.shape(0)), n = size_t(tri.shape(0));
  {
    py::gil_scoped_release release;
    clraster::antialias(ctx, c, channels, r, b, p, v, images, t, o, n, d);
  }
  return out;
}

py::tuple antialiasGrad(clraster::Context& ctx, const FloatArray& color, const FloatArray& rast, const FloatArray& pos,
                        const IntArray& tri, const IntArray& opp, const FloatArray& gradOut, float posBoost)
{
  checkAntialias(color, rast, pos, tri, opp);
  expectShape("grad_out", gradOut, {color.shape(0), color.shape(1), color.shape(2), color.shape(3)});
  const clraster::ImageBatch b = batchOf(rast);
  FloatArray gradColor({color.shape(0), color.shape(1), color.shape(2), color.shape(3)});
  FloatArray gradPos({pos.shape(0), pos.shape(1), py::ssize_t(4)});
  const float *c = color.data(), *r = rast.data(), *p = pos.data(), *g = gradOut.data();
  const int32_t *t = tri.data(), *o = opp.data();
  float *gc = gradColor.mutable_data(), *gp = gradPos.mutable_data();
  const uint32_t channels = uint32_t(color.shape(3));
  const size_t v = size_t(pos.shape(1)), images = size_t(pos.shape(0)), n = size_t(tri.shape(0));
  {
    py::gil_scoped_release release;
    clraster::antialiasGrad(ctx, c, channels, r, b, p, v, images, t, o, n, g, posBoost, gc, gp);
  }
  return py::make_tuple(gradColor, gradPos);
}

IntArray antialiasTopology(const IntArray& tri, size_t numVertices)
{
  expectShape("tri", tri, {-1, 3});
  std::vector<int32_t> opp;
  const int32_t* t = tri.data();
  const size_t n = size_t(tri.shape(0));
  {
    py::gil_scoped_release release;
    opp = clraster::antialiasTopology(t, n, numVertices);
  }
  IntArray out({tri.shape(0), py::ssize_t(3)});
  std::copy(opp.begin(), opp.end(), out.mutable_data());
  return out;
}

// Instanced (ranges None, pos [P, V, 4]) or range mode (pos [1, V, 4], ranges
// [N, 2]) into rast [B, H, W, 4] and db (the same, or None).
void rasterizeBatch(clraster::Context& ctx, const FloatArray& pos, const IntArray& tri, std::optional<IntArray> ranges,
                    FloatArray rast, std::optional<FloatArray> db)
{
  expectShape("pos", pos, {-1, -1, 4});
  expectShape("tri", tri, {-1, 3});
  expectShape("rast", rast, {ranges ? -1 : pos.shape(0), -1, -1, 4});
  if (ranges) expectShape("ranges", *ranges, {rast.shape(0), 2});
  if (db) expectShape("rast_db", *db, {rast.shape(0), rast.shape(1), rast.shape(2), 4});
  const float* p = pos.data();
  const int32_t *t = tri.data(), *r = ranges ? ranges->data() : nullptr;
  float *out = rast.mutable_data(), *d = db ? db->mutable_data() : nullptr;
  const size_t v = size_t(pos.shape(1)), images = size_t(pos.shape(0)), n = size_t(tri.shape(0));
  const size_t numRanges = ranges ? size_t(ranges->shape(0)) : 0;
  const uint32_t w = uint32_t(rast.shape(2)), h = uint32_t(rast.shape(1));
  py::gil_scoped_release release;  // raw pointers only from here
  clraster::rasterizeBatch(ctx, p, v, images, t, n, r, numRanges, w, h, out, d);
}

// One peeling layer of a batch, rasterize_batch's arguments and floor
// [B, H, W]: (rast [B, H, W, 4], db [B, H, W, 4] or [B, H, W, 0], next
// floor [B, H, W]).
py::tuple rasterizePeel(clraster::Context& ctx, const FloatArray& pos, const IntArray& tri,
                        std::optional<IntArray> ranges, const FloatArray& floor, bool withDb)
{
  expectShape("pos", pos, {-1, -1, 4});
  expectShape("tri", tri, {-1, 3});
  expectShape("floor", floor, {ranges ? -1 : pos.shape(0), -1, -1});
  if (ranges) expectShape("ranges", *ranges, {floor.shape(0), 2});
  const py::ssize_t b = floor.shape(0), h = floor.shape(1), w = floor.shape(2);
  FloatArray rast({b, h, w, py::ssize_t(4)}), db({b, h, w, py::ssize_t(withDb ? 4 : 0)}), next({b, h, w});
  const float *p = pos.data(), *f = floor.data();
  const int32_t *t = tri.data(), *r = ranges ? ranges->data() : nullptr;
  float *out = rast.mutable_data(), *d = withDb ? db.mutable_data() : nullptr, *nx = next.mutable_data();
  const size_t v = size_t(pos.shape(1)), images = size_t(pos.shape(0)), n = size_t(tri.shape(0));
  const size_t numRanges = ranges ? size_t(ranges->shape(0)) : 0;
  {
    py::gil_scoped_release release;
    clraster::rasterizePeel(ctx, p, v, images, t, n, r, numRanges, uint32_t(w), uint32_t(h), f, out, d, nx);
  }
  return py::make_tuple(rast, db, next);
}

}  // namespace

void bindDiff(py::module_& m)
{
  m.def("rasterize_grad", &rasterizeGrad, py::arg("ctx"), py::arg("pos").noconvert(), py::arg("tri").noconvert(),
        py::arg("rast").noconvert(), py::arg("grad_rast").noconvert(), py::arg("grad_db").noconvert() = py::none());
  m.def("interpolate_grad", &interpolateGrad, py::arg("ctx"), py::arg("attr").noconvert(), py::arg("rast").noconvert(),
        py::arg("tri").noconvert(), py::arg("grad_out").noconvert(), py::arg("db").noconvert() = py::none(),
        py::arg("diff") = std::vector<int>{}, py::arg("grad_da").noconvert() = py::none());
  m.def("texture_mips", &textureMips, py::arg("ctx"), py::arg("tex").noconvert(), py::arg("max_mip_level"));
  m.def("texture_fwd", &textureForward, py::arg("ctx"), py::arg("tex").noconvert(), py::arg("mips").noconvert(),
        py::arg("uv").noconvert(), py::arg("uv_da").noconvert(), py::arg("bias").noconvert(), py::arg("filter"),
        py::arg("boundary"), py::arg("max_mip_level"));
  m.def("texture_grad", &textureGrad, py::arg("ctx"), py::arg("tex").noconvert(), py::arg("mips").noconvert(),
        py::arg("uv").noconvert(), py::arg("uv_da").noconvert(), py::arg("bias").noconvert(),
        py::arg("grad_out").noconvert(), py::arg("filter"), py::arg("boundary"), py::arg("max_mip_level"));
  m.def("antialias_fwd", &antialiasForward, py::arg("ctx"), py::arg("color").noconvert(), py::arg("rast").noconvert(),
        py::arg("pos").noconvert(), py::arg("tri").noconvert(), py::arg("opp").noconvert());
  m.def("antialias_grad", &antialiasGrad, py::arg("ctx"), py::arg("color").noconvert(), py::arg("rast").noconvert(),
        py::arg("pos").noconvert(), py::arg("tri").noconvert(), py::arg("opp").noconvert(),
        py::arg("grad_out").noconvert(), py::arg("pos_gradient_boost"));
  m.def("antialias_topology", &antialiasTopology, py::arg("tri").noconvert(), py::arg("num_vertices"));
  m.def("rasterize_batch", &rasterizeBatch, py::arg("ctx"), py::arg("pos").noconvert(), py::arg("tri").noconvert(),
        py::arg("ranges").noconvert(), py::arg("rast").noconvert(), py::arg("db").noconvert());
  m.def("rasterize_peel", &rasterizePeel, py::arg("ctx"), py::arg("pos").noconvert(), py::arg("tri").noconvert(),
        py::arg("ranges").noconvert(), py::arg("floor").noconvert(), py::arg("grad_db"));
}
