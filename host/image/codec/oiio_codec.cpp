// The image module (image_codec.h): every image gridrt writes or reads goes through
// OpenImageIO here, encoded to memory (OpenImageIO's IOVecOutput) and decoded from files
// or memory. Built as a shared module that image_module.h loads on first use.
#include <OpenImageIO/color.h>
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "eight_bit_image.h"
#include "errors.h"
#include "image_codec.h"
#include "parallel_loops.h"

namespace gridrt {
namespace {

// OpenImageIO messages may span lines; ours are one line.
std::string oneLine(std::string message) {
  while (!message.empty() && message.back() == '\n') message.pop_back();
  std::replace(message.begin(), message.end(), '\n', ' ');
  return message.empty() ? "unknown OpenImageIO error" : message;
}

[[noreturn]] void fail(const std::string& reason) { throw RenderError(reason); }

// The encoder for `format`, writing into `bytes` through OpenImageIO's memory proxy.
std::vector<unsigned char> encodeToMemory(const std::string& format, const OIIO::ImageSpec& spec,
                                          OIIO::TypeDesc type, const void* pixels) {
  const std::string name = "image." + format;  // the extension picks the encoder
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(name);
  if (!out) fail(oneLine(OIIO::geterror()));
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  if (!out->set_ioproxy(&proxy)) fail(format + " cannot be written to memory");
  if (!out->open(name, spec) || !out->write_image(type, pixels) || !out->close())
    fail(oneLine(out->geterror()));
  return bytes;
}

// PNG and JPEG: the image's 8-bit codes (eight_bit_image.h), with alpha (PNG only) stored
// unassociated.
std::vector<unsigned char> encodeEightBit(const LayeredImage& image, const std::string& format) {
  const EightBitImage codes = eightBitImage(image, format);
  OIIO::ImageSpec spec(image.width, image.height, codes.channels, OIIO::TypeDesc::UINT8);
  if (codes.channels == 4) {
    spec.alpha_channel = 3;
    spec.attribute("oiio:UnassociatedAlpha", 1);  // as computed: OpenImageIO must not divide
  }
  return encodeToMemory(format, spec, OIIO::TypeDesc::UINT8, codes.codes.data());
}

OIIO::TypeDesc typeOf(SampleType type) {
  return type == SampleType::UInt ? OIIO::TypeDesc::UINT32 : OIIO::TypeDesc::FLOAT;
}

// EXR, TIFF and HDR: every channel's 32-bit values as they are (HDR: R, G, B only, and no
// alpha), with the data window. An alpha channel is associated alpha, OpenEXR's and TIFF's
// default: the colour holds no share of the background (layered_image.h).
std::vector<unsigned char> encodeChannels(const LayeredImage& image, const std::string& format) {
  std::vector<const ImageChannel*> channels;
  if (format == "hdr") {
    if (channelIndex(image, "A") >= 0) fail("hdr holds no alpha channel (use .exr or .tif)");
    for (const char* name : {"R", "G", "B"}) channels.push_back(&colourChannel(image, name));
  } else {
    for (const ImageChannel& c : image.channels) channels.push_back(&c);
  }
  const int nc = int(channels.size());
  OIIO::ImageSpec spec(image.width, image.height, nc, typeOf(channels[0]->type));
  spec.x = image.x;
  spec.y = image.y;
  spec.full_x = spec.full_y = 0;
  spec.full_width = image.full_width ? image.full_width : image.width;
  spec.full_height = image.full_width ? image.full_height : image.height;
  spec.channelnames.clear();
  bool mixed = false;
  for (const ImageChannel* c : channels) {
    spec.channelnames.push_back(c->name);
    mixed |= c->type != channels[0]->type;
  }
  if (mixed) {
    if (format != "exr") fail("channels of different types need .exr");
    for (const ImageChannel* c : channels) spec.channelformats.push_back(typeOf(c->type));
  }
  if (format == "hdr" && channels[0]->type != SampleType::Float) fail("HDR holds floats only");
  spec.alpha_channel = format == "hdr" ? -1 : channelIndex(image, "A");
  if (spec.alpha_channel >= 0)
    spec.attribute("gridrt:background", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::VEC3),
                   image.background.data());
  // Interleaved, each value as its 32 bits.
  const size_t pixels = size_t(image.width) * size_t(image.height);
  std::vector<uint32_t> data(pixels * nc);
  parallelFor(0LL, (long long)pixels, [&](long long p) {
    for (int c = 0; c < nc; ++c) {
      uint32_t& to = data[size_t(p) * nc + c];
      if (channels[c]->type == SampleType::UInt)
        to = channels[c]->uints[p];
      else
        std::memcpy(&to, &channels[c]->floats[p], 4);
    }
  });
  return encodeToMemory(format, spec, mixed ? OIIO::TypeDesc::UNKNOWN : spec.format, data.data());
}

std::vector<unsigned char> encode(const LayeredImage& image, const std::string& format) {
  checkImage(image);
  if (format == "png" || format == "jpg") return encodeEightBit(image, format);
  if (format == "exr" || format == "tif" || format == "hdr") return encodeChannels(image, format);
  fail("unsupported format '" + format + "'");
}

LayeredImage read(const std::string& path) {
  auto fail_read = [&](const std::string& why) { fail("cannot read '" + path + "': " + why); };
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
  if (!in) fail_read(oneLine(OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.depth > 1) fail_read("a volume image; gridrt reads flat images only");
  LayeredImage image;
  image.width = spec.width;
  image.height = spec.height;
  image.x = spec.x - spec.full_x;
  image.y = spec.y - spec.full_y;
  image.full_width = spec.full_width;
  image.full_height = spec.full_height;
  const size_t pixels = size_t(spec.width) * size_t(spec.height);
  for (int c = 0; c < spec.nchannels; ++c) {
    const OIIO::TypeDesc stored = spec.channelformat(c);
    const bool integer = stored == OIIO::TypeDesc::UINT32 || stored == OIIO::TypeDesc::INT32;
    ImageChannel channel{
        spec.channel_name(c), integer ? SampleType::UInt : SampleType::Float, {}, {}};
    void* to = nullptr;
    if (integer) {
      channel.uints.resize(pixels);
      to = channel.uints.data();
    } else {
      channel.floats.resize(pixels);
      to = channel.floats.data();
    }
    // Integers keep their 32 bits (an INT32 as the same bits); the rest become floats.
    if (!in->read_image(0, 0, c, c + 1, integer ? stored : OIIO::TypeDesc::FLOAT, to))
      fail_read(oneLine(in->geterror()));
    image.channels.push_back(std::move(channel));
  }
  const OIIO::ParamValue* background = spec.find_attribute("gridrt:background");
  // OpenEXR reads it back as a vector (a V3f): any three floats will do.
  if (background && background->type().basetype == OIIO::TypeDesc::FLOAT &&
      background->type().aggregate == OIIO::TypeDesc::VEC3 && background->type().arraylen == 0)
    std::memcpy(image.background.data(), background->data(), sizeof image.background);
  return image;
}

bool startsWith(const std::vector<unsigned char>& bytes, const char* signature, size_t n) {
  return bytes.size() >= n && std::memcmp(bytes.data(), signature, n) == 0;
}

// A file name whose extension makes OpenImageIO pick the decoder.
std::string decoderName(const std::vector<unsigned char>& bytes, const std::string& hint) {
  if (startsWith(bytes, "\x89PNG\r\n\x1a\n", 8)) return "image.png";
  if (startsWith(bytes, "\xff\xd8\xff", 3)) return "image.jpg";
  const size_t slash = hint.rfind('/');
  if (hint.rfind("image/", 0) == 0) return "image." + hint.substr(slash + 1);  // a MIME type
  return hint.empty() ? "image" : hint;
}

ImageData decode(const std::vector<unsigned char>& bytes, const std::string& format_hint,
                 const std::string& label, long long max_pixels) {
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
  auto in = OIIO::ImageInput::open(decoderName(bytes, format_hint), &config, &reader);
  if (!in) return refuse(oneLine(OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) return refuse("it has no pixels");
  if ((long long)spec.width * spec.height > max_pixels)
    return refuse(std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                  " pixels is more than the limit of " + std::to_string(max_pixels));
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

}  // namespace
}  // namespace gridrt

extern "C" __attribute__((visibility("default"))) const gridrt::ImageCodec* gridrt_image_codec() {
  static const gridrt::ImageCodec codec{&gridrt::encode, &gridrt::read, &gridrt::decode,
                                        &gridrt::srgbToLinear};
  return &codec;
}
