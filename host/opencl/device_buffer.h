// A device buffer of T that grows when a batch needs more room and is otherwise reused,
// so nothing is allocated per frame once the largest batch has been seen.
#pragma once
#include <string>
#include <vector>

#include "cl_runtime.h"

namespace gridrt {

template <typename T>
class DeviceBuffer {
 public:
  explicit DeviceBuffer(std::string what, cl_mem_flags flags = CL_MEM_READ_WRITE)
      : what_(std::move(what)), flags_(flags) {}

  // Makes room for `count` elements (at least one, since OpenCL forbids empty buffers).
  cl::Buffer& reserve(ClRuntime& rt, size_t count) {
    count = count ? count : 1;
    if (count > capacity_) {
      size_t grown = std::max(count, capacity_ + capacity_ / 2);
      rt.checkAllocation(grown * sizeof(T), what_);
      buffer_ = cl::Buffer(rt.context(), flags_, grown * sizeof(T));
      rt.noteBufferResize(capacity_ * sizeof(T), grown * sizeof(T));
      capacity_ = grown;
    }
    return buffer_;
  }

  // Non-blocking: `data` must stay alive and unchanged until the queue has run the copy
  // (a later blocking read or finish). Per-batch data that outlives the batch only.
  cl::Buffer& upload(ClRuntime& rt, const T* data, size_t count) {
    reserve(rt, count);
    if (count) rt.queue().enqueueWriteBuffer(buffer_, CL_FALSE, 0, count * sizeof(T), data);
    return buffer_;
  }
  template <typename Allocator>
  cl::Buffer& upload(ClRuntime& rt, const std::vector<T, Allocator>& data) {
    return upload(rt, data.data(), data.size());
  }

  // Blocking: returns once the data is copied, so `data` may be a temporary.
  template <typename Allocator>
  cl::Buffer& uploadNow(ClRuntime& rt, const std::vector<T, Allocator>& data) {
    reserve(rt, data.size());
    if (!data.empty())
      rt.queue().enqueueWriteBuffer(buffer_, CL_TRUE, 0, data.size() * sizeof(T), data.data());
    return buffer_;
  }

  // Blocking: makes room for `count` elements and calls fill(T*) on the buffer's memory
  // mapped for writing, its old contents dropped (on a CPU device the buffer itself: no
  // staging copy of tens of megabytes).
  template <typename Fill>
  cl::Buffer& fillMapped(ClRuntime& rt, size_t count, const Fill& fill) {
    reserve(rt, count);
    if (!count) return buffer_;
    T* data = static_cast<T*>(rt.queue().enqueueMapBuffer(
        buffer_, CL_TRUE, CL_MAP_WRITE_INVALIDATE_REGION, 0, count * sizeof(T)));
    fill(data);
    cl::Event done;
    rt.queue().enqueueUnmapMemObject(buffer_, data, nullptr, &done);
    done.wait();
    return buffer_;
  }

  void download(ClRuntime& rt, T* data, size_t count) {
    if (count) rt.queue().enqueueReadBuffer(buffer_, CL_TRUE, 0, count * sizeof(T), data);
  }

  cl::Buffer& get() { return buffer_; }
  size_t capacity() const { return capacity_; }

 private:
  std::string what_;
  cl_mem_flags flags_;
  cl::Buffer buffer_;
  size_t capacity_ = 0;
};

}  // namespace gridrt
