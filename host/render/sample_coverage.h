// The image's alpha: per pixel, how many camera samples it took and how many of them hit
// geometry. Every pass of a frame (bands of rows, adaptive refinement) adds its samples,
// so the alpha is the share of all of a pixel's camera samples that hit something.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace gridrt {

class SampleCoverage {
 public:
  // `pixels` pixels, none sampled yet.
  void reset(size_t pixels);
  // Pixel `pixel` took `samples` more camera samples, `hits` of them on geometry. Calls for
  // distinct pixels may run in parallel.
  void add(size_t pixel, uint32_t hits, uint32_t samples) {
    hits_[pixel] += hits;
    samples_[pixel] += samples;
  }
  // hits / samples per pixel: 0 where nothing was hit (or nothing sampled), 1 where every
  // sample hit.
  std::vector<float> alpha() const;

 private:
  std::vector<uint32_t> hits_, samples_;
};

}  // namespace gridrt
