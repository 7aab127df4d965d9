// module_diff.cpp — the backward passes (include/clraster/diff.hpp) as
// functions of clraster._clraster, for python/clraster/torch.py, which
// checks its arguments first. These bindings check again what memory safety
// needs (shapes and contiguity: a wrong array is a ValueError); the GIL is
// released around the device work.
#include <clraster/diff.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

namespace py = pybind11;

namespace {

using FloatArray = py::array_t<float, py::array::c_style>;
using IntArray = py::array_t<int32_t, py::array::c_style>;

void expectDims(const char* name, const py::array& a, std::initializer_list<py::ssize_t> shape)
{
  bool ok = a.ndim() == py::ssize_t(shape.size());
  size_t k = 0;
  for (py::ssize_t n : shape) {
    ok = ok && (n < 0 || a.shape(k) == n);
    ++k;
  }
  if (!ok) throw py::value_error(std::string(name) + ": wrong shape");
}

clraster::ImageBatch batchOf(const FloatArray& rast)
{
  expectDims("rast", rast, {-1, -1, -1, 4});
  return {size_t(rast.shape(0)), uint32_t(rast.shape(2)), uint32_t(rast.shape(1))};
}

// pos [P, V, 4], tri [T, 3], rast and grad_rast [B, H, W, 4], grad_db the
// same or None: grad_pos [P, V, 4].
FloatArray rasterizeGrad(clraster::Context& ctx, const FloatArray& pos, const IntArray& tri, const FloatArray& rast,
                         const FloatArray& gradRast, std::optional<FloatArray> gradDb)
{
  expectDims("pos", pos, {-1, -1, 4});
  expectDims("tri", tri, {-1, 3});
  const clraster::ImageBatch b = batchOf(rast);
  expectDims("grad_rast", gradRast, {rast.shape(0), rast.shape(1), rast.shape(2), 4});
  if (gradDb) expectDims("grad_db", *gradDb, {rast.shape(0), rast.shape(1), rast.shape(2), 4});
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
  expectDims("attr", attr, {-1, -1, -1});
  expectDims("tri", tri, {-1, 3});
  const clraster::ImageBatch b = batchOf(rast);
  const py::ssize_t n0 = rast.shape(0), n1 = rast.shape(1), n2 = rast.shape(2), c = attr.shape(2);
  expectDims("grad_out", gradOut, {n0, n1, n2, c});
  if (!diff.empty()) {
    if (!db || !gradDa) throw py::value_error("rast_db: needed with diff_attrs");
    expectDims("rast_db", *db, {n0, n1, n2, 4});
    expectDims("grad_da", *gradDa, {n0, n1, n2, py::ssize_t(2 * diff.size())});
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

}  // namespace

void bindDiff(py::module_& m)
{
  m.def("rasterize_grad", &rasterizeGrad, py::arg("ctx"), py::arg("pos").noconvert(), py::arg("tri").noconvert(),
        py::arg("rast").noconvert(), py::arg("grad_rast").noconvert(), py::arg("grad_db").noconvert() = py::none());
  m.def("interpolate_grad", &interpolateGrad, py::arg("ctx"), py::arg("attr").noconvert(), py::arg("rast").noconvert(),
        py::arg("tri").noconvert(), py::arg("grad_out").noconvert(), py::arg("db").noconvert() = py::none(),
        py::arg("diff") = std::vector<int>{}, py::arg("grad_da").noconvert() = py::none());
}
