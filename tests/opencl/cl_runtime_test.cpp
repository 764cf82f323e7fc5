// ClRuntime::runAndWait: the commands `enqueue` queues have all run when it
// returns, from any host thread count, and an exception from `enqueue` comes out of it
// (a throw that left the parallel region inside would end the process).
#include "cl_runtime.h"

#include <gtest/gtest.h>

#include <numeric>
#include <vector>

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
