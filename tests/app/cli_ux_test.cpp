// The command line's conveniences: the progress bar (only on a terminal), --crop parsing,
// --device by plain index, the quick refusal of absurd image sizes, and the tracing time
// split by ray kind in --stats-json.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "crop_window.h"
#include "errors.h"
#include "memory_estimate.h"
#include "options.h"
#include "progress.h"
#include "run_command.h"
#include "test_support.h"

namespace {

using gridrt::test::CommandResult;
using gridrt::test::gridrtBinary;
using gridrt::test::joinArgs;
using gridrt::test::runCommand;
using gridrt::test::tempPath;

gridrt::Options parse(std::vector<std::string> words) {
  words.insert(words.begin(), "gridrt");
  std::vector<const char*> argv;
  for (const auto& w : words) argv.push_back(w.c_str());
  return *gridrt::parseCommandLine(int(argv.size()), argv.data());
}

bool haveDevice() { return gridrt::test::gridrtHasDevice(); }

// Sets an environment variable for this process and the commands it runs, until the end of
// the scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (old_)
      setenv(name_, old_->c_str(), 1);
    else
      unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// --- progress -------------------------------------------------------------------------------

TEST(Progress, LineShowsBarPercentElapsedAndRemaining) {
  std::string line = gridrt::formatProgressLine(0.5, 1.25, 1.25);
  EXPECT_EQ(line, "gridrt: [############............]  50%  1.2 s elapsed, about 1.2 s left");
  EXPECT_NE(gridrt::formatProgressLine(1.0, 75.0, 0.0).find("1 min 15 s elapsed"),
            std::string::npos);
}

TEST(Progress, FractionIsClampedAndRemainingNeverNegative) {
  std::string line = gridrt::formatProgressLine(1.7, 2.0, -3.0);
  EXPECT_NE(line.find("100%"), std::string::npos) << line;
  EXPECT_NE(line.find("about 0.0 s left"), std::string::npos) << line;
}

// With no delay the bar would be drawn at the first update of any render: off a terminal
// there is still none, only the closing summary.
TEST(Progress, NothingButTheSummaryWhenStderrIsNotATerminal) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  ScopedEnv no_delay("GRIDRT_PROGRESS_DELAY", "0");
  CommandResult r = runCommand(
      {gridrtBinary(), "--width", "64", "--height", "48", "-o", tempPath("quiet_progress.png")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("elapsed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Mrays/s"), std::string::npos) << "the closing summary is kept: " << r.err;
}

bool haveScript() { return std::system("command -v script >/dev/null 2>&1") == 0; }

// util-linux `script` runs the command on a pseudo-terminal, where the bar must appear
// (with no delay, whatever the render's length) and be erased before the summary.
TEST(Progress, BarIsDrawnOnATerminal) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  if (!haveScript()) GTEST_SKIP() << "util-linux 'script' is not installed (a pseudo-terminal)";
  ScopedEnv no_delay("GRIDRT_PROGRESS_DELAY", "0");
  std::string command =
      gridrtBinary() + " --width 64 --height 48 -o " + tempPath("tty_progress.png");
  CommandResult r = runCommand({"script", "-qec", command, "/dev/null"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("elapsed, about"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\r\033[K"), std::string::npos) << "the bar is erased: " << r.out;
  EXPECT_NE(r.out.find("Mrays/s"), std::string::npos) << r.out;
}

// Ctrl-C (SIGINT) while the bar is drawn ends its line before the program dies of the
// signal, so the shell's prompt does not start in the middle of the bar.
TEST(Progress, InterruptEndsTheBarsLine) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  if (!haveScript()) GTEST_SKIP() << "util-linux 'script' is not installed (a pseudo-terminal)";
  ScopedEnv no_delay("GRIDRT_PROGRESS_DELAY", "0");
  const std::string command = "timeout --preserve-status -s INT 3 " + gridrtBinary() +
                              " --width 320 --height 240 --repeat 100000 -o " +
                              tempPath("tty_interrupted.png");
  CommandResult r = runCommand({"script", "-qec", command, "/dev/null"});
  EXPECT_EQ(r.exit_code, 128 + 2) << "dies of SIGINT: " << r.out << r.err;
  const size_t last_bar = r.out.rfind("left");
  ASSERT_NE(last_bar, std::string::npos) << "the bar was drawn: " << r.out;
  EXPECT_NE(r.out.find('\n', last_bar), std::string::npos)
      << "the bar's line is ended: " << r.out.substr(last_bar);
}

TEST(Progress, QuietSuppressesTheBarOnATerminalToo) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  if (!haveScript()) GTEST_SKIP() << "util-linux 'script' is not installed (a pseudo-terminal)";
  ScopedEnv no_delay("GRIDRT_PROGRESS_DELAY", "0");
  std::string command =
      gridrtBinary() + " -q --width 64 --height 48 -o " + tempPath("tty_quiet.png");
  CommandResult r = runCommand({"script", "-qec", command, "/dev/null"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.out.find("elapsed"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find('\r'), std::string::npos) << r.out;
}

TEST(Progress, WantedOnlyOnATerminalThatRedrawsAndWithoutQuiet) {
  EXPECT_TRUE(gridrt::progressWanted(false, true, "xterm-256color"));
  EXPECT_TRUE(gridrt::progressWanted(false, true, nullptr));
  EXPECT_FALSE(gridrt::progressWanted(true, true, "xterm-256color"));
  EXPECT_FALSE(gridrt::progressWanted(false, false, "xterm-256color"));
  EXPECT_FALSE(gridrt::progressWanted(false, true, "dumb"));
}

TEST(Progress, DelayComesFromTheEnvironmentWhenItIsANumber) {
  {
    ScopedEnv delay("GRIDRT_PROGRESS_DELAY", "0");
    EXPECT_EQ(gridrt::progressDelaySeconds(), 0.0);
  }
  {
    ScopedEnv delay("GRIDRT_PROGRESS_DELAY", "2.5");
    EXPECT_EQ(gridrt::progressDelaySeconds(), 2.5);
  }
  for (const char* bad : {"", "soon", "-1", "1s"}) {
    ScopedEnv delay("GRIDRT_PROGRESS_DELAY", bad);
    EXPECT_EQ(gridrt::progressDelaySeconds(), gridrt::kProgressDelayS) << bad;
  }
}

// --- --crop ---------------------------------------------------------------------------------

TEST(CropOption, ParsesHalfOpenBoundsInsideTheImage) {
  gridrt::Options o = parse({"--width", "64", "--height", "48", "--crop", "0,8,64,48"});
  ASSERT_TRUE(o.crop);
  EXPECT_EQ(o.crop->x0, 0);
  EXPECT_EQ(o.crop->y0, 8);
  EXPECT_EQ(o.crop->width(), 64);
  EXPECT_EQ(o.crop->height(), 40);
  EXPECT_EQ(o.crop_output, gridrt::CropOutput::Full);
}

TEST(CropOption, RefusesMalformedEmptyOrOutsideWindows) {
  for (const char* bad : {"1,2,3", "a,b,c,d", "0,0,0,10", "5,0,4,10", "0,0,65,48", "0,0,64,49",
                          "-1,0,10,10", "0,0,99999999999,10", "0,0,10,10,10", " 0,0,10,10"}) {
    EXPECT_THROW(parse({"--width", "64", "--height", "48", "--crop", bad}), gridrt::UsageError)
        << bad;
  }
}

TEST(CropOption, WindowOutputNeedsAFormatWithADataWindow) {
  EXPECT_THROW(parse({"--crop", "0,0,8,8", "--crop-output", "window", "-o", "a.png"}),
               gridrt::UsageError);
  EXPECT_THROW(parse({"--crop", "0,0,8,8", "--crop-output", "tile"}), gridrt::UsageError);
  EXPECT_NO_THROW(parse({"--crop", "0,0,8,8", "--crop-output", "window", "-o", "a.EXR"}));
}

TEST(CropOption, BadWindowOnTheCommandLineExitsWithUsageCode) {
  CommandResult r = runCommand({gridrtBinary(), "--crop", "0,0,700,10"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.rfind("gridrt: --crop:", 0), 0u) << r.err;
}

// --- resources and devices ------------------------------------------------------------------

// Refused before anything is loaded: a scene that does not exist is never opened.
TEST(Resources, HugeImageIsRefusedBeforeTheSceneIsLoadedWithOneLine) {
  const std::string out = tempPath("huge.png");
  CommandResult r = runCommand({gridrtBinary(), tempPath("no_such_scene.glb"), "--width", "65536",
                                "--height", "65536", "-o", out});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err.rfind("gridrt: image 65536x65536", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// The need it states counts what --transfer copy keeps on the host beside the device's
// buffers: one pass's device bytes more than the mapped batches need.
TEST(Resources, CopiedBatchesAddTheirHostArraysToTheStatedNeed) {
  auto neededMiB = [](const std::vector<std::string>& extra) {
    std::vector<std::string> argv{
        gridrtBinary(), tempPath("no_such_scene.glb"), "--width", "65536", "--height", "65536",
        "-o",           tempPath("huge.png")};
    argv.insert(argv.end(), extra.begin(), extra.end());
    const CommandResult r = runCommand(argv);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    const size_t at = r.err.find("needs about ");
    EXPECT_NE(at, std::string::npos) << r.err;
    return at == std::string::npos ? -1.0 : std::stod(r.err.substr(at + 12));
  };
  const double mapped = neededMiB({}), copied = neededMiB({"--transfer", "copy"});
  const double pass_mib = gridrt::estimateMemory(65536, 65536, 1).device_bytes / (1 << 20);
  EXPECT_NEAR(copied - mapped, pass_mib, 1.0);  // each figure is rounded down to a MiB
}

TEST(Devices, PlainIndexPicksTheNthDeviceOfTheTable) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  std::vector<std::string> argv{
      gridrtBinary(),         "--device", "0", "--width", "8", "--height", "8", "-o",
      tempPath("device0.png")};
  CommandResult r = runCommand(argv);
  ASSERT_EQ(r.exit_code, 0) << joinArgs(argv) << "\n" << r.err;
  EXPECT_EQ(r.err.rfind("gridrt: device 0:0 ", 0), 0u) << r.err;
}

TEST(Devices, IndexPastTheTableIsAUsageError) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  for (const char* spec : {"999", "99999999999", "0:99999999999"}) {
    CommandResult r = runCommand({gridrtBinary(), "--device", spec, "-o", tempPath("none.png")});
    EXPECT_EQ(r.exit_code, 2) << spec << ": " << r.err;
    EXPECT_NE(r.err.find("unknown device"), std::string::npos) << r.err;
  }
}

// --- statistics -----------------------------------------------------------------------------

nlohmann::json renderStats(const std::string& name, std::vector<std::string> extra) {
  const std::string json = tempPath(name + ".json");
  std::vector<std::string> argv{gridrtBinary(), "--width", "64", "--height",
                                "48",           "-q",      "-o", tempPath(name + ".png"),
                                "--stats-json", json};
  argv.insert(argv.end(), extra.begin(), extra.end());
  CommandResult r = runCommand(argv);
  EXPECT_EQ(r.exit_code, 0) << joinArgs(argv) << "\n" << r.err;
  std::ifstream in(json);
  return nlohmann::json::parse(in, nullptr, false);
}

TEST(Statistics, TracingTimeSplitsByRayKind) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  // The default scene's mirror and glass spawn secondary rays; its light, shadow rays.
  const nlohmann::json all = renderStats("stats_all", {});
  ASSERT_TRUE(all.contains("trace")) << all.dump();
  const nlohmann::json& t = all["trace"];
  EXPECT_GT(t["primary_ms"].get<double>(), 0.0);
  EXPECT_GT(t["secondary_ms"].get<double>(), 0.0);
  EXPECT_GT(t["shadow_ms"].get<double>(), 0.0);
  // Tracing is part of the frame, timed by the frame's own clock.
  EXPECT_LE(all["intersect_ms"].get<double>(), all["frame_ms"].get<double>());
  const double secondary_rays =
      all["rays"]["reflection"].get<double>() + all["rays"]["refraction"].get<double>();
  EXPECT_NEAR(t["secondary_ns_per_ray"].get<double>(),
              t["secondary_ms"].get<double>() * 1e6 / secondary_rays, 1e-6);

  // No bounces: no secondary time; headlight shading: no shadow rays either.
  const nlohmann::json flat = renderStats("stats_depth0", {"--max-depth", "0"});
  EXPECT_EQ(flat["trace"]["secondary_ms"].get<double>(), 0.0);
  EXPECT_EQ(flat["trace"]["secondary_ns_per_ray"].get<double>(), 0.0);
  EXPECT_GT(flat["trace"]["shadow_ms"].get<double>(), 0.0);
  const nlohmann::json primary = renderStats("stats_primary", {"--primary-only"});
  EXPECT_EQ(primary["trace"]["shadow_ms"].get<double>(), 0.0);
  EXPECT_EQ(primary["trace"]["secondary_ms"].get<double>(), 0.0);
  EXPECT_GT(primary["trace"]["primary_ms"].get<double>(), 0.0);
}

}  // namespace
