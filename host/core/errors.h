// Error kinds the command line maps to exit codes: UsageError -> 2, everything else -> 1.
// Every message is one line that names the problem (and the file or element involved).
#pragma once
#include <stdexcept>
#include <string>

namespace gridrt {

// Bad command-line flag or value.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Missing, unreadable or malformed scene file, or a scene with nothing to render.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Device selection, kernel build, out-of-resources and output-writing failures.
struct RenderError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace gridrt
