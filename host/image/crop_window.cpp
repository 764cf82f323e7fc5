#include "crop_window.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <regex>

#include "errors.h"

namespace gridrt {

bool keepsDataWindow(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".exr" || ext == ".tif" || ext == ".tiff";
}

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

std::vector<float> placeWindow(const std::vector<float>& window_data, int width, int height,
                               int channels, const PixelWindow& window, float outside) {
  std::vector<float> out(size_t(width) * height * channels, outside);
  const size_t row = size_t(window.width()) * channels;
  for (int y = window.y0; y < window.y1; ++y)
    std::copy_n(window_data.begin() + size_t(y - window.y0) * row, row,
                out.begin() + (size_t(y) * width + window.x0) * channels);
  return out;
}

}  // namespace gridrt
