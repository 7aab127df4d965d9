// transform.cpp — host side of kernels/transform.cl: one work-item per
// vertex writes clipPos = mvp · position. A frame does not run it (setup
// transforms the vertices it reads); the painter's sort and tests do, and
// the clip-position buffer exists only from their first call.
#include "pipeline/pipeline.h"

namespace clr {

void Pipeline::transform()
{
  clipPos_.reserve(params_.numVerts, true);
  cl::Event event;
  setArgs(transformKernel_, positions_.get(), paramsBuf_.get(), clipPos_.get());
  cl_.queue.enqueueNDRangeKernel(transformKernel_, cl::NullRange, linear(params_.numVerts), cl::NDRange(64), nullptr,
                                 &event);
  record("transform", event);
}

}  // namespace clr
