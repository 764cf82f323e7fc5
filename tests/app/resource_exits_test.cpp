// The exits no ordinary run reaches, forced through the environment: a kernel that does not
// build (GRIDRT_KERNEL_OPTIONS) and a scene whose own data does not fit the device
// (GRIDRT_MAX_BUFFER_BYTES), and no device at all (POCL_CACHE_DIR, OCL_ICD_VENDORS). Each is
// exit 1 with one line naming the problem.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "run_command.h"
#include "test_support.h"

namespace gridrt {
namespace {

// Runs gridrt on bunny_res4 with one environment variable set for it.
test::CommandResult runWith(const char* variable, const std::string& value) {
  setenv(variable, value.c_str(), 1);
  test::CommandResult r = test::runCommand(
      {test::gridrtBinary(), test::modelScene("bunny_res4.glb"), "-q", "--width", "32", "--height",
       "24", "-o", test::tempPath(std::string(variable) + ".png")});
  unsetenv(variable);
  return r;
}

void expectOneLine(const test::CommandResult& r, int exit_code, const std::string& text) {
  EXPECT_EQ(r.exit_code, exit_code) << r.err;
  EXPECT_EQ(r.err.rfind("gridrt: ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
  EXPECT_NE(r.err.find(text), std::string::npos) << r.err;
}

// No device: the line says the likeliest cause. PoCL that cannot make its cache folder
// (here a path under a regular file, which even root cannot create) reports no device at
// all; no driver installed (the ICD loader pointed at an empty vendors folder) asks for one.
TEST(ResourceExits, NoDeviceSaysWhy) {
  const test::CommandResult cache = runWith("POCL_CACHE_DIR", "/etc/passwd/pocl-cache");
  expectOneLine(cache, 1, "POCL_CACHE_DIR");
  EXPECT_NE(cache.err.find("'/etc/passwd/pocl-cache'"), std::string::npos) << cache.err;
  EXPECT_EQ(cache.err.find("install"), std::string::npos) << "PoCL is installed: " << cache.err;

  const std::string empty = test::tempPath("no_vendors");
  ASSERT_EQ(std::system(("mkdir -p '" + empty + "'").c_str()), 0);
  const test::CommandResult none = runWith("OCL_ICD_VENDORS", empty);
  expectOneLine(none, 1, "install an OpenCL driver");

  setenv("POCL_CACHE_DIR", "/etc/passwd/pocl-cache", 1);
  const test::CommandResult listed = test::runCommand({test::gridrtBinary(), "--list-devices"});
  unsetenv("POCL_CACHE_DIR");
  expectOneLine(listed, 1, "POCL_CACHE_DIR");
}

TEST(ResourceExits, AKernelThatDoesNotBuildNamesTheKernelAndTheCompilersWords) {
  // An unbalanced parenthesis in a macro every kernel uses: a compile error in each.
  const test::CommandResult r = runWith("GRIDRT_KERNEL_OPTIONS", "-DGR_PE_LOCAL_SIZE=(");
  expectOneLine(r, 1, "building kernel '");
  EXPECT_NE(r.err.find("failed (CL_BUILD_PROGRAM_FAILURE)"), std::string::npos) << r.err;
}

TEST(ResourceExits, SceneDataTooLargeForTheDeviceIsRefusedWithTheSizes) {
  // bunny_res4's 948 triangles take more than 4 KiB in one buffer.
  const test::CommandResult r = runWith("GRIDRT_MAX_BUFFER_BYTES", "4096");
  expectOneLine(r, 1, "in one buffer, more than the device allows (4 KiB)");
}

TEST(ResourceExits, AMalformedLimitIsRefused) {
  expectOneLine(runWith("GRIDRT_MAX_BUFFER_BYTES", "lots"), 1,
                "GRIDRT_MAX_BUFFER_BYTES: expected a positive number of bytes, got 'lots'");
}

}  // namespace
}  // namespace gridrt
