#include "sample_coverage.h"

#include "parallel_loops.h"

namespace gridrt {

void SampleCoverage::reset(size_t pixels) {
  hits_.assign(pixels, 0);
  samples_.assign(pixels, 0);
}

std::vector<float> SampleCoverage::alpha() const {
  std::vector<float> alpha(hits_.size());
  parallelFor(0LL, (long long)(alpha.size()), [&](long long p) {
    alpha[p] = samples_[p] == 0 ? 0.0f : float(hits_[p]) / float(samples_[p]);
  });
  return alpha;
}

}  // namespace gridrt
