// arrays.h — the numpy array types the extension's bindings take, and the one
// shape check (module.cpp, module_diff.cpp): a wrong shape is a ValueError
// naming the argument, before any pointer into the array is used.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <initializer_list>
#include <string>

namespace clraster_py {

namespace py = pybind11;
using FloatArray = py::array_t<float, py::array::c_style>;
using IntArray = py::array_t<int32_t, py::array::c_style>;

// `shape` lists each dimension's size, -1 for any.
inline void expectShape(const char* name, const py::array& a, std::initializer_list<py::ssize_t> shape)
{
  bool ok = a.ndim() == py::ssize_t(shape.size());
  size_t k = 0;
  for (py::ssize_t n : shape) {
    ok = ok && (n < 0 || a.shape(k) == n);
    ++k;
  }
  if (!ok) throw py::value_error(std::string(name) + ": wrong shape");
}

}  // namespace clraster_py
