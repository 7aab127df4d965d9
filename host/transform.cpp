// transform.cpp — host side of kernels/transform.cl: one work-item per
// vertex writes clipPos = mvp · position.
#include "pipeline.h"

namespace clr {

void Pipeline::transform()
{
  cl::Event event;
  setArgs(transformKernel_, positions_.get(), paramsBuf_.get(), clipPos_.get());
  cl_.queue.enqueueNDRangeKernel(transformKernel_, cl::NullRange, linear(params_.numVerts), cl::NDRange(64), nullptr,
                                 &event);
  record("transform", event);
}

}  // namespace clr
