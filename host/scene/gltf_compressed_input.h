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
//
// A large .glb's binary chunk is set aside the same way, compressed or not: tinygltf
// copies it into buffer 0 after zeroing a buffer of its size, both on one core (~130 of the
// 356 ms that loading a 93 MB scene took, 2 cores, AVX2, 2026-12-03); restoreCompressedInput
// copies it once, into memory faulted in on every core.
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
  // Buffer 0's bytes in the .glb's binary chunk, left out of `bytes` (null: not set aside).
  // They point into the caller's data, which must outlive restoreCompressedInput.
  const unsigned char* glb_binary = nullptr;
  size_t glb_binary_bytes = 0;
};

// A .glb's binary chunk is set aside from this size on (below it the copy costs little).
constexpr size_t kSetAsideBinaryBytes = size_t(1) << 20;

// `doc`: the file's JSON (of a .glb: its JSON chunk) as parsed from `data`. A file without
// either member, or a .glb whose chunks do not add up (tinygltf then says why), is left as
// it is. A .glb's binary chunk is set aside when it holds at least kSetAsideBinaryBytes, is
// well formed as tinygltf checks it, holds buffer 0 (no uri, byteLength within the chunk)
// and no image reads a buffer view (tinygltf hands those bytes to the image loader as it
// parses).
CompressedInput prepareCompressedInput(const nlohmann::json& doc, const unsigned char* data,
                                       size_t size, bool binary);

// Puts back what prepareCompressedInput took out of `model`, parsed from input.bytes.
void restoreCompressedInput(const CompressedInput& input, tinygltf::Model& model);

}  // namespace gridrt::gltf
