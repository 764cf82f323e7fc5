// The command line's options as the Python module takes them: render(..., max_depth=2)
// becomes --max-depth 2 (python/gridrt/__init__.py spells the flags), parsed by the
// command line's own parser, so every value is checked and defaulted as gridrt's are.
#pragma once
#include <string>
#include <vector>

#include "options.h"

namespace gridrt {

// The options of `arguments` (gridrt's command line without the program's name, quiet).
// Throws UsageError with the command line's message for a bad flag or value, and for the
// options that write files or print instead of rendering (the module returns the image).
Options pythonOptions(const std::vector<std::string>& arguments);

}  // namespace gridrt
