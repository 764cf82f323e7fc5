// The window module (viewer_window.h), loaded with dlopen only when --view asks for a
// window, where module_search.h looks: beside the running executable, in the installed
// modules' folder, then where the build put it.
#pragma once
#include <memory>
#include <stdexcept>
#include <string>

#include "viewer_window.h"

namespace gridrt {

// Throws NoDisplay when there is no display to open a window on (neither DISPLAY nor
// WAYLAND_DISPLAY set).
void checkDisplay();

// A window of the given size and title. Throws NoDisplay with the reason when there is no
// display to open it on, or the module cannot be loaded.
std::unique_ptr<ViewerWindow> openViewerWindow(const std::string& title, int width, int height);

struct NoDisplay : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace gridrt
