// The fuzz build embeds no kernels (cmake/EmbedKernelsScript.cmake generates the real
// function for gridrt itself); --version in the option fuzzer names that plainly.
namespace gridrt {
const char* embeddedKernelsDigest() { return "none (fuzz build: no kernels embedded)"; }
}  // namespace gridrt
