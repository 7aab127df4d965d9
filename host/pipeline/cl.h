// cl.h — the one place the OpenCL C++ bindings are configured and included,
// with the names of OpenCL status codes.
//
// Debian 12's <CL/opencl.hpp> needs CL_HPP_MINIMUM_OPENCL_VERSION >= 200 for
// its cl::Program source constructor to compile. Exceptions are on: every
// OpenCL failure becomes a cl::Error that the CLI reports on one line.
#pragma once

#define CL_HPP_ENABLE_EXCEPTIONS
#define CL_HPP_MINIMUM_OPENCL_VERSION 200
#define CL_HPP_TARGET_OPENCL_VERSION 300
#include <CL/opencl.hpp>

#include "base/error.h"

namespace clr {

// Human-readable name of an OpenCL status code.
const char* clErrorName(cl_int code);

}  // namespace clr
