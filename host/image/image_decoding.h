// Encoded images held in memory (a glTF file's PNG or JPEG textures) decoded through
// OpenImageIO, the project's one image decoder, and the sRGB transfer function it uses.
#pragma once
#include <string>
#include <vector>

#include "layered_image.h"

namespace gridrt {

// Images with more pixels than this are refused before their pixels are read: decoded to
// float RGBA with mip levels they take about 21 bytes a pixel, 1.4 GiB at this size.
constexpr long long kMaxDecodedPixels = 1LL << 26;

// Decodes `bytes` (the first subimage) into float pixels: 8- and 16-bit values to [0, 1]
// as stored, no colour conversion, colours not multiplied by alpha (as glTF stores them). The
// format comes from the bytes' signature (PNG, JPEG), else from `format_hint` (a MIME type such as
// "image/png" or a file name with an extension). Throws RenderError with a one-line message
// starting with `label` when the bytes cannot be decoded or the image is larger than
// kMaxDecodedPixels.
ImageData decodeImage(const std::vector<unsigned char>& bytes, const std::string& format_hint,
                      const std::string& label);

// The sRGB transfer function undone: an encoded value in [0, 1] to linear.
float srgbToLinear(float encoded);

}  // namespace gridrt
