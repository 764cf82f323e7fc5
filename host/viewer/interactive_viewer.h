// gridrt --view: a window that renders the scene continuously through the command line's
// own frame loop (PreparedScene and Renderer, the same options), moved with the mouse and
// keys (key_bindings.h, docs/viewer.md). Returns the exit code: 0 when the window is
// closed or Q / Escape pressed; throws NoDisplay (window_module.h) without a display, and
// the errors of host/core/errors.h as the command line does.
#pragma once
#include "options.h"

namespace gridrt {

int runViewer(const Options& options);

}  // namespace gridrt
