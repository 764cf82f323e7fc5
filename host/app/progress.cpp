#include "progress.h"

#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace gridrt {
namespace {

constexpr int kBarCells = 24;
// Redraw at most this often: --repeat can call update() thousands of times a second.
constexpr double kRedrawIntervalMs = 100.0;

std::string formatSeconds(double s) {
  char text[32];
  if (s < 60.0)
    std::snprintf(text, sizeof text, "%.1f s", s);
  else
    std::snprintf(text, sizeof text, "%d min %02d s", int(s) / 60, int(s) % 60);
  return text;
}

// Ctrl-C or a SIGTERM while the bar is drawn: end the bar's line, so the shell's prompt
// starts on a line of its own, then die of the signal as before (the exit status a shell
// expects: 130 for Ctrl-C). Only async-signal-safe calls.
void endLineAndDie(int signal_number) {
  static const char kNewline[] = "\n";
  (void)!::write(STDERR_FILENO, kNewline, sizeof kNewline - 1);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

}  // namespace

bool progressWanted(bool quiet) {
  return progressWanted(quiet, ::isatty(STDERR_FILENO), std::getenv("TERM"));
}

bool progressWanted(bool quiet, bool terminal, const char* term) {
  if (quiet || !terminal) return false;
  return !(term && std::strcmp(term, "dumb") == 0);  // no '\r' redraw on dumb terminals
}

double progressDelaySeconds() {
  const char* text = std::getenv("GRIDRT_PROGRESS_DELAY");
  if (!text || !*text) return kProgressDelayS;
  char* end = nullptr;
  const double s = std::strtod(text, &end);
  return *end == '\0' && s >= 0.0 ? s : kProgressDelayS;
}

std::string formatProgressLine(double fraction, double elapsed_s, double remaining_s,
                               const std::string& note) {
  fraction = std::clamp(fraction, 0.0, 1.0);
  int filled = int(fraction * kBarCells + 0.5);
  std::string bar(size_t(filled), '#');
  bar.append(size_t(kBarCells - filled), '.');
  char percent[8];
  std::snprintf(percent, sizeof percent, "%3d%%", int(fraction * 100.0 + 0.5));
  return "gridrt: [" + bar + "] " + percent + "  " + (note.empty() ? "" : note + ", ") +
         formatSeconds(elapsed_s) + " elapsed, about " + formatSeconds(std::max(0.0, remaining_s)) +
         " left";
}

ProgressBar::ProgressBar(bool enabled, double delay_s)
    : enabled_(enabled), delay_ms_(delay_s * 1000.0) {}

void ProgressBar::update(double fraction, const std::string& note) {
  if (!enabled_) return;
  double now = clock_.ms();
  if (now < delay_ms_ || now - last_draw_ms_ < kRedrawIntervalMs) return;
  last_draw_ms_ = now;
  double elapsed = now / 1000.0;
  // A linear estimate: the first bounce (primary rays) dominates, so early estimates are
  // pessimistic rather than optimistic.
  double remaining = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  // "\033[K" erases what a longer previous line left to the right.
  std::fprintf(stderr, "\r%s\033[K",
               formatProgressLine(fraction, elapsed, remaining, note).c_str());
  std::fflush(stderr);
  if (!drawn_) {
    struct sigaction ends_line {};
    ends_line.sa_handler = endLineAndDie;
    sigemptyset(&ends_line.sa_mask);
    sigaction(SIGINT, &ends_line, &previous_int_);
    sigaction(SIGTERM, &ends_line, &previous_term_);
  }
  drawn_ = true;
}

void ProgressBar::finish() {
  if (!drawn_) return;
  sigaction(SIGINT, &previous_int_, nullptr);
  sigaction(SIGTERM, &previous_term_, nullptr);
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace gridrt
