// The rendering options reach the renderer: each of --aa, --intersector, --pe-interrupt,
// --pe-layout, --threads, --camera, --grid-density, --min-path-weight, --ambient and --stats,
// given on the command line, changes what the program does in the way its help text says (the
// image, the AOVs, the rays traced or the grid in --stats-json), against the same render
// without it. And
// bad values of --look-at, --fov and --stats-json end the run with one line and the
// documented exit code (2 for usage, 1 otherwise).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "image_output.h"
#include "run_command.h"
#include "test_support.h"

namespace {

using gridrt::test::CommandResult;
using gridrt::test::gridrtBinary;
using gridrt::test::joinArgs;
using gridrt::test::runCommand;
using gridrt::test::sourcePath;
using gridrt::test::tempPath;

constexpr int kWidth = 64, kHeight = 48;

bool haveDevice() { return gridrt::test::gridrtHasDevice(); }

struct Render {
  gridrt::ImageData image, depth;
  nlohmann::json stats;
  std::string out;  // stdout
};

// The default scene (or `scene`) at 64x48 with `flags`: the image, its depth AOV, the
// statistics.
Render render(const std::string& name, const std::vector<std::string>& flags,
              const std::string& scene = "") {
  const std::string image = tempPath(name + ".exr"), depth = tempPath(name + "_depth.exr"),
                    json = tempPath(name + ".json");
  std::vector<std::string> argv{gridrtBinary()};
  if (!scene.empty()) argv.push_back(scene);
  for (const std::string& a :
       {std::string("-q"), std::string("--width"), std::to_string(kWidth), std::string("--height"),
        std::to_string(kHeight), std::string("-o"), image, std::string("--aov"), "depth=" + depth,
        std::string("--stats-json"), json})
    argv.push_back(a);
  argv.insert(argv.end(), flags.begin(), flags.end());
  CommandResult r = runCommand(argv);
  Render out;
  EXPECT_EQ(r.exit_code, 0) << joinArgs(argv) << "\n" << r.err;
  if (r.exit_code != 0) return out;
  out.image = gridrt::readImage(image);
  out.depth = gridrt::readImage(depth);
  std::ifstream in(json);
  out.stats = nlohmann::json::parse(in, nullptr, false);
  out.out = r.out;
  return out;
}

// Pixels whose value differs in some channel, bit for bit.
size_t differingPixels(const gridrt::ImageData& a, const gridrt::ImageData& b) {
  EXPECT_EQ(a.pixels.size(), b.pixels.size());
  if (a.pixels.size() != b.pixels.size() || a.channels == 0) return 0;
  size_t differ = 0;
  for (size_t p = 0; p < a.pixels.size() / a.channels; ++p) {
    bool same = true;
    for (int c = 0; c < a.channels; ++c)
      same &= a.pixels[p * a.channels + c] == b.pixels[p * a.channels + c];
    differ += !same;
  }
  return differ;
}

uint64_t secondaryRays(const nlohmann::json& stats) {
  return stats["rays"]["reflection"].get<uint64_t>() + stats["rays"]["refraction"].get<uint64_t>();
}

class CliOptions : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
    plain_ = render("plain", {});
    ASSERT_FALSE(plain_.image.pixels.empty());
  }
  Render plain_;
};

// Centres, then --aa-samples more samples in the refined pixels only.
TEST_F(CliOptions, AaAdaptiveRefinesSomePixelsWithTheirExtraSamples) {
  const Render adaptive = render("adaptive", {"--aa", "adaptive", "--aa-samples", "4"});
  const uint64_t refined = adaptive.stats["refined_pixels"].get<uint64_t>();
  EXPECT_GT(refined, 0u);
  EXPECT_LT(refined, uint64_t(kWidth) * kHeight / 2);
  EXPECT_EQ(adaptive.stats["rays"]["primary"].get<uint64_t>(),
            uint64_t(kWidth) * kHeight + 4 * refined);
  const size_t changed = differingPixels(plain_.image, adaptive.image);
  EXPECT_GT(changed, 0u);
  EXPECT_LE(changed, refined) << "only refined pixels may change";
}

