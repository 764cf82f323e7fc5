// The image file formats gridrt writes, what each can hold, and how a format is named: by
// a path's extension (-o out.png) or by name (--format png, for -o - where there is no
// extension).
#pragma once
#include <optional>
#include <string>

namespace gridrt {

enum class ImageFormat {
  Png,   // 8-bit sRGB, alpha
  Jpeg,  // 8-bit sRGB, no alpha (lossy)
  Exr,   // 32-bit float or unsigned int per channel, any channels, a data window
  Tiff,  // 32-bit float or unsigned int (one type for all channels), a data window
  Hdr,   // Radiance RGBE: RGB only, no alpha
};

// By extension, case-insensitive: .png, .jpg/.jpeg, .exr, .tif/.tiff, .hdr; nullopt else.
std::optional<ImageFormat> formatOfPath(const std::string& path);
// By --format name: png, jpg (or jpeg), exr; nullopt else.
std::optional<ImageFormat> formatNamed(const std::string& name);
// "png", "jpg", "exr", "tif", "hdr": the name the image module encodes by.
std::string formatName(ImageFormat format);

// 8-bit formats: the film is sRGB-encoded, clamped to [0, 1].
inline bool isEightBit(ImageFormat f) { return f == ImageFormat::Png || f == ImageFormat::Jpeg; }
// Formats that keep 32-bit floats (and integers) exactly: AOVs need one.
inline bool keepsFloats(ImageFormat f) { return f == ImageFormat::Exr || f == ImageFormat::Tiff; }
// Formats with an alpha channel (the film's coverage).
inline bool hasAlpha(ImageFormat f) {
  return f == ImageFormat::Png || f == ImageFormat::Exr || f == ImageFormat::Tiff;
}
// Formats whose files keep a data window (an offset inside a larger display window), so a
// window alone can be written.
inline bool keepsDataWindow(ImageFormat f) { return keepsFloats(f); }

}  // namespace gridrt
