#include "progressive_film.h"

#include <stdexcept>

namespace gridrt {

void ProgressiveFilm::add(const Film& frame) {
  if (samples_ == 0) {
    sum_.assign(frame.rgb.begin(), frame.rgb.end());
    alpha_sum_.assign(frame.alpha.begin(), frame.alpha.end());
    mean_ = frame;
  } else {
    if (frame.rgb.size() != sum_.size() || frame.alpha.size() != alpha_sum_.size())
      throw std::logic_error("ProgressiveFilm: a frame of another size");
    for (size_t k = 0; k < sum_.size(); ++k) sum_[k] += frame.rgb[k];
    for (size_t k = 0; k < alpha_sum_.size(); ++k) alpha_sum_[k] += frame.alpha[k];
  }
  ++samples_;
}

const Film& ProgressiveFilm::mean() {
  // One sample: the frame itself, bit for bit (sum_ holds its floats exactly).
  for (size_t k = 0; k < sum_.size(); ++k) mean_.rgb[k] = float(sum_[k] / samples_);
  for (size_t k = 0; k < alpha_sum_.size(); ++k) mean_.alpha[k] = float(alpha_sum_[k] / samples_);
  return mean_;
}

}  // namespace gridrt
