#include "window_output.h"

#include <OpenImageIO/imagebuf.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "errors.h"

namespace gridrt {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void failWrite(const std::string& path, std::string reason) {
  std::replace(reason.begin(), reason.end(), '\n', ' ');
  throw RenderError("cannot write '" + path + "': " + reason);
}

}  // namespace

void writeWindowImage(const std::string& path, const PixelWindow& window, int full_width,
                      int full_height, int channels, const std::vector<float>& data) {
  if (!keepsDataWindow(path)) failWrite(path, "a window needs .exr, .tif or .tiff");
  if (data.size() != size_t(window.width()) * window.height() * channels)
    failWrite(path, "window data has the wrong size");
  OIIO::ImageSpec spec(window.width(), window.height(), channels, OIIO::TypeDesc::FLOAT);
  spec.x = window.x0;
  spec.y = window.y0;
  spec.full_x = 0;
  spec.full_y = 0;
  spec.full_width = full_width;
  spec.full_height = full_height;
  OIIO::ImageBuf buf(spec);
  buf.set_pixels(buf.roi(), OIIO::TypeDesc::FLOAT, data.data());

  // Same scheme as image_output.cpp: a hidden sibling keeping the extension (OpenImageIO
  // picks the format from it), renamed onto the path only once complete.
  fs::path target(path), dir = target.parent_path().empty() ? "." : target.parent_path();
  fs::path temp = dir / ("." + target.stem().string() + ".tmp" + std::to_string(::getpid()) +
                         "-window" + target.extension().string());
  try {
    if (!buf.write(temp.string(), OIIO::TypeDesc::FLOAT)) failWrite(path, buf.geterror());
    if (std::rename(temp.c_str(), path.c_str()) != 0) failWrite(path, std::strerror(errno));
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
}

}  // namespace gridrt
