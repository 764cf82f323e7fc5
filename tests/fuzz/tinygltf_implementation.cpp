// tinygltf compiled into the fuzzers themselves (instead of linking Debian's shared
// libtinygltf) so that its parser is instrumented too: coverage guides the fuzzer through
// it and the sanitizers see its memory accesses. Images are never decoded by gridrt
// (gltf_loader.cpp installs a loader that ignores them), so no stb_image is needed.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
