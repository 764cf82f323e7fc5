#include "test_support.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>

#include "moller_trumbore.h"
#include "watertight.h"

namespace gridrt::test {

std::string sourcePath(const std::string& relative) {
  return std::string(GRIDRT_SOURCE_DIR) + "/" + relative;
}

std::string modelScene(const std::string& name) { return sourcePath("scenes/models/" + name); }

std::string gridrtBinary() { return GRIDRT_BINARY; }

namespace {
// The per-process temporary directory, removed when the test process exits.
struct TempDir {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("gridrt_test_" + std::to_string(::getpid()));
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};
}  // namespace

std::string tempPath(const std::string& name) {
  static TempDir dir;
  std::filesystem::create_directories(dir.path);
  return (dir.path / name).string();
}

bool fileExists(const std::string& path) { return std::filesystem::exists(path); }

std::string freshDir(const std::string& name) {
  std::string dir = tempPath(name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::vector<std::string> listDir(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

size_t hitMismatches(const std::vector<GrHit>& want, const std::vector<GrHit>& got,
                     const std::string& label) {
  size_t bad = 0;
  for (size_t i = 0; i < want.size(); ++i) {
    bool same = want[i].prim == got[i].prim &&
                (want[i].prim < 0 || std::memcmp(&want[i].t, &got[i].t, sizeof(float)) == 0);
    if (!same && bad++ == 0)
      ADD_FAILURE() << label << ": ray " << i << " want prim " << want[i].prim << " t " << want[i].t
                    << ", got prim " << got[i].prim << " t " << got[i].t;
  }
  return bad;
}

int intersectScalar(const GrTriangle& tri, const glm::vec3& o, const glm::vec3& d, float* t,
                    float* u, float* v) {
  if (tri.vertex_layout)
    return gr_intersect_watertight_vertices(o.x, o.y, o.z, d.x, d.y, d.z, tri.v0x, tri.v0y, tri.v0z,
                                            tri.e1x, tri.e1y, tri.e1z, tri.e2x, tri.e2y, tri.e2z, t,
                                            u, v);
  return gr_intersect_mt(o.x, o.y, o.z, d.x, d.y, d.z, tri.v0x, tri.v0y, tri.v0z, tri.e1x, tri.e1y,
                         tri.e1z, tri.e2x, tri.e2y, tri.e2z, t, u, v);
}

std::string base64(const std::string& bytes) {
  static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    uint32_t v = 0;
    for (size_t k = 0; k < 3; ++k) v = v << 8 | (k < n ? uint8_t(bytes[i + k]) : 0u);
    for (size_t k = 0; k < 4; ++k) out += k <= n ? kDigits[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

}  // namespace gridrt::test
