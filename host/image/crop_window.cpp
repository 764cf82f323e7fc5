#include "crop_window.h"

#include <regex>

#include "errors.h"

namespace gridrt {

PixelWindow parseCropWindow(const std::string& text, int width, int height) {
  // At most 9 digits each, so the conversion cannot overflow an int.
  static const std::regex four(R"(^(\d{1,9}),(\d{1,9}),(\d{1,9}),(\d{1,9})$)");
  std::smatch m;
  if (!std::regex_match(text, m, four))
    throw UsageError("--crop: expected X0,Y0,X1,Y1 (four pixel bounds), got '" + text + "'");
  PixelWindow w{std::stoi(m[1]), std::stoi(m[2]), std::stoi(m[3]), std::stoi(m[4])};
  if (w.x0 >= w.x1 || w.y0 >= w.y1 || w.x1 > width || w.y1 > height)
    throw UsageError(
        "--crop: window '" + text + "' must satisfy X0 < X1 <= " + std::to_string(width) +
        " and Y0 < Y1 <= " + std::to_string(height) + " (half-open pixel bounds inside the " +
        std::to_string(width) + "x" + std::to_string(height) + " image)");
  return w;
}

}  // namespace gridrt
