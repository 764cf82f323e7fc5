#include "image_decoding.h"

#include "image_module.h"

namespace gridrt {

ImageData decodeImage(const std::vector<unsigned char>& bytes, const std::string& format_hint,
                      const std::string& label) {
  return imageCodec().decode(bytes, format_hint, label, kMaxDecodedPixels);
}

float srgbToLinear(float encoded) { return imageCodec().srgb_to_linear(encoded); }

}  // namespace gridrt
