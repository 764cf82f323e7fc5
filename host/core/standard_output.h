// The path that means standard output (-o -, --stats-json -).
#pragma once

namespace gridrt {

constexpr const char* kStandardOutput = "-";

}  // namespace gridrt
