// The window the viewer draws in, as the viewer sees it: images in, input events out. Only
// the window module (sdl/sdl_window.cpp, a shared module window_module.h loads with dlopen
// for --view alone) links the window library, so the command line never needs it.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace gridrt {

// Keys without a character of their own (the others are their lower-case ASCII code:
// 'a'..'z', '0'..'9', ' ', '[', ']', ',', '.', '=', '-', 27 for Escape).
enum WindowKey : int {
  kKeyEscape = 27,
  kKeyLeft = 0x100,
  kKeyRight,
  kKeyUp,
  kKeyDown,
  kKeyHome,
};

struct WindowEvent {
  enum class Kind { Key, Drag, Wheel, Resized, Quit };
  Kind kind = Kind::Quit;
  int key = 0;         // Key: the key (WindowKey or its character)
  int button = 0;      // Drag: 1 left, 2 middle, 3 right
  int dx = 0, dy = 0;  // Drag: the pointer's motion in pixels (y down); Wheel: dy notches, + away
  int width = 0, height = 0;  // Resized: the window's new size in pixels
};

class ViewerWindow {
 public:
  virtual ~ViewerWindow() = default;
  virtual void setTitle(const std::string& title) = 0;
  // Shows `rgb` (width * height * 3 8-bit sRGB codes, row 0 at the top) at 1:1 in the
  // window's top left corner, until the next call (and after the window is uncovered).
  virtual void present(const unsigned char* rgb, int width, int height) = 0;
  // The events since the last call; with none pending, waits up to timeout_ms for one.
  virtual std::vector<WindowEvent> events(int timeout_ms) = 0;
  // The window's size in pixels.
  virtual void size(int& width, int& height) const = 0;
};

// The module's one entry point: a window `width` x `height` titled `title`, or null with
// the reason in why[0 .. why_size) (no display, no window library).
using OpenWindowEntry = ViewerWindow* (*)(const char* title, int width, int height, char* why,
                                          size_t why_size);
#define GRIDRT_WINDOW_ENTRY "gridrt_open_window"

}  // namespace gridrt
