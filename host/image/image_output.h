// Image files in and out through OpenImageIO: the rendered film, AOVs (depth, primitive id,
// normals) and reading images back for tests and comparison tools.
//
// Writes are atomic: the image goes to a hidden temporary file in the target directory
// (keeping the real extension, so OpenImageIO picks the format), which is then renamed
// onto the path. On any error the temporary file is removed and a previous file at the
// path is left untouched. Every error is a one-line RenderError naming the file.
#pragma once
#include <string>
#include <vector>

#include "film.h"

namespace gridrt {

// What is about to be written: the formats allowed differ.
enum class OutputKind {
  Image,  // .png/.jpg/.jpeg (8-bit sRGB), .exr/.hdr/.tif/.tiff (linear float)
  Aov,    // .exr/.tif/.tiff only: float data must survive exactly
};

// Checks, before any rendering, that the extension is supported for `kind` and that the
// target directory exists and is writable. Throws RenderError otherwise.
void validateOutputPath(const std::string& path, OutputKind kind = OutputKind::Image);

// Writes the film by extension: .png/.jpg/.jpeg become 8-bit sRGB-encoded, clamped to
// [0,1] (NaN as 0); .exr, .hdr, .tif and .tiff keep linear float RGB.
void writeImage(const std::string& path, const Film& film);

// Writes a float image with any channel count (1 for depth or primitive id, 3 for normals)
// as 32-bit float, exactly (integers up to 2^24 survive). Row-major, row 0 = top,
// channels interleaved; data.size() must be width * height * channels.
void writeAov(const std::string& path, int width, int height, int channels,
              const std::vector<float>& data);

// Any image OpenImageIO can read (first subimage), converted to float.
struct ImageData {
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;  // row-major, row 0 = top, channels interleaved
};
ImageData readImage(const std::string& path);

}  // namespace gridrt
