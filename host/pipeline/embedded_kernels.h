// embedded_kernels.h — the OpenCL sources compiled into the binary by
// cmake/embed_kernels.cmake, in the order they are handed to the compiler,
// and programSource(), which joins them: the prelude headers (fixed.h,
// shared.h, lanes.h) first, then each .cl file with each of its #include lines
// replaced by the embedded header it names, recursively. The
// included headers carry include guards, so each stage's file names what
// it uses and the order of the .cl files does not matter to the compiler.
#pragma once

#include <cstddef>
#include <string>

namespace clr {

struct EmbeddedKernel {
  const char* name;
  const char* text;
};

extern const EmbeddedKernel kEmbeddedKernels[];
extern const size_t kEmbeddedKernelCount;

// The program's source text; a clr::Error names a header no embedded file holds.
std::string programSource();

}  // namespace clr
