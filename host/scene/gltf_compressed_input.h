// Compressed glTF files as tinygltf 2.7 can parse them. Two members of such files make
// tinygltf refuse the file before the decoders (gltf_draco.h, gltf_meshopt.h) see it:
// - the `indices` accessor of a KHR_draco_mesh_compression primitive has no buffer view,
//   and tinygltf requires one for indices;
// - EXT_meshopt_compression's placeholder buffers have no `uri` (only a byteLength for the
//   decoded data), and tinygltf reads every buffer: in a .gltf a missing uri is an error,
//   in a .glb it copies the BIN chunk, or fails where the placeholder is longer.
// prepareCompressedInput takes them out of the file; restoreCompressedInput puts them back
// into the parsed model: the indices, and each placeholder as an empty buffer (the
// decoders write the decoded data to new buffers of their own).
#pragma once
#include <tiny_gltf.h>

#include <cstddef>
#include <nlohmann/json.hpp>
#include <vector>

namespace gridrt::gltf {

struct CompressedInput {
  std::vector<unsigned char> bytes;  // the file to parse instead; empty: the original
  struct LiftedIndices {
    size_t mesh = 0, primitive = 0;
    int accessor = -1;
  };
  std::vector<LiftedIndices> draco_indices;
  std::vector<size_t> placeholder_buffers;
};

// `doc`: the file's JSON (of a .glb: its JSON chunk) as parsed from `data`. A file without
// either member, or a .glb whose chunks do not add up (tinygltf then says why), is left as
// it is.
CompressedInput prepareCompressedInput(const nlohmann::json& doc, const unsigned char* data,
                                       size_t size, bool binary);

// Puts back what prepareCompressedInput took out of `model`, parsed from input.bytes.
void restoreCompressedInput(const CompressedInput& input, tinygltf::Model& model);

}  // namespace gridrt::gltf
