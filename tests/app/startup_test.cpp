// Start-up: gridrt links no OpenImageIO; the image module (host/image/image_module.h) loads
// it the first time an image other than a PNG is read or written, so --version, --help,
// --list-devices and a render to PNG run without its ~250 libraries. The dynamic loader's own log
// (LD_DEBUG=libs) says what a run loaded.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "run_command.h"
#include "test_support.h"

namespace {

using gridrt::test::CommandResult;
using gridrt::test::gridrtBinary;
using gridrt::test::joinArgs;
using gridrt::test::runCommand;
using gridrt::test::tempPath;

// gridrt's arguments run with the loader logging every library it looks up (on stderr).
CommandResult runLoggingLibraries(const std::vector<std::string>& args) {
  std::vector<std::string> argv{"env", "LD_DEBUG=libs", gridrtBinary()};
  argv.insert(argv.end(), args.begin(), args.end());
  return runCommand(argv);
}

// The loader names each file it opens by its path: ".../libtbb.so.12".
bool loaded(const CommandResult& r, const std::string& library) {
  return r.err.find("/" + library) != std::string::npos;
}

TEST(Startup, VersionHelpAndDeviceListLoadNoImageLibrary) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"--version"}, {"--help"}, {"--list-devices"}}) {
    CommandResult r = runLoggingLibraries(args);
    ASSERT_TRUE(r.exit_code == 0 || args[0] == "--list-devices") << joinArgs(args) << r.err;
    ASSERT_TRUE(loaded(r, "libtbb")) << "the loader's log is missing: " << r.err.substr(0, 500);
    EXPECT_FALSE(loaded(r, "libOpenImageIO")) << joinArgs(args) << " loaded OpenImageIO";
    EXPECT_FALSE(loaded(r, "gridrt_image_codec")) << joinArgs(args);
  }
}

// PNG, the default output, is written with libpng (png_encoder.h); other formats load the
// module.
TEST(Startup, WritingAPngLoadsNoImageModuleAndAnExrLoadsIt) {
  for (const char* name : {"startup.png", "startup.exr"}) {
    const std::string out = tempPath(name);
    CommandResult r =
        runLoggingLibraries({"-q", "--width", "16", "--height", "12", "--primary-only", "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.err.substr(r.err.size() > 2000 ? r.err.size() - 2000 : 0);
    ASSERT_TRUE(loaded(r, "libtbb")) << "the loader's log is missing: " << r.err.substr(0, 500);
    const bool png = std::string(name).find(".png") != std::string::npos;
    EXPECT_EQ(loaded(r, "gridrt_image_codec"), !png) << name;
    EXPECT_EQ(loaded(r, "libOpenImageIO"), !png) << name;
    EXPECT_TRUE(gridrt::test::fileExists(out)) << name;
  }
}

}  // namespace
