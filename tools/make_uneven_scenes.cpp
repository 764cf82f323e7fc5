// make_uneven_scenes MODEL OUTDIR [ROW_COUNT]: writes the family of uneven scenes around a
// dense model (tools/uneven_scenes.h; the model e.g. scenes/models/bunny.glb or
// bunny_res4.glb) as binary glTF: floor_1x.glb, floor_10x.glb, floor_100x.glb,
// floor_1000x.glb, scattered.glb, row.glb (ROW_COUNT copies, default 16), huge_triangle.glb.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "gltf_loader.h"
#include "gltf_writer.h"
#include "uneven_scenes.h"

int main(int argc, char** argv) {
  if (argc != 3 && argc != 4) {
    std::fprintf(stderr, "usage: make_uneven_scenes MODEL OUTDIR [ROW_COUNT]\n");
    return 2;
  }
  try {
    const gridrt::Scene model = gridrt::loadGltfFile(argv[1]);
    std::filesystem::path dir(argv[2]);
    std::filesystem::create_directories(dir);
    const int row_count = argc == 4 ? std::stoi(argv[3]) : 16;
    for (const auto& [name, scene] : gridrt::unevenScenes(model, row_count)) {
      const std::filesystem::path path = dir / (name + ".glb");
      gridrt::writeGltf(scene, path.string());
      std::printf("%s: %zu triangles, %ju bytes\n", path.string().c_str(), scene.triangleCount(),
                  static_cast<uintmax_t>(std::filesystem::file_size(path)));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_uneven_scenes: %s\n", e.what());
    return 1;
  }
  return 0;
}
