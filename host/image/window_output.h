// Writing one window of a larger image (gridrt --crop ... --crop-output window) so that
// the file itself says where the window lies: OpenImageIO's data window (ImageSpec x, y)
// inside the display window (full_width x full_height), which EXR stores natively and
// TIFF as its position tags. tools/merge_tiles pastes such files back together.
#pragma once
#include <string>
#include <vector>

#include "crop_window.h"

namespace gridrt {

// Writes the window's values (window.width() x window.height() pixels of `channels`
// 32-bit floats, row-major) at offset (x0, y0) of a full_width x full_height image.
// Atomic like host/image/image_output.h: a temporary sibling file renamed onto `path`.
// Throws RenderError naming the file.
void writeWindowImage(const std::string& path, const PixelWindow& window, int full_width,
                      int full_height, int channels, const std::vector<float>& data);

}  // namespace gridrt
