// embedded_kernels.h — the OpenCL sources compiled into the binary by
// cmake/embed_kernels.cmake, in the order they are handed to the compiler.
#pragma once

#include <cstddef>

namespace clr {

struct EmbeddedKernel {
  const char* name;
  const char* text;
};

extern const EmbeddedKernel kEmbeddedKernels[];
extern const size_t kEmbeddedKernelCount;

}  // namespace clr
