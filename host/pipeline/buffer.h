// buffer.h — typed device buffers that grow to what the scene needs.
//
// DeviceBuffer<T> owns a cl::Buffer of `capacity` elements of T. reserve(n)
// keeps the buffer when it is large enough and otherwise reallocates it: to
// n the first time, then to n plus 1/8 slack (so a moving camera does not
// reallocate every frame). A request larger than the device's maximum single
// allocation, or one that would take the buffers past the device's global
// memory or the caller's limit (DeviceMemory::limitBytes), is a clr::Error
// naming the buffer and the sizes, never a crash. On a device whose memory
// is the host's (a CPU device) the host's headroom is checked too
// (base/memory.h), and each new buffer is touched at once, so the driver
// allocates it while the check still holds (PoCL aborts, rather than
// failing, when it cannot allocate a buffer later). The shared byte counter
// is what --stats reports as device_bytes.
#pragma once

#include "base/memory.h"
#include "pipeline/cl.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace clr {

struct DeviceMemory {
  cl::Context context;
  cl::CommandQueue queue;
  size_t maxAllocBytes = 0;
  size_t bytesAllocated = 0;             // sum of live buffer capacities
  uint64_t globalMemBytes = UINT64_MAX;  // the device's global memory
  uint64_t limitBytes = UINT64_MAX;      // the caller's limit on all buffers (Context::setMemoryLimit)
  bool hostBacked = false;               // device memory is host memory (a CPU device)
};

struct ClContext;
// The account of a context's buffers: its device's limits, none of the caller's (device.cpp).
DeviceMemory deviceMemoryOf(const ClContext& cl);

template <typename T>
class DeviceBuffer {
 public:
  DeviceBuffer(DeviceMemory& memory, const char* name) : memory_(&memory), name_(name) {}
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  ~DeviceBuffer() { memory_->bytesAllocated -= capacity_ * sizeof(T); }

  // Ensures room for n elements (at least one, so kernels always get a
  // buffer). A buffer's first allocation takes what the frame needs, so a
  // still camera's memory is what its scene uses; a buffer whose size
  // changes from frame to frame (it must grow again: a moving camera) then
  // grows with 1/8 slack, so that small changes do not reallocate. `exact`
  // buffers, sized once per scene or viewport (uploads, the image), never
  // take slack. The slack stops at `most`, a bound on what the buffer can
  // ever need.
  void reserve(uint64_t n, bool exact = false, uint64_t most = UINT64_MAX)
  {
    n = n == 0 ? 1 : n;
    if (n <= capacity_) return;
    const bool growingAgain = capacity_ > 1;  // not the one-element placeholder of an unused buffer
    const uint64_t grown = exact || !growingAgain ? n : std::max(n, std::min(n + n / 8, most));
    const uint64_t bytes = grown * sizeof(T);
    const uint64_t needed = n * sizeof(T);
    if (needed > memory_->maxAllocBytes)
      throw Error("the frame needs " + std::to_string(needed) + " bytes for " + name_ +
                  ", more than the device's largest allocation (" + std::to_string(memory_->maxAllocBytes) + " bytes)");
    uint64_t chosen = bytes <= memory_->maxAllocBytes ? grown : n;
    buffer_ = cl::Buffer();
    memory_->bytesAllocated -= capacity_ * sizeof(T);
    capacity_ = 0;
    const uint64_t total = memory_->bytesAllocated + needed;
    if (memory_->bytesAllocated + chosen * sizeof(T) > std::min(memory_->globalMemBytes, memory_->limitBytes))
      chosen = n;  // no slack where it would not fit
    if (total > memory_->globalMemBytes || total > memory_->limitBytes) {
      const bool device = memory_->globalMemBytes <= memory_->limitBytes;
      throw Error("the frame needs " + byteCount(total) + " of device memory with " + name_ + ", more than " +
                  (device ? "the device's " + byteCount(memory_->globalMemBytes)
                          : "the memory limit of " + byteCount(memory_->limitBytes)));
    }
    if (memory_->hostBacked) checkHostMemory("the frame's device buffer for " + name_, chosen * sizeof(T));
    try {
      buffer_ = cl::Buffer(memory_->context, CL_MEM_READ_WRITE, chosen * sizeof(T));
      if (memory_->hostBacked) memory_->queue.enqueueFillBuffer(buffer_, cl_uchar(0), 0, 1);
    } catch (const cl::Error& e) {
      throw Error("cannot allocate " + std::to_string(chosen * sizeof(T)) + " bytes for " + name_ + " (" +
                  clErrorName(e.err()) + ")");
    }
    capacity_ = chosen;
    memory_->bytesAllocated += capacity_ * sizeof(T);
  }

  void upload(const std::vector<T>& data) { uploadPadded(data, 0); }

  // upload, then `pad` zero elements after the data (so that a kernel may
  // read a whole vector at the last element).
  void uploadPadded(const std::vector<T>& data, uint64_t pad)
  {
    reserve(data.size() + pad, true);
    if (!data.empty()) memory_->queue.enqueueWriteBuffer(buffer_, CL_TRUE, 0, data.size() * sizeof(T), data.data());
    if (pad) memory_->queue.enqueueFillBuffer(buffer_, T{}, data.size() * sizeof(T), pad * sizeof(T));
  }

  std::vector<T> download(uint64_t n, uint64_t first = 0) const
  {
    std::vector<T> out(n);
    if (n) memory_->queue.enqueueReadBuffer(buffer_, CL_TRUE, first * sizeof(T), n * sizeof(T), out.data());
    return out;
  }

  void zero(uint64_t n, std::vector<cl::Event>* events = nullptr)
  {
    reserve(n);
    cl::Event event;
    memory_->queue.enqueueFillBuffer(buffer_, T{}, 0, n * sizeof(T), nullptr, &event);
    if (events) events->push_back(event);
  }

  const cl::Buffer& get() const { return buffer_; }
  uint64_t capacity() const { return capacity_; }

 private:
  DeviceMemory* memory_;
  std::string name_;
  cl::Buffer buffer_;
  uint64_t capacity_ = 0;
};

}  // namespace clr
