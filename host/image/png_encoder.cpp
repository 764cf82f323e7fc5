#include "png_encoder.h"

#include <png.h>

#include <string>

#include "eight_bit_image.h"
#include "errors.h"

namespace gridrt {

std::vector<unsigned char> encodePng(const LayeredImage& image) {
  checkImage(image);
  const EightBitImage codes = eightBitImage(image, "png");

  // libpng's simplified writer: 8-bit values are written as they are, with an sRGB chunk.
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = png_uint_32(image.width);
  png.height = png_uint_32(image.height);
  png.format = codes.channels == 4 ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
  png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(png);  // room for any encoding, one pass
  std::vector<unsigned char> bytes(size);
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, codes.codes.data(), 0, nullptr))
    throw RenderError(std::string("PNG encoding failed: ") + png.message);
  bytes.resize(size);
  return bytes;
}

}  // namespace gridrt
