#include "image_output.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "errors.h"
#include "image_module.h"
#include "png_encoder.h"

namespace gridrt {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void failWrite(const std::string& path, const std::string& reason) {
  throw RenderError("cannot write '" + path + "': " + reason);
}

fs::path directoryOf(const std::string& path) {
  fs::path dir = fs::path(path).parent_path();
  return dir.empty() ? fs::path(".") : dir;
}

std::string extensionShown(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  return ext.empty() ? "(none)" : "'" + ext + "'";
}

void writeToStandardOutput(const std::vector<unsigned char>& bytes) {
  if (std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size() ||
      std::fflush(stdout) != 0)
    throw RenderError(std::string("cannot write to standard output: ") + std::strerror(errno));
}

// `bytes` to a hidden sibling of `path`, then renamed onto it. On failure the temporary
// file is removed and whatever was at `path` stays as it was.
void writeAtomically(const std::string& path, const std::vector<unsigned char>& bytes) {
  static std::atomic<unsigned> counter{0};  // distinct names for concurrent writers
  const fs::path target(path);
  const fs::path temp =
      directoryOf(path) / ("." + target.filename().string() + ".tmp" + std::to_string(::getpid()) +
                           "-" + std::to_string(counter++));
  try {
    {
      std::ofstream out(temp, std::ios::binary);
      if (!out) failWrite(path, std::strerror(errno));
      out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
      out.close();
      if (!out) failWrite(path, std::strerror(errno));
    }
    if (std::rename(temp.c_str(), path.c_str()) != 0) failWrite(path, std::strerror(errno));
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
}

}  // namespace

ImageFormat validateOutputPath(const std::string& path, OutputKind kind,
                               std::optional<ImageFormat> format) {
  const bool to_stdout = path == kStandardOutput;
  if (to_stdout && !format) failWrite(path, "standard output needs a format named");
  if (!format) format = formatOfPath(path);
  const std::string shown = to_stdout ? "'" + formatName(*format) + "'" : extensionShown(path);
  if (kind == OutputKind::Layers && format != ImageFormat::Exr)
    failWrite(path, "unsupported multi-layer format " + shown + " (use .exr)");
  if (kind == OutputKind::Aov && !(format && keepsFloats(*format)))
    failWrite(path, "unsupported AOV format " + shown + " (use .exr)");
  if (!format) failWrite(path, "unsupported output format " + shown + " (use .png, .jpg or .exr)");
  if (to_stdout) return *format;

  const fs::path dir = directoryOf(path);
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    failWrite(path, "directory '" + dir.string() + "' does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    failWrite(path, "directory '" + dir.string() + "' is not writable: " + std::strerror(errno));
  if (fs::is_directory(path, ec)) failWrite(path, "it is a directory");
  return *format;
}

void writeLayeredImage(const std::string& path, const LayeredImage& image, OutputKind kind,
                       std::optional<ImageFormat> format) {
  const ImageFormat chosen = validateOutputPath(path, kind, format);
  std::vector<unsigned char> bytes;
  try {
    // PNG, the default output, without the image module's libraries (png_encoder.h).
    bytes = chosen == ImageFormat::Png ? encodePng(image)
                                       : imageCodec().encode(image, formatName(chosen));
  } catch (const RenderError& e) {
    failWrite(path, e.what());
  }
  if (path == kStandardOutput)
    writeToStandardOutput(bytes);
  else
    writeAtomically(path, bytes);
}

LayeredImage filmImage(const Film& film) {
  LayeredImage image;
  image.width = film.width;
  image.height = film.height;
  for (int c = 0; c < 3; ++c) {
    image.channels.push_back(floatChannel(std::string(1, "RGB"[c]), film.rgb, 3, c));
    image.background[c] = film.background[c];
  }
  if (film.alpha.empty()) return image;
  // Associated with the alpha (layered_image.h): the background's share taken out.
  for (int c = 0; c < 3; ++c) {
    std::vector<float>& colour = image.channels[c].floats;
    for (size_t p = 0; p < colour.size(); ++p) {
      const float a = film.alpha[p];
      colour[p] = a <= 0.0f   ? 0.0f
                  : a >= 1.0f ? colour[p]
                              : colour[p] - (1.0f - a) * image.background[c];
    }
  }
  image.channels.push_back({"A", SampleType::Float, film.alpha, {}});
  return image;
}

void writeImage(const std::string& path, const Film& film, std::optional<ImageFormat> format) {
  if (film.rgb.size() != size_t(std::max(film.width, 0)) * size_t(std::max(film.height, 0)) * 3)
    failWrite(path, "image is " + std::to_string(film.width) + "x" + std::to_string(film.height) +
                        " with 3 channels but has " + std::to_string(film.rgb.size()) + " values");
  writeLayeredImage(path, filmImage(film), OutputKind::Image, format);
}

void writeAov(const std::string& path, int width, int height, int channels,
              const std::vector<float>& data) {
  if (channels <= 0 || data.size() != size_t(std::max(width, 0)) * std::max(height, 0) * channels)
    failWrite(path, "image is " + std::to_string(width) + "x" + std::to_string(height) + " with " +
                        std::to_string(channels) + " channels but has " +
                        std::to_string(data.size()) + " values");
  LayeredImage image;
  image.width = width;
  image.height = height;
  for (int c = 0; c < channels; ++c) {
    const std::string name = channels == 1   ? std::string("Y")
                             : channels == 3 ? std::string(1, "RGB"[c])
                                             : "C" + std::to_string(c);
    image.channels.push_back(floatChannel(name, data, channels, c));
  }
  writeLayeredImage(path, image, OutputKind::Aov);
}

LayeredImage readLayeredImage(const std::string& path) { return imageCodec().read(path); }

ImageData readImage(const std::string& path) {
  const LayeredImage image = readLayeredImage(path);
  ImageData data;
  data.width = image.width;
  data.height = image.height;
  data.channels = int(image.channels.size());
  const size_t pixels = size_t(image.width) * size_t(image.height);
  data.pixels.resize(pixels * image.channels.size());
  for (size_t c = 0; c < image.channels.size(); ++c) {
    const ImageChannel& channel = image.channels[c];
    for (size_t p = 0; p < pixels; ++p)
      data.pixels[p * data.channels + c] =
          channel.type == SampleType::UInt ? float(int32_t(channel.uints[p])) : channel.floats[p];
  }
  return data;
}

}  // namespace gridrt
