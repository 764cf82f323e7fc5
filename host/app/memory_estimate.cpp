#include "memory_estimate.h"

#include <algorithm>

#include "renderer.h"

namespace gridrt {

namespace {

// Measured peaks, rounded up: 3840x2160 took 75 bytes a pixel more than 1920x1080 (the
// same passes); a 640x480 frame's two passes of 154k samples ~150 MB.
// Bytes per pixel of the frame: radiance, film, AOVs, the encoded copy written out.
constexpr double kHostBytesPerPixel = 96.0;
// Bytes per primary sample of one pass: rays, hits, paths, shadow rays, slots, bundles
// on the host, and no more than these on the device.
constexpr double kBytesPerPassSample = 800.0;
// Bytes per pixel of the full image when a cropped film is written at full size: the
// placed copy and its encoded copy (measured: 8000x6000 with a 200x200 window, 24 bytes
// a pixel more than with --crop-output window).
constexpr double kFullOutputBytesPerPixel = 32.0;

}  // namespace

MemoryEstimate estimateMemory(int width, int height, int spp, const PixelWindow& crop,
                              bool full_size_output, bool batches_copied) {
  const PixelWindow film = crop.orWholeImage(width, height);
  const double pixels = double(film.width()) * double(film.height());
  const double frame = pixels * spp, row = double(film.width()) * spp;
  MemoryEstimate m;
  // renderInBands: the whole window, or kMaxPassRays, or at least one row.
  m.pass_samples = std::min(frame, std::max(double(kMaxPassRays), row));
  m.device_bytes = m.pass_samples * kBytesPerPassSample;
  m.host_bytes = pixels * kHostBytesPerPixel + m.device_bytes;
  if (batches_copied) m.host_bytes += m.device_bytes;
  if (!crop.whole() && full_size_output)
    m.host_bytes += double(width) * double(height) * kFullOutputBytesPerPixel;
  return m;
}

}  // namespace gridrt
