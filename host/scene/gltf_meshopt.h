// EXT_meshopt_compression, decoded through Debian's libmeshoptimizer before the loader
// reads the model: each buffer view with the extension is decoded from the compressed
// range the extension names (mode ATTRIBUTES, TRIANGLES or INDICES; for ATTRIBUTES the
// filter NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL applied after decoding) into a new
// buffer, and the view points to it; accessors, animations and everything else then read
// it as they read any view. A placeholder (fallback) buffer without data stays empty.
//
// Every rule the specification lists for the extension object is checked (strides, counts,
// modes against filters, the view's byteLength equal to count * byteStride); a broken rule
// or data the decoder refuses is a SceneError naming the buffer view.
#pragma once
#include <tiny_gltf.h>

#include <string>

namespace gridrt::gltf {

// No valid stream decodes to more than this many bytes per compressed byte (the attribute
// codec's best case, 16 zero bytes in 2 header bits, is 64); a view that claims more is
// refused before its decoded size is allocated.
constexpr size_t kMaxMeshoptExpansion = 64;

void decodeMeshoptViews(tinygltf::Model& model, const std::string& label);

}  // namespace gridrt::gltf
