// Helpers the tests have in common: paths of the source tree, the model scenes and the binary.
#pragma once
#include <cstring>
#include <functional>
#include <glm/glm.hpp>
#include <string>
#include <type_traits>
#include <vector>

#include "gridrt_types.h"

namespace gridrt::test {

std::string sourcePath(const std::string& relative);  // <repo>/relative
std::string modelScene(const std::string& name);      // <repo>/scenes/models/name
std::string gridrtBinary();                           // build/gridrt
std::string tempPath(const std::string& name);        // a fresh path under a per-test temp dir
bool fileExists(const std::string& path);

// Whether two values are the same bits (floats: -0 differs from +0, and a NaN equals
// itself; a struct of floats, such as a ray, field by field).
template <typename T>
bool sameBits(const T& a, const T& b) {
  static_assert(std::is_trivially_copyable_v<T>, "compared as bytes");
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// An empty directory of its own (under the per-process temp dir), so a test's listings
// see only that test's files; and the sorted names in a directory.
std::string freshDir(const std::string& name);
std::vector<std::string> listDir(const std::string& dir);

// The message of the `Error` `f` throws, or "<no error>".
template <typename Error>
std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "<no error>";
}

// `bytes` in base64 (RFC 4648, with padding), for data URIs in glTF documents made by tests.
std::string base64(const std::string& bytes);

// The bytes of `values` as they lie in memory: a glTF buffer's contents.
template <typename T>
std::string bytesOf(const std::vector<T>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// Rays where `got` differs from `want`: another primitive, or another t bit for bit.
// Reports the first difference as a test failure naming `label`.
size_t hitMismatches(const std::vector<GrHit>& want, const std::vector<GrHit>& got,
                     const std::string& label);

// The scalar ray/triangle test of a prepared triangle's layout (prepareTriangle), on one ray.
int intersectScalar(const GrTriangle& tri, const glm::vec3& o, const glm::vec3& d, float* t,
                    float* u, float* v);

}  // namespace gridrt::test
