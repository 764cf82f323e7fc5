// The window module: viewer_window.h over SDL2 (Debian's libsdl2). SDL's software renderer
// copies the image to the window at 1:1, so the window's pixels are the image's codes (a
// screenshot of a 24-bit X server equals the PNG the viewer writes).
#include <SDL.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "viewer_window.h"

namespace gridrt {
namespace {

int keyOf(SDL_Keycode sym) {
  switch (sym) {
    case SDLK_LEFT: return kKeyLeft;
    case SDLK_RIGHT: return kKeyRight;
    case SDLK_UP: return kKeyUp;
    case SDLK_DOWN: return kKeyDown;
    case SDLK_HOME: return kKeyHome;
    case SDLK_ESCAPE: return kKeyEscape;
    case SDLK_KP_PLUS: return '=';
    case SDLK_KP_MINUS: return '-';
    default: break;
  }
  // SDL's key codes of printable keys are their (lower-case) characters.
  if (sym >= 32 && sym < 127) return int(sym);
  return 0;
}

class SdlWindow final : public ViewerWindow {
 public:
  SdlWindow(SDL_Window* window, SDL_Renderer* renderer) : window_(window), renderer_(renderer) {}
  ~SdlWindow() override {
    if (texture_) SDL_DestroyTexture(texture_);
    SDL_DestroyRenderer(renderer_);
    SDL_DestroyWindow(window_);
    SDL_Quit();
  }

  void setTitle(const std::string& title) override { SDL_SetWindowTitle(window_, title.c_str()); }

  void present(const unsigned char* rgb, int width, int height) override {
    if (!texture_ || width != texture_width_ || height != texture_height_) {
      if (texture_) SDL_DestroyTexture(texture_);
      texture_ = SDL_CreateTexture(renderer_, SDL_PIXELFORMAT_RGB24, SDL_TEXTUREACCESS_STREAMING,
                                   width, height);
      texture_width_ = width;
      texture_height_ = height;
    }
    if (texture_) SDL_UpdateTexture(texture_, nullptr, rgb, width * 3);
    draw();
  }

  std::vector<WindowEvent> events(int timeout_ms) override {
    std::vector<WindowEvent> out;
    SDL_Event e;
    bool have = timeout_ms > 0 ? SDL_WaitEventTimeout(&e, timeout_ms) != 0 : SDL_PollEvent(&e) != 0;
    while (have) {
      translate(e, out);
      have = SDL_PollEvent(&e) != 0;
    }
    return out;
  }

  void size(int& width, int& height) const override {
    SDL_GetWindowSize(window_, &width, &height);
  }

 private:
  void draw() {
    SDL_SetRenderDrawColor(renderer_, 0, 0, 0, 255);
    SDL_RenderClear(renderer_);
    if (texture_) {
      const SDL_Rect where{0, 0, texture_width_, texture_height_};
      SDL_RenderCopy(renderer_, texture_, nullptr, &where);
    }
    SDL_RenderPresent(renderer_);
  }

  void translate(const SDL_Event& e, std::vector<WindowEvent>& out) {
    WindowEvent w;
    switch (e.type) {
      case SDL_QUIT:
        w.kind = WindowEvent::Kind::Quit;
        break;
      case SDL_KEYDOWN:
        w.kind = WindowEvent::Kind::Key;
        w.key = keyOf(e.key.keysym.sym);
        if (w.key == 0) return;
        break;
      case SDL_MOUSEMOTION: {
        const Uint32 s = e.motion.state;
        w.button = s & SDL_BUTTON_LMASK ? 1 : s & SDL_BUTTON_MMASK ? 2 : s & SDL_BUTTON_RMASK ? 3 : 0;
        if (w.button == 0) return;
        w.kind = WindowEvent::Kind::Drag;
        w.dx = e.motion.xrel;
        w.dy = e.motion.yrel;
        // One drag event for a run of motion with the same button.
        if (!out.empty() && out.back().kind == WindowEvent::Kind::Drag &&
            out.back().button == w.button) {
          out.back().dx += w.dx;
          out.back().dy += w.dy;
          return;
        }
        break;
      }
      case SDL_MOUSEWHEEL:
        w.kind = WindowEvent::Kind::Wheel;
        w.dy = e.wheel.direction == SDL_MOUSEWHEEL_FLIPPED ? -e.wheel.y : e.wheel.y;
        if (w.dy == 0) return;
        break;
      case SDL_WINDOWEVENT:
        if (e.window.event == SDL_WINDOWEVENT_SIZE_CHANGED) {
          w.kind = WindowEvent::Kind::Resized;
          w.width = e.window.data1;
          w.height = e.window.data2;
          break;
        }
        if (e.window.event == SDL_WINDOWEVENT_EXPOSED) draw();
        return;
      default:
        return;
    }
    out.push_back(w);
  }

  SDL_Window* window_;
  SDL_Renderer* renderer_;
  SDL_Texture* texture_ = nullptr;
  int texture_width_ = 0, texture_height_ = 0;
};

void fail(char* why, size_t why_size, const char* what) {
  std::snprintf(why, why_size, "%s: %s", what, SDL_GetError());
}

}  // namespace
}  // namespace gridrt

extern "C" __attribute__((visibility("default"))) gridrt::ViewerWindow* gridrt_open_window(
    const char* title, int width, int height, char* why, size_t why_size) {
  // A window on the display the environment names, and on no other: without this SDL goes
  // on from a display it cannot open to drivers with no window to see (KMSDRM, offscreen).
  if (!std::getenv("SDL_VIDEODRIVER")) {
    const char* display = std::getenv("DISPLAY");
    const bool x11 = display && *display;
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    SDL_SetHint(SDL_HINT_VIDEODRIVER, wayland && *wayland ? (x11 ? "wayland,x11" : "wayland") : "x11");
  }
  if (SDL_Init(SDL_INIT_VIDEO) != 0) {
    gridrt::fail(why, why_size, "SDL_Init");
    return nullptr;
  }
  SDL_Window* window = SDL_CreateWindow(title, SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED,
                                        width, height, SDL_WINDOW_RESIZABLE);
  if (!window) {
    gridrt::fail(why, why_size, "SDL_CreateWindow");
    SDL_Quit();
    return nullptr;
  }
  SDL_Renderer* renderer = SDL_CreateRenderer(window, -1, SDL_RENDERER_SOFTWARE);
  if (!renderer) {
    gridrt::fail(why, why_size, "SDL_CreateRenderer");
    SDL_DestroyWindow(window);
    SDL_Quit();
    return nullptr;
  }
  return new gridrt::SdlWindow(window, renderer);
}
