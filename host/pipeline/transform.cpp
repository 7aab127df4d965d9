// transform.cpp — host side of kernels/transform.cl: one work-item per
// vertex writes clipPos = mvp · position. A frame does not run it (setup
// transforms the vertices it reads); the painter's sort and tests do, and
// the clip-position buffer exists only from their first call.
#include "pipeline/pipeline.h"

namespace clr {

void Pipeline::transform()
{
  clipPos_.reserve(params_.numVerts, true);
  TransformArgs args;
  args.positions = positions_.get(), args.params = paramsBuf_.get(), args.clipPos = clipPos_.get();
  setKernelArgs(transformKernel_, args);
  launchLinear(transformKernel_, params_.numVerts, "transform");
}

}  // namespace clr
