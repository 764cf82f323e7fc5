// The path that means standard output (-o -, --stats-json -), and the scene that means
// standard input (gridrt -).
#pragma once

namespace gridrt {

constexpr const char* kStandardOutput = "-";
constexpr const char* kStandardInput = "-";

}  // namespace gridrt
