#include "frame_sequence.h"

#include <cctype>
#include <optional>
#include <regex>

#include "errors.h"

namespace gridrt {
namespace {

struct ParsedPattern {
  std::string prefix, suffix;
  int width = 0;
  bool zero_padded = false;
};

// The pattern's parts, or the reason it is not one.
std::optional<ParsedPattern> parsePattern(const std::string& text, std::string& why) {
  ParsedPattern p;
  bool converted = false;
  for (size_t i = 0; i < text.size(); ++i) {
    std::string& out = converted ? p.suffix : p.prefix;
    if (text[i] != '%') {
      out += text[i];
      continue;
    }
    if (i + 1 < text.size() && text[i + 1] == '%') {
      out += '%';
      ++i;
      continue;
    }
    size_t j = i + 1;
    const bool zero = j < text.size() && text[j] == '0';
    if (zero) ++j;
    const size_t digits_at = j;
    while (j < text.size() && std::isdigit(static_cast<unsigned char>(text[j]))) ++j;
    if (j - digits_at > 2 || j >= text.size() || text[j] != 'd') {
      why = "'%" + text.substr(i + 1, j + 1 - (i + 1)) +
            "' is not a frame number (%d, %4d or %04d; %% for a '%')";
      return std::nullopt;
    }
    if (converted) {
      why = "it has more than one frame number";
      return std::nullopt;
    }
    converted = true;
    p.zero_padded = zero;
    p.width = j > digits_at ? std::stoi(text.substr(digits_at, j - digits_at)) : 0;
    i = j;
  }
  if (!converted) {
    why = "it has no frame number (e.g. out_%04d.png)";
    return std::nullopt;
  }
  return p;
}

}  // namespace

FrameRange parseFrameRange(const std::string& text) {
  static const std::regex range(R"(^(\d{1,7}):(\d{1,7})$)");
  std::smatch m;
  FrameRange r;
  if (std::regex_match(text, m, range)) {
    r.first = std::stol(m[1]);
    r.last = std::stol(m[2]);
  }
  if (!std::regex_match(text, m, range) || r.first > r.last || r.last > kMaxFrameNumber)
    throw UsageError("--frames: expected A:B, whole numbers with 0 <= A <= B <= " +
                     std::to_string(kMaxFrameNumber) + ", got '" + text + "'");
  if (r.last - r.first + 1 > kMaxFramesPerRun)
    throw UsageError("--frames: " + text + " is " + std::to_string(r.last - r.first + 1) +
                     " frames, more than the " + std::to_string(kMaxFramesPerRun) +
                     " of one run (split it into several runs)");
  return r;
}

double frameTime(long frame, double fps) { return double(frame) / fps; }

FramePattern::FramePattern(const std::string& flag, const std::string& text) {
  std::string why;
  const std::optional<ParsedPattern> p = parsePattern(text, why);
  if (!p) throw UsageError(flag + ": '" + text + "' is not a frame pattern for --frames: " + why);
  prefix_ = p->prefix;
  suffix_ = p->suffix;
  width_ = p->width;
  zero_padded_ = p->zero_padded;
}

bool FramePattern::isPattern(const std::string& text) {
  std::string why;
  return parsePattern(text, why).has_value();
}

std::string FramePattern::path(long frame) const {
  std::string number = std::to_string(frame);
  if (int(number.size()) < width_)
    number.insert(0, size_t(width_) - number.size(), zero_padded_ ? '0' : ' ');
  return prefix_ + number + suffix_;
}

}  // namespace gridrt
