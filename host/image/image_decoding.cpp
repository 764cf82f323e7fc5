#include "image_decoding.h"

#include <OpenImageIO/color.h>
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>

#include "errors.h"

namespace gridrt {
namespace {

std::string oneLine(std::string message) {
  while (!message.empty() && message.back() == '\n') message.pop_back();
  std::replace(message.begin(), message.end(), '\n', ' ');
  return message.empty() ? "unknown OpenImageIO error" : message;
}

bool startsWith(const std::vector<unsigned char>& bytes, const char* signature, size_t n) {
  return bytes.size() >= n && std::memcmp(bytes.data(), signature, n) == 0;
}

// A file name whose extension makes OpenImageIO pick the decoder.
std::string formatName(const std::vector<unsigned char>& bytes, const std::string& hint) {
  if (startsWith(bytes, "\x89PNG\r\n\x1a\n", 8)) return "image.png";
  if (startsWith(bytes, "\xff\xd8\xff", 3)) return "image.jpg";
  const size_t slash = hint.rfind('/');
  if (hint.rfind("image/", 0) == 0) return "image." + hint.substr(slash + 1);  // a MIME type
  return hint.empty() ? "image" : hint;
}

}  // namespace

ImageData decodeImage(const std::vector<unsigned char>& bytes, const std::string& format_hint,
                      const std::string& label) {
  auto refuse = [&](const std::string& why) -> ImageData {
    throw RenderError(label + ": cannot decode the image: " + why);
  };
  if (bytes.empty()) return refuse("it has no data");
  OIIO::Filesystem::IOMemReader reader(bytes.data(), bytes.size());
  // glTF's colours are not premultiplied by their alpha: read them as stored.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  // With a configuration the readers take the proxy from it, not from the argument.
  OIIO::Filesystem::IOProxy* proxy = &reader;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  auto in = OIIO::ImageInput::open(formatName(bytes, format_hint), &config, &reader);
  if (!in) return refuse(oneLine(OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) return refuse("it has no pixels");
  if ((long long)spec.width * spec.height > kMaxDecodedPixels)
    return refuse(std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                  " pixels is more than the limit of " + std::to_string(kMaxDecodedPixels));
  ImageData image;
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.nchannels;
  image.pixels.resize(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
    return refuse(oneLine(in->geterror()));
  return image;
}

float srgbToLinear(float encoded) { return OIIO::sRGB_to_linear(encoded); }

}  // namespace gridrt
