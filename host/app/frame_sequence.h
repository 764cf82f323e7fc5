// Which frames a run renders (--frames A:B, --fps F), at which times, into which files
// (an output path with a printf pattern for the frame number).
#pragma once
#include <string>

namespace gridrt {

struct FrameRange {
  long first = 0, last = 0;  // inclusive, 0 <= first <= last
};

// The largest frame number --frames takes, and the most frames one run renders (a run
// lists its frames' files before it starts; 100,000 frames are 69 minutes at 24 fps).
constexpr long kMaxFrameNumber = 9999999;
constexpr long kMaxFramesPerRun = 100000;

// "A:B" with 0 <= A <= B <= kMaxFrameNumber and at most kMaxFramesPerRun frames; throws
// UsageError naming --frames otherwise.
FrameRange parseFrameRange(const std::string& text);

// The time of frame `frame` at `fps` frames a second: frame / fps in double. The one place
// it is computed, so that frame K of any range is posed exactly as --time K/F would be
// (given the double K/F, e.g. as the statistics print it).
double frameTime(long frame, double fps);

// An output path with exactly one conversion for the frame number, as printf writes an
// int: %d, %Nd (padded with spaces) or %0Nd (with zeros), N at most 2 digits; %% stands
// for a '%'. Nothing else may follow a '%'.
class FramePattern {
 public:
  // Throws UsageError naming `flag` (e.g. "-o") when `text` is not such a pattern.
  FramePattern(const std::string& flag, const std::string& text);
  // Whether `text` is such a pattern.
  static bool isPattern(const std::string& text);
  // The path of frame `frame`.
  std::string path(long frame) const;

 private:
  std::string prefix_, suffix_;  // '%%' already made '%'
  int width_ = 0;
  bool zero_padded_ = false;
};

}  // namespace gridrt
