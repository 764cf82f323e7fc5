// A one-line progress bar on stderr for renders that take a while:
//   gridrt: [##########..........]  50%  1.2 s elapsed, about 1.2 s left
// (with a frame sequence: "50%  frame 3 of 10, 1.2 s elapsed, ...").
// Drawn only when stderr is a terminal and --quiet is off, and only once the render has
// run for `delay_s` (quick renders print nothing but the closing summary). The line is
// redrawn in place with '\r' and erased by finish(), so the summary line replaces it.
// While it is drawn, SIGINT and SIGTERM end its line before the program dies of them.
#pragma once
#include <signal.h>

#include <string>

#include "stopwatch.h"

namespace gridrt {

// Whether a progress bar belongs on stderr: a terminal (not a pipe or a file), not quiet.
bool progressWanted(bool quiet);
// The same decision for a given stderr (terminal or not) and $TERM (null when unset).
bool progressWanted(bool quiet, bool terminal, const char* term);

// How long a render runs before the bar appears: $GRIDRT_PROGRESS_DELAY seconds (a number
// >= 0; tests set 0 to see the bar on a render of any length), else kProgressDelayS.
constexpr double kProgressDelayS = 0.5;
double progressDelaySeconds();

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled, double delay_s = kProgressDelayS);
  ~ProgressBar() { finish(); }
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // fraction in [0, 1] of the whole job done so far; `note` (e.g. "frame 3 of 10") is shown
  // after the percentage.
  void update(double fraction, const std::string& note = "");
  // Erases the bar if it was drawn. Safe to call more than once.
  void finish();

 private:
  bool enabled_;
  bool drawn_ = false;
  double delay_ms_;
  double last_draw_ms_ = -1e9;
  Stopwatch clock_;
  struct sigaction previous_int_ {
  }, previous_term_{};  // restored by finish()
};

// The text of the bar (without '\r'), for a given fraction, elapsed and remaining seconds.
// Separate from the drawing so that it can be tested.
std::string formatProgressLine(double fraction, double elapsed_s, double remaining_s,
                               const std::string& note = "");

}  // namespace gridrt
