// Progressive refinement: frames of one jittered sample each (RenderSettings::single_sample)
// added up while nothing moves, shown as their mean until all --spp samples are in.
#pragma once
#include <vector>

#include "film.h"

namespace gridrt {

class ProgressiveFilm {
 public:
  // Forgets every sample (the view changed).
  void restart() { samples_ = 0; }
  int samples() const { return samples_; }
  // Adds a frame of one sample a pixel (its size must be the first frame's since restart).
  void add(const Film& frame);
  // The mean of the samples added, as a film (the first frame's background and size).
  const Film& mean();

 private:
  int samples_ = 0;
  std::vector<double> sum_, alpha_sum_;
  Film mean_;
};

}  // namespace gridrt