// The watertight test computes t differently: the depths change in their last bits.
TEST_F(CliOptions, IntersectorWatertightRunsAnotherRayTriangleTest) {
  const Render watertight = render("watertight", {"--intersector", "watertight"});
  EXPECT_GT(differingPixels(plain_.depth, watertight.depth), 0u);
  EXPECT_EQ(watertight.stats["rays"]["primary"], plain_.stats["rays"]["primary"]);
}

// Shadow and list batches skip pairs too; the hits, so the image, stay the same. How many
// pairs are skipped depends on the order the work-groups run in: both renders run on one
// PoCL thread, which runs them in order, so the counts are the same from run to run.
TEST_F(CliOptions, PeInterruptSkipsPairsInEveryBatchWithTheSameImage) {
  const Render camera_only = render("interrupt_camera", {"--threads", "1"});
  const Render all = render("interrupt", {"--pe-interrupt", "--threads", "1"});
  EXPECT_GT(all.stats["interrupt"]["skipped_pairs"].get<uint64_t>(),
            camera_only.stats["interrupt"]["skipped_pairs"].get<uint64_t>());
  EXPECT_EQ(differingPixels(plain_.image, all.image), 0u);
}

// The host's list time split by pass: a Whitted frame walks the lists of its reflection and
// refraction rays and bins their pairs, and bundles its camera rays; camera rays alone are
// only bundled. The PE kernels are timed on the device too.
TEST_F(CliOptions, StatisticsSplitTheHostListTimeByPassAndTimeTheKernelsOnTheDevice) {
  const nlohmann::json& lists = plain_.stats["lists"];
  ASSERT_GT(secondaryRays(plain_.stats), 0u);
  EXPECT_GT(lists["walk_ms"].get<double>(), 0.0);
  EXPECT_GT(lists["binning_ms"].get<double>(), 0.0);
  EXPECT_GT(lists["bundling_ms"].get<double>(), 0.0);
  // The PE kernels' own time on the device (profiling) is part of the kernel phase.
  EXPECT_GT(plain_.stats["kernel_device_ms"].get<double>(), 0.0);
  EXPECT_LE(plain_.stats["kernel_device_ms"].get<double>(),
            plain_.stats["kernel_ms"].get<double>());
  // The device time over the frame's packets; a camera ray that hits (depth -1: a miss)
  // holds a lane of one, 16 lanes a packet.
  const double packets = plain_.stats["kernel_packets"].get<double>();
  const size_t hit_pixels = size_t(std::count_if(
      plain_.depth.pixels.begin(), plain_.depth.pixels.end(), [](float z) { return z >= 0.0f; }));
  ASSERT_GT(hit_pixels, 0u);
  EXPECT_GE(packets * 16, double(hit_pixels));
  EXPECT_DOUBLE_EQ(plain_.stats["kernel_ns_per_packet"].get<double>(),
                   plain_.stats["kernel_device_ms"].get<double>() * 1e6 / packets);
  const Render primary = render("lists_primary", {"--primary-only"});
  EXPECT_EQ(primary.stats["lists"]["walk_ms"].get<double>(), 0.0);
  EXPECT_EQ(primary.stats["lists"]["binning_ms"].get<double>(), 0.0);
  EXPECT_GT(primary.stats["lists"]["bundling_ms"].get<double>(), 0.0);
}

// --pe-layout picks gridrt's PE kernels: a CPU device runs the packets by default, the lanes
// when asked, with the same image; the statistics name the layout that ran. Other
// intersectors have no PE kernels and refuse it.
TEST_F(CliOptions, PeLayoutPicksThePeKernelsNotTheImage) {
  EXPECT_EQ(plain_.stats["pe_layout"], plain_.stats["device_type"] == "CPU" ? "packets" : "lanes");
  for (const char* layout : {"packets", "lanes"}) {
    const Render r = render(std::string("layout_") + layout, {"--pe-layout", layout});
    EXPECT_EQ(r.stats["pe_layout"], layout);
    EXPECT_EQ(differingPixels(plain_.image, r.image), 0u) << layout;
    EXPECT_EQ(differingPixels(plain_.depth, r.depth), 0u) << layout;
  }
  const CommandResult bad =
      runCommand({gridrtBinary(), "--accel", "dda", "--pe-layout", "lanes", "-o", "unused.png"});
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("--pe-layout: only with --accel gridrt"), std::string::npos) << bad.err;
}

