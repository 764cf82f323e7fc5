#include "image_output.h"

#include <OpenImageIO/color.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "errors.h"
#include "parallel_loops.h"

namespace gridrt {
namespace {

namespace fs = std::filesystem;

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// 8-bit formats: written sRGB-encoded.
bool isLdrFormat(const std::string& ext) {
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}

// Formats that store 32-bit floats exactly.
bool isFloatFormat(const std::string& ext) {
  return ext == ".exr" || ext == ".tif" || ext == ".tiff";
}

// OpenImageIO messages may span lines; ours are one line.
std::string oneLine(std::string message) {
  while (!message.empty() && message.back() == '\n') message.pop_back();
  std::replace(message.begin(), message.end(), '\n', ' ');
  return message.empty() ? "unknown OpenImageIO error" : message;
}

[[noreturn]] void failWrite(const std::string& path, const std::string& reason) {
  throw RenderError("cannot write '" + path + "': " + reason);
}

fs::path directoryOf(const std::string& path) {
  fs::path dir = fs::path(path).parent_path();
  return dir.empty() ? fs::path(".") : dir;
}

void checkSize(const std::string& path, int width, int height, int channels, size_t count) {
  if (width <= 0 || height <= 0 || channels <= 0)
    failWrite(path, "invalid image size " + std::to_string(width) + "x" + std::to_string(height) +
                        " with " + std::to_string(channels) + " channels");
  size_t expected = size_t(width) * size_t(height) * size_t(channels);
  if (count != expected)
    failWrite(path, "image is " + std::to_string(width) + "x" + std::to_string(height) + " with " +
                        std::to_string(channels) + " channels but has " + std::to_string(count) +
                        " values (expected " + std::to_string(expected) + ")");
}

OIIO::ImageBuf makeBuffer(int width, int height, int channels, const float* data) {
  OIIO::ImageBuf buf(OIIO::ImageSpec(width, height, channels, OIIO::TypeDesc::FLOAT));
  buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, data);
  return buf;
}

// Writes `buf` as `format` to a hidden sibling of `path` that keeps its extension (so
// OpenImageIO picks the file format from it), then renames it onto `path`. On failure the
// temporary file is removed and whatever was at `path` stays as it was.
void writeAtomically(const std::string& path, const OIIO::ImageBuf& buf, OIIO::TypeDesc format) {
  static std::atomic<unsigned> counter{0};  // distinct names for concurrent writers
  const fs::path target(path);
  const fs::path temp =
      directoryOf(path) / ("." + target.stem().string() + ".tmp" + std::to_string(::getpid()) +
                           "-" + std::to_string(counter++) + target.extension().string());
  try {
    if (!buf.write(temp.string(), format)) failWrite(path, oneLine(buf.geterror()));
    if (std::rename(temp.c_str(), path.c_str()) != 0) failWrite(path, std::strerror(errno));
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
}

}  // namespace

void validateOutputPath(const std::string& path, OutputKind kind) {
  const std::string ext = lowerExtension(path);
  const std::string shown = ext.empty() ? "(none)" : "'" + ext + "'";
  if (kind == OutputKind::Aov && !isFloatFormat(ext))
    failWrite(path, "unsupported AOV format " + shown + " (use .exr)");
  if (kind == OutputKind::Image && !isLdrFormat(ext) && !isFloatFormat(ext) && ext != ".hdr")
    failWrite(path, "unsupported output format " + shown + " (use .png, .jpg or .exr)");

  const fs::path dir = directoryOf(path);
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    failWrite(path, "directory '" + dir.string() + "' does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    failWrite(path, "directory '" + dir.string() + "' is not writable: " + std::strerror(errno));
  if (fs::is_directory(path, ec)) failWrite(path, "it is a directory");
}

void writeImage(const std::string& path, const Film& film) {
  checkSize(path, film.width, film.height, 3, film.rgb.size());
  validateOutputPath(path, OutputKind::Image);
  if (!isLdrFormat(lowerExtension(path))) {
    writeAtomically(path, makeBuffer(film.width, film.height, 3, film.rgb.data()),
                    OIIO::TypeDesc::FLOAT);
    return;
  }
  // OpenImageIO writes floats to 8-bit formats without any transfer function, so encode
  // sRGB here (OpenImageIO's own formula), after clamping to the displayable range, in one
  // pass on all cores straight into the buffer OpenImageIO writes from.
  std::vector<float> srgb(film.rgb.size());
  const long long count = (long long)srgb.size();
  parallelFor(0LL, (long long)(count), [&](long long k) {
    const float v = film.rgb[k];
    srgb[k] = OIIO::linear_to_sRGB(std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f));
  });
  const OIIO::ImageBuf encoded(OIIO::ImageSpec(film.width, film.height, 3, OIIO::TypeDesc::FLOAT),
                               srgb.data());
  writeAtomically(path, encoded, OIIO::TypeDesc::UINT8);
}

void writeAov(const std::string& path, int width, int height, int channels,
              const std::vector<float>& data) {
  checkSize(path, width, height, channels, data.size());
  validateOutputPath(path, OutputKind::Aov);
  writeAtomically(path, makeBuffer(width, height, channels, data.data()), OIIO::TypeDesc::FLOAT);
}

ImageData readImage(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw RenderError("cannot read '" + path + "': " + oneLine(OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  ImageData image;
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.nchannels;
  image.pixels.resize(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
    throw RenderError("cannot read '" + path + "': " + oneLine(in->geterror()));
  return image;
}

}  // namespace gridrt
