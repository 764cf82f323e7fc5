// KHR_draco_mesh_compression, decoded through Debian's libdraco before the loader reads
// the model: each TRIANGLES primitive with the extension is decoded from its buffer view,
// and its compressed attributes (the extension's `attributes` map: semantic -> Draco
// attribute id) and indices point to new accessors over the decoded data, in the component
// type, type and count the file's accessors declare (their other members, min and max
// included, are kept). The accessors of the file itself are left as they are. Attributes
// the extension does not list are read as usual, as the specification asks. A primitive
// without `indices` gets UNSIGNED_INT indices. Primitives of other modes are left to the
// loader, which skips them.
//
// Malformed Draco data, a point cloud, an attribute id the data lacks, counts or component
// counts unlike the accessors', or values the accessor's component type cannot hold are a
// SceneError naming the primitive.
#pragma once
#include <tiny_gltf.h>

#include <string>

namespace gridrt::gltf {

void decodeDracoPrimitives(tinygltf::Model& model, const std::string& label);

}  // namespace gridrt::gltf