// --transfer picks how gridrt's batches cross to the device: mapped by default, copied when
// asked, with the same image; the statistics name the transfer that ran. Other
// intersectors refuse it.
TEST_F(CliOptions, TransferPicksHowBatchesCrossNotTheImage) {
  EXPECT_EQ(plain_.stats["transfer"], "map");
  for (const char* transfer : {"map", "copy"}) {
    const Render r = render(std::string("transfer_") + transfer, {"--transfer", transfer});
    EXPECT_EQ(r.stats["transfer"], transfer);
    EXPECT_EQ(differingPixels(plain_.image, r.image), 0u) << transfer;
    EXPECT_EQ(differingPixels(plain_.depth, r.depth), 0u) << transfer;
    // The copies are timed on the device, within the kernel phase that waits for them.
    const double device_ms = r.stats["transfer_device_ms"].get<double>();
    EXPECT_GE(device_ms, 0.0) << transfer;
    if (std::string(transfer) == "copy") {
      EXPECT_GT(device_ms, 0.0);
      EXPECT_LE(device_ms, r.stats["kernel_ms"].get<double>());
    }
  }
  const CommandResult bad =
      runCommand({gridrtBinary(), "--accel", "brute", "--transfer", "copy", "-o", "unused.png"});
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("--transfer: only with --accel gridrt"), std::string::npos) << bad.err;
  const CommandResult unknown = runCommand({gridrtBinary(), "--transfer", "pinned"});
  EXPECT_EQ(unknown.exit_code, 2) << unknown.err;
  EXPECT_NE(unknown.err.find("--transfer"), std::string::npos) << unknown.err;
}

// --threads N limits the host's loops and PoCL's threads together; the image does not
// depend on the count (every parallel loop splits its range by count, never by timing).
TEST_F(CliOptions, ThreadsSetsTheHostAndDeviceThreadCountsNotTheImage) {
  for (const char* threads : {"1", "3"}) {
    const Render limited = render(std::string("threads") + threads, {"--threads", threads});
    EXPECT_EQ(limited.stats["host_threads"].get<int>(), std::atoi(threads));
    // PoCL runs at most one thread a CPU.
    EXPECT_EQ(limited.stats["device_compute_units"].get<int>(),
              std::min(std::atoi(threads), plain_.stats["device_compute_units"].get<int>()));
    EXPECT_EQ(differingPixels(plain_.image, limited.image), 0u) << threads << " threads";
    EXPECT_EQ(differingPixels(plain_.depth, limited.depth), 0u) << threads << " threads";
  }
  const CommandResult bad = runCommand({gridrtBinary(), "--threads", "-1"});
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("--threads"), std::string::npos) << bad.err;
}

