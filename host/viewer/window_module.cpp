#include "window_module.h"

#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "module_search.h"

namespace gridrt {
namespace {

OpenWindowEntry loadEntry() {
#ifndef GRIDRT_WINDOW_MODULE_FILE
  throw NoDisplay("gridrt was built without the window module (install libsdl2-dev, rebuild)");
#else
  const std::vector<std::string> candidates = moduleSearchPaths(
      GRIDRT_WINDOW_MODULE_FILE, GRIDRT_MODULE_DIR_FROM_BIN, GRIDRT_WINDOW_MODULE_PATH);
  // Kept loaded for the life of the process (the window's code runs until exit).
  std::string why;
  if (void* entry = loadModuleEntry(candidates, GRIDRT_WINDOW_ENTRY, why))
    return reinterpret_cast<OpenWindowEntry>(entry);
  if (why.empty())
    why = "not found beside the executable, in its " GRIDRT_MODULE_DIR_FROM_BIN
          " nor at " GRIDRT_WINDOW_MODULE_PATH;
  throw NoDisplay("cannot load the window module " GRIDRT_WINDOW_MODULE_FILE ": " + why);
#endif
}

}  // namespace

void checkDisplay() {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!display || !*display) && (!wayland || !*wayland)) throw NoDisplay("DISPLAY is not set");
}

std::unique_ptr<ViewerWindow> openViewerWindow(const std::string& title, int width, int height) {
  checkDisplay();
  const OpenWindowEntry open = loadEntry();
  char why[512] = {0};
  std::unique_ptr<ViewerWindow> window(open(title.c_str(), width, height, why, sizeof why));
  if (!window) throw NoDisplay(why[0] ? why : "the window could not be opened");
  return window;
}

}  // namespace gridrt
