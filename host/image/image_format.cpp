#include "image_format.h"

#include <cctype>
#include <filesystem>

namespace gridrt {
namespace {

std::string lower(std::string text) {
  for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

}  // namespace

std::optional<ImageFormat> formatOfPath(const std::string& path) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  if (ext == ".png") return ImageFormat::Png;
  if (ext == ".jpg" || ext == ".jpeg") return ImageFormat::Jpeg;
  if (ext == ".exr") return ImageFormat::Exr;
  if (ext == ".tif" || ext == ".tiff") return ImageFormat::Tiff;
  if (ext == ".hdr") return ImageFormat::Hdr;
  return std::nullopt;
}

std::optional<ImageFormat> formatNamed(const std::string& name) {
  if (name == "png") return ImageFormat::Png;
  if (name == "jpg" || name == "jpeg") return ImageFormat::Jpeg;
  if (name == "exr") return ImageFormat::Exr;
  return std::nullopt;
}

std::string formatName(ImageFormat format) {
  switch (format) {
    case ImageFormat::Png:
      return "png";
    case ImageFormat::Jpeg:
      return "jpg";
    case ImageFormat::Exr:
      return "exr";
    case ImageFormat::Tiff:
      return "tif";
    case ImageFormat::Hdr:
      return "hdr";
  }
  return "";
}

}  // namespace gridrt