// -v says what was chosen, one line each: the default scene's lights, its default camera,
// its grid (the glass sphere's voxels are full, so it is refined) and the passes; a bare
// scene's added lights; nothing of it without -v; and -v with -q is a usage error.
TEST_F(CliOptions, VerboseSaysWhatWasChosen) {
  auto run = [](std::vector<std::string> argv) {
    argv.insert(argv.begin(), gridrtBinary());
    for (const char* a : {"--width", "64", "--height", "48", "-o"}) argv.push_back(a);
    argv.push_back(tempPath("verbose.png"));
    return runCommand(argv);
  };
  const CommandResult v = run({"-v"});
  ASSERT_EQ(v.exit_code, 0) << v.err;
  for (const char* line : {"gridrt: scene: the built-in default scene, 4438 triangles",
                           "gridrt: camera: ", ", 64x48\n", "gridrt: grid: adaptive over ",
                           "gridrt: render: gridrt, Whitted, up to 5 bounces, 1 sample a pixel"})
    EXPECT_NE(v.err.find(line), std::string::npos) << line << " in:\n" << v.err;
  // One triangle, no camera, no lights.
  const std::string bare_scene = tempPath("bare.gltf");
  std::ofstream(bare_scene)
      << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
      << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"accessors":[{)"
      << R"("bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],)"
      << R"("max":[1,1,0]}],"bufferViews":[{"buffer":0,"byteLength":36}],"buffers":[{)"
      << R"("byteLength":36,"uri":"data:application/octet-stream;base64,)"
      << R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})";
  const CommandResult bare = run({"-v", bare_scene, "--primary-only", "--grid", "uniform"});
  ASSERT_EQ(bare.exit_code, 0) << bare.err;
  for (const char* line : {"no lights: a key and a fill light added", "the default three-quarter",
                           "gridrt: grid: uniform ", "primary rays, headlight shading"})
    EXPECT_NE(bare.err.find(line), std::string::npos) << line << " in:\n" << bare.err;
  const CommandResult plain = run({});
  EXPECT_EQ(plain.err.find("gridrt: grid:"), std::string::npos) << plain.err;
  const CommandResult both = run({"-v", "-q"});
  EXPECT_EQ(both.exit_code, 2) << both.err;
  EXPECT_NE(both.err.find("--verbose and --quiet"), std::string::npos) << both.err;
}

// A finer grid changes the PEs, never the hits.
TEST_F(CliOptions, GridDensityRefinesTheGridButNotTheImage) {
  const Render dense = render("dense", {"--grid-density", "2"});
  EXPECT_GT(dense.stats["grid"]["voxels"].get<uint64_t>(),
            plain_.stats["grid"]["voxels"].get<uint64_t>());
  EXPECT_EQ(differingPixels(plain_.image, dense.image), 0u);
}

// Bounces whose throughput is below the weight are not traced: fewer secondary rays.
TEST_F(CliOptions, MinPathWeightLeavesDimBouncesOut) {
  const Render cut = render("cut", {"--min-path-weight", "0.3"});
  EXPECT_LT(secondaryRays(cut.stats), secondaryRays(plain_.stats));
  EXPECT_GT(secondaryRays(cut.stats), 0u);
  EXPECT_GT(differingPixels(plain_.image, cut.image), 0u);
}

// The ambient term adds ambient * albedo to every hit: more of it, no pixel darker (float
// sums of non-negative terms grow with each term) and the lit surfaces brighter.
TEST_F(CliOptions, AmbientBrightensAndDarkensNoPixel) {
  const Render bright = render("ambient", {"--ambient", "0.5"});
  ASSERT_EQ(bright.image.pixels.size(), plain_.image.pixels.size());
  size_t darker = 0, brighter = 0;
  for (size_t k = 0; k < plain_.image.pixels.size(); ++k) {
    darker += bright.image.pixels[k] < plain_.image.pixels[k];
    brighter += bright.image.pixels[k] > plain_.image.pixels[k];
  }
  EXPECT_EQ(darker, 0u);
  EXPECT_GT(brighter, plain_.image.pixels.size() / 2);
}

// The table on stdout names the same rays as the JSON.
TEST_F(CliOptions, StatsPrintsTheTableOfTheRender) {
  const Render table = render("table", {"--stats"});
  std::istringstream lines(table.out);
  std::string line;
  std::string primary, total;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string key, value;
    words >> key >> value;
    if (key == "rays.primary") primary = value;
    if (key == "rays.total") total = value;
  }
  EXPECT_EQ(primary, std::to_string(table.stats["rays"]["primary"].get<uint64_t>())) << table.out;
  EXPECT_EQ(total, std::to_string(table.stats["rays"]["total"].get<uint64_t>())) << table.out;
  EXPECT_TRUE(plain_.out.empty()) << "no table without --stats: " << plain_.out;
}

