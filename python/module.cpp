// module.cpp — the extension clraster._clraster: the C++ API's calls on
// numpy arrays, for python/clraster/__init__.py, which checks shapes, dtypes
// and index ranges first (with ValueErrors naming the argument) and gives
// the nvdiffrast calling conventions. These bindings check again what memory
// safety needs (shapes and contiguity: a wrong array is a ValueError, never
// a read out of bounds); clraster::Error becomes clraster.Error, a
// RuntimeError. The GIL is released around the C++ calls, once the arrays
// are checked; __init__.py makes calls on one Context take turns.
#include <clraster/clraster.hpp>

#include "arrays.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

namespace py = pybind11;

void bindDiff(py::module_& m);  // module_diff.cpp: the backward passes

namespace {

using clraster_py::expectShape;
using clraster_py::FloatArray;
using clraster_py::IntArray;

// rasterize of one image into rast (and db when given): pos [V, 4], tri [T, 3], out [H, W, 4].
void rasterizeInto(clraster::Context& ctx, const FloatArray& pos, const IntArray& tri, FloatArray rast,
                   std::optional<FloatArray> db)
{
  expectShape("pos", pos, {-1, 4});
  expectShape("tri", tri, {-1, 3});
  expectShape("rast", rast, {-1, -1, 4});
  const uint32_t h = uint32_t(rast.shape(0)), w = uint32_t(rast.shape(1));
  if (db) expectShape("rast_db", *db, {h, w, 4});
  const float* posData = pos.data();
  const int32_t* triData = tri.data();
  const size_t numVertices = size_t(pos.shape(0)), numTriangles = size_t(tri.shape(0));
  float *rastData = rast.mutable_data(), *dbData = db ? db->mutable_data() : nullptr;
  py::gil_scoped_release release;  // raw pointers only from here
  clraster::rasterizeInto(ctx, posData, numVertices, triData, numTriangles, w, h, rastData, nullptr, dbData);
}

// interpolate of one image: attr [V, C], rast [H, W, 4], tri [T, 3], out [H, W, C],
// with db [H, W, 4] and out_da [H, W, 2·len(diff)] when diff is not empty.
void interpolateInto(const FloatArray& attr, const FloatArray& rast, const IntArray& tri, FloatArray out,
                     std::optional<FloatArray> db, const std::vector<int>& diff, std::optional<FloatArray> outDa)
{
  expectShape("attr", attr, {-1, -1});
  expectShape("rast", rast, {-1, -1, 4});
  expectShape("tri", tri, {-1, 3});
  const py::ssize_t h = rast.shape(0), w = rast.shape(1), c = attr.shape(1);
  expectShape("out", out, {h, w, c});
  if (!diff.empty()) {
    if (!db || !outDa) throw py::value_error("rast_db: needed for diff_attrs");
    expectShape("rast_db", *db, {h, w, 4});
    expectShape("out_da", *outDa, {h, w, py::ssize_t(2 * diff.size())});
  }
  const float *attrData = attr.data(), *rastData = rast.data(), *dbData = db ? db->data() : nullptr;
  const int32_t* triData = tri.data();
  const size_t numVertices = size_t(attr.shape(0)), numTriangles = size_t(tri.shape(0));
  float *outData = out.mutable_data(), *outDaData = outDa ? outDa->mutable_data() : nullptr;
  py::gil_scoped_release release;  // raw pointers only from here
  clraster::interpolateInto(attrData, numVertices, size_t(c), rastData, size_t(h * w), triData, numTriangles, outData,
                            dbData, diff, outDaData);
}

}  // namespace

PYBIND11_MODULE(_clraster, m)
{
  m.doc() = "clraster's C++ API for the clraster package (use `import clraster`)";
  m.attr("__version__") = std::to_string(CLRASTER_VERSION_MAJOR) + "." + std::to_string(CLRASTER_VERSION_MINOR);
  py::register_exception<clraster::Error>(m, "Error", PyExc_RuntimeError);
  py::class_<clraster::Context>(m, "Context")
      .def(py::init<const std::string&>(), py::arg("device") = "")
      .def_property_readonly("device_name", [](const clraster::Context& c) { return c.device().name; })
      .def_property_readonly("device_type", [](const clraster::Context& c) { return c.device().type; })
      .def_property_readonly("platform", [](const clraster::Context& c) { return c.device().platform; })
      .def_property("memory_limit", &clraster::Context::memoryLimit, &clraster::Context::setMemoryLimit)
      .def("release", &clraster::Context::release);
  // (It builds the kernels on a Context's first call: without the GIL.)
  m.def("check_rasterize_memory", &clraster::checkRasterizeMemory, py::arg("ctx"), py::arg("width"), py::arg("height"),
        py::arg("output_bytes"), py::call_guard<py::gil_scoped_release>());
  m.def("rasterize_into", &rasterizeInto, py::arg("ctx"), py::arg("pos").noconvert(), py::arg("tri").noconvert(),
        py::arg("rast").noconvert(), py::arg("db").noconvert() = py::none());
  m.def("interpolate_into", &interpolateInto, py::arg("attr").noconvert(), py::arg("rast").noconvert(),
        py::arg("tri").noconvert(), py::arg("out").noconvert(), py::arg("db").noconvert() = py::none(),
        py::arg("diff") = std::vector<int>{}, py::arg("out_da").noconvert() = py::none());
  bindDiff(m);
  m.def("devices", [] {
    py::list out;
    for (const clraster::DeviceInfo& d : clraster::listDevices())
      out.append(py::dict(py::arg("index") = d.index, py::arg("name") = d.name, py::arg("platform") = d.platform,
                          py::arg("type") = d.type));
    return out;
  });
}
