// Image files in and out: the rendered film, AOVs (depth, primitive id, normals), several
// of them as the layers of one EXR, and reading images back for tests and tools. The
// encoding is the image module's (image_codec.h, OpenImageIO, loaded on first use); one
// writer, writeLayeredImage, makes every file.
//
// Writes to a path are atomic: the file's bytes go to a hidden temporary file in the
// target directory, which is then renamed onto the path. On any error the temporary file
// is removed and a previous file at the path is left untouched. The path "-" is standard
// output (the format named, since there is no extension). Every error is a one-line
// RenderError naming the file.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "film.h"
#include "image_format.h"
#include "layered_image.h"
#include "standard_streams.h"

namespace gridrt {

// What is about to be written: the formats allowed differ.
enum class OutputKind {
  Image,   // .png/.jpg/.jpeg (8-bit sRGB), .exr/.hdr/.tif/.tiff (linear float)
  Aov,     // .exr/.tif/.tiff only: float data and 32-bit ids must survive exactly
  Layers,  // .exr only: channels of different types in one file
};

// The format of `path` for `kind`: `named` (--format) if given, which must then agree
// with the extension; else the extension's. Checks, before any rendering, that the format
// suits `kind` and that the target directory exists and is writable (nothing to check for
// standard output, which needs `named`). Throws RenderError otherwise.
ImageFormat validateOutputPath(const std::string& path, OutputKind kind = OutputKind::Image,
                               std::optional<ImageFormat> named = std::nullopt);

// Encodes `image` as `format` (the path's, when not given) and writes it to `path`.
void writeLayeredImage(const std::string& path, const LayeredImage& image, OutputKind kind,
                       std::optional<ImageFormat> format = std::nullopt);

// The film as R, G, B and, where it has alpha, A, with the colour associated with it
// (layered_image.h): .png/.jpg/.jpeg 8-bit sRGB-encoded, clamped to [0,1] (NaN as 0);
// .exr, .hdr, .tif and .tiff linear float; alpha only in .png, .exr, .tif and .tiff.
// docs/output.md says what the colour holds where alpha is below 1.
LayeredImage filmImage(const Film& film);
void writeImage(const std::string& path, const Film& film,
                std::optional<ImageFormat> format = std::nullopt);

// Writes a float image with any channel count (1 for depth, 3 for normals) as 32-bit
// float, exactly. Row-major, row 0 = top, channels interleaved; data.size() must be
// width * height * channels. Channels Y (one), R, G, B (three), else C0, C1, ...
void writeAov(const std::string& path, int width, int height, int channels,
              const std::vector<float>& data);

// Every channel of a file's first subimage, as the image module reads it (image_codec.h).
LayeredImage readLayeredImage(const std::string& path);
// Any image (first subimage), every channel as float, interleaved: 32-bit integer
// channels read as signed (2^32 - 1 is -1, a miss), exact up to 2^24.
ImageData readImage(const std::string& path);

}  // namespace gridrt