// The default scene's file with a second camera, 0.3 to the right of the first.
std::string sceneWithTwoCameras() {
  std::ifstream in(sourcePath("scenes/default.gltf"));
  nlohmann::json gltf = nlohmann::json::parse(in);
  nlohmann::json camera = gltf["cameras"][0];
  camera["name"] = "side camera";
  gltf["cameras"].push_back(camera);
  nlohmann::json node;
  node["name"] = "side camera";
  node["camera"] = gltf["cameras"].size() - 1;
  node["translation"] = {0.3, 1.0, 2.0};
  gltf["nodes"].push_back(node);
  gltf["scenes"][0]["nodes"].push_back(gltf["nodes"].size() - 1);
  const std::string path = tempPath("two_cameras.gltf");
  std::ofstream(path) << gltf.dump();
  return path;
}

TEST_F(CliOptions, CameraPicksTheNamedCamera) {
  const std::string scene = sceneWithTwoCameras();
  const Render first = render("first", {}, scene);
  const Render named_first = render("named_first", {"--camera", "default camera"}, scene);
  const Render side = render("side", {"--camera", "side camera"}, scene);
  EXPECT_EQ(differingPixels(first.image, plain_.image), 0u) << "the first camera is the default";
  EXPECT_EQ(differingPixels(named_first.image, first.image), 0u);
  EXPECT_GT(differingPixels(side.image, first.image), size_t(kWidth) * kHeight / 4);
  CommandResult r = runCommand(
      {gridrtBinary(), scene, "--camera", "no such camera", "-q", "-o", tempPath("none.png")});
  EXPECT_EQ(r.exit_code, 2);  // the command line's mistake, not the file's
  EXPECT_NE(r.err.find("camera 'no such camera' not found"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'side camera'"), std::string::npos) << "the cameras are listed: " << r.err;
}

}  // namespace

namespace {

// One line on stderr starting with "gridrt: ", holding `text`.
void expectOneErrorLine(const CommandResult& r, const std::string& text) {
  EXPECT_EQ(r.err.rfind("gridrt: ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
  EXPECT_NE(r.err.find(text), std::string::npos) << r.err;
}

TEST(BadInput, MalformedLookAtIsAUsageError) {
  for (const char* bad : {"1,2:3,4,5", "1,2,3", "1,2,3:a,b,c", "1,2,3:4,5,nan"}) {
    CommandResult r = runCommand({gridrtBinary(), "--look-at", bad, "-o", tempPath("la.png")});
    EXPECT_EQ(r.exit_code, 2) << bad;
    expectOneErrorLine(r, "--look-at");
  }
}

TEST(BadInput, EyeEqualToTargetIsAUsageError) {
  CommandResult r =
      runCommand({gridrtBinary(), "--look-at", "1,2,3:1,2,3", "-o", tempPath("eye.png")});
  EXPECT_EQ(r.exit_code, 2);
  expectOneErrorLine(r, "eye and target are the same point");
}

TEST(BadInput, FieldOfViewOutsideItsRangeIsAUsageError) {
  for (const char* bad : {"0", "0.001", "179.5", "200", "-10"}) {
    CommandResult r = runCommand({gridrtBinary(), "--fov", bad, "-o", tempPath("fov.png")});
    EXPECT_EQ(r.exit_code, 2) << bad;
    expectOneErrorLine(r, "--fov");
  }
}

// "--stats-json -" writes the statistics to standard output, and only them.
TEST(StatisticsOutput, DashWritesTheJsonToStandardOutput) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  CommandResult r = runCommand({gridrtBinary(), "-q", "--width", "8", "--height", "6", "-o",
                                tempPath("stdout_stats.png"), "--stats-json", "-"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json stats = nlohmann::json::parse(r.out, nullptr, false);
  ASSERT_FALSE(stats.is_discarded()) << r.out;
  EXPECT_EQ(stats["width"], 8);
  EXPECT_EQ(stats["rays"]["primary"], 48);
  EXPECT_FALSE(std::ifstream("-").good()) << "no file named '-'";
}

TEST(BadInput, UnwritableStatisticsFileFailsTheRun) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  const std::string json = tempPath("no_such_folder") + "/stats.json";
  CommandResult r = runCommand({gridrtBinary(), "-q", "--width", "8", "--height", "8", "-o",
                                tempPath("stats.png"), "--stats-json", json});
  EXPECT_EQ(r.exit_code, 1);
  expectOneErrorLine(r, "cannot write '" + json + "'");
}

}  // namespace
