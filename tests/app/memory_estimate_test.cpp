// The memory check refuses images that cannot fit, and only those: a frame renders in
// passes, so its need grows with the pixels, not with pixels x samples.
#include "memory_estimate.h"

#include <gtest/gtest.h>

#include "renderer.h"

namespace gridrt {
namespace {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

TEST(MemoryEstimate, APassHoldsAtMostTheBudgetOrOneRow) {
  EXPECT_EQ(estimateMemory(1920, 1080, 1).pass_samples, double(kMaxPassRays));
  EXPECT_EQ(estimateMemory(100, 100, 1).pass_samples, 10000.0);  // a small frame is one pass
  EXPECT_EQ(estimateMemory(3840, 2160, 64).pass_samples, double(kMaxPassRays));
  EXPECT_EQ(estimateMemory(65536, 4, 4096).pass_samples, 65536.0 * 4096.0);  // one row
}

TEST(MemoryEstimate, SamplesDoNotMultiplyTheFrame) {
  // 4K at 64 samples is 530M samples: 400 bytes each (every sample in flight at once, as
  // before passes) would be 198 GiB; in passes it is the image plus one pass.
  const MemoryEstimate many = estimateMemory(3840, 2160, 64);
  EXPECT_LT(many.host_bytes, 2.0 * kGiB);
  EXPECT_EQ(many.device_bytes, estimateMemory(3840, 2160, 1).device_bytes);
  EXPECT_GT(many.host_bytes, 3840.0 * 2160.0 * 12.0);  // at least the radiance itself
}

TEST(MemoryEstimate, AbsurdImagesStayRefused) {
  EXPECT_GT(estimateMemory(65536, 65536, 1).host_bytes, 256.0 * kGiB);
  EXPECT_GT(estimateMemory(65536, 4, 4096).device_bytes, 64.0 * kGiB);
}

// With --crop the film holds the window alone: a window of a huge image needs the memory
// of the window, unless it is written at full size (the placed copy: the full image's
// pixels once more).
TEST(MemoryEstimate, ACropWindowNeedsTheMemoryOfItsWindow) {
  const PixelWindow window{1000, 2000, 1512, 2512};
  const MemoryEstimate tile = estimateMemory(65536, 65536, 4, window, false);
  const MemoryEstimate alone = estimateMemory(512, 512, 4);
  EXPECT_EQ(tile.host_bytes, alone.host_bytes);
  EXPECT_EQ(tile.device_bytes, alone.device_bytes);
  EXPECT_EQ(tile.pass_samples, alone.pass_samples);
  EXPECT_GT(estimateMemory(65536, 65536, 4, window, true).host_bytes, 64.0 * kGiB);
}

// --transfer copy keeps host arrays beside the device buffers (at most one pass's worth):
// measured at 1920x1080 on the default scene, the peak host memory 397 MiB mapped and 469
// copied, with 77 MiB of device buffers.
TEST(MemoryEstimate, CopiedBatchesCountTheDeviceBuffersOnTheHostOnceMore) {
  const MemoryEstimate mapped = estimateMemory(3840, 2160, 4);
  const MemoryEstimate copied = estimateMemory(3840, 2160, 4, {}, true, true);
  EXPECT_EQ(copied.host_bytes, mapped.host_bytes + mapped.device_bytes);
  EXPECT_EQ(copied.device_bytes, mapped.device_bytes);
}

}  // namespace
}  // namespace gridrt
