// ClRuntime::runAndWait: the commands `enqueue` queues have all run when it
// returns, from any host thread count, and an exception from `enqueue` comes out of it
// (a throw that left the parallel region inside would end the process). DeviceBuffer's
// mapped fill.
#include "cl_runtime.h"

#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include "device_buffer.h"
#include "errors.h"
#include "parallel_loops.h"

namespace {

using gridrt::ClRuntime;

TEST(ClRuntime, CommandsHaveRunWhenItReturns) {
  ClRuntime rt("");
  const size_t n = 1 << 20;
  std::vector<int> source(n), back(n, -1);
  std::iota(source.begin(), source.end(), 0);
  cl::Buffer buffer(rt.context(), CL_MEM_READ_WRITE, n * sizeof(int));
  for (int threads : {1, 2, 4}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    std::fill(back.begin(), back.end(), -1);
    rt.runAndWait([&] {
      rt.queue().enqueueWriteBuffer(buffer, CL_FALSE, 0, n * sizeof(int), source.data());
      rt.queue().enqueueReadBuffer(buffer, CL_FALSE, 0, n * sizeof(int), back.data());
    });
    EXPECT_EQ(back, source) << threads << " threads";
  }
}

// DeviceBuffer::fillMapped: what the fill writes is what the device holds, also when the
// buffer grows for a second, larger fill.
TEST(DeviceBuffer, FillMappedHoldsWhatWasWritten) {
  ClRuntime rt("");
  gridrt::DeviceBuffer<int> buffer("test values", CL_MEM_READ_ONLY);
  for (size_t n : {size_t(1000), size_t(3) << 20}) {
    buffer.fillMapped(rt, n, [&](int* data) {
      for (size_t k = 0; k < n; ++k) data[k] = int(k * 7 + n);
    });
    std::vector<int> back(n, -1);
    buffer.download(rt, back.data(), n);
    for (size_t k = 0; k < n; ++k) ASSERT_EQ(back[k], int(k * 7 + n)) << k << " of " << n;
  }
}

TEST(ClRuntime, AnExceptionFromEnqueueIsRethrown) {
  ClRuntime rt("");
  EXPECT_THROW(rt.runAndWait([] { throw gridrt::RenderError("no room"); }), gridrt::RenderError);
  // The runtime still works afterwards.
  int value = 0;
  cl::Buffer buffer(rt.context(), CL_MEM_READ_WRITE, sizeof(int));
  rt.runAndWait([&] {
    const int seven = 7;
    rt.queue().enqueueWriteBuffer(buffer, CL_TRUE, 0, sizeof(int), &seven);
    rt.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, sizeof(int), &value);
  });
  EXPECT_EQ(value, 7);
}

}  // namespace
