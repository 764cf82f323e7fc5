// Frame ranges, frame times and output patterns (host/app/frame_sequence.h), and the
// command-line checks around --time, --frames, --fps and --animation.
#include "frame_sequence.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "errors.h"
#include "options.h"
#include "progress.h"
#include "test_support.h"

namespace gridrt {
namespace {

std::string usageError(const std::function<void()>& f) { return test::errorOf<UsageError>(f); }

Options parse(std::vector<std::string> args) {
  args.insert(args.begin(), "gridrt");
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  return *parseCommandLine(int(argv.size()), argv.data());
}

TEST(FrameSequence, PatternsWriteTheFrameNumberAsPrintfWould) {
  EXPECT_EQ(FramePattern("-o", "out_%04d.png").path(7), "out_0007.png");
  EXPECT_EQ(FramePattern("-o", "out_%d.exr").path(123), "out_123.exr");
  EXPECT_EQ(FramePattern("-o", "out_%3d.exr").path(5), "out_  5.exr");
  EXPECT_EQ(FramePattern("-o", "out_%02d.exr").path(12345), "out_12345.exr");
  EXPECT_EQ(FramePattern("-o", "100%%_%d.png").path(2), "100%_2.png");
  EXPECT_EQ(FramePattern("-o", "f%0d/%%.png").path(3), "f3/%.png");
}

TEST(FrameSequence, WhatIsNotAPatternIsAUsageErrorSayingWhy) {
  EXPECT_EQ(usageError([] { FramePattern("-o", "out.png"); }),
            "-o: 'out.png' is not a frame pattern for --frames: it has no frame number (e.g. "
            "out_%04d.png)");
  EXPECT_EQ(usageError([] { FramePattern("-o", "out_%s.png"); }),
            "-o: 'out_%s.png' is not a frame pattern for --frames: '%s' is not a frame number "
            "(%d, %4d or %04d; %% for a '%')");
  EXPECT_EQ(usageError([] { FramePattern("--aov depth", "d_%d_%d.exr"); }),
            "--aov depth: 'd_%d_%d.exr' is not a frame pattern for --frames: it has more than "
            "one frame number");
  for (const char* bad : {"o_%.png", "o_%123d.png", "o_%-4d.png", "o_%", "o_%%.png", "o_%ld"})
    EXPECT_NE(usageError([&] { FramePattern("-o", bad); }), "<no error>") << bad;
  EXPECT_FALSE(FramePattern::isPattern("out.png"));
  EXPECT_TRUE(FramePattern::isPattern("out_%04d.png"));
}

TEST(FrameSequence, RangesAreWholeNumbersInOrder) {
  const FrameRange r = parseFrameRange("3:10");
  EXPECT_EQ(r.first, 3);
  EXPECT_EQ(r.last, 10);
  EXPECT_EQ(parseFrameRange("4:4").last, 4);
  EXPECT_EQ(parseFrameRange("0:99999").last, 99999);
  EXPECT_EQ(usageError([] { parseFrameRange("0:100000"); }),
            "--frames: 0:100000 is 100001 frames, more than the 100000 of one run (split it "
            "into several runs)");
  for (const char* bad : {"10:3", "3", "-1:2", "1:2:3", "a:b", "1.5:2", "1:99999999", ""})
    EXPECT_NE(usageError([&] { parseFrameRange(bad); }).find("--frames: expected A:B"),
              std::string::npos)
        << bad;
}

TEST(FrameSequence, FrameTimesAreFrameOverFps) {
  EXPECT_EQ(frameTime(0, 24.0), 0.0);
  EXPECT_EQ(frameTime(12, 24.0), 0.5);
  EXPECT_EQ(frameTime(1, 24.0), 1.0 / 24.0);
  EXPECT_EQ(frameTime(7, 30.0), 7.0 / 30.0);
}

TEST(FrameSequence, CommandLineTakesFramesFpsTimeAndAnimation) {
  const Options o = parse({"s.gltf", "--frames", "2:5", "--fps", "30", "--animation", "Walk", "-o",
                           "f_%03d.png", "--aov", "depth=d_%03d.exr"});
  ASSERT_TRUE(o.frames);
  EXPECT_EQ(o.frames->first, 2);
  EXPECT_EQ(o.frames->last, 5);
  EXPECT_EQ(o.fps, 30.0);
  EXPECT_EQ(o.animation, "Walk");
  EXPECT_EQ(parse({"--time", "0.25"}).time, 0.25);
  EXPECT_EQ(parse({"--frames", "0:1"}).fps, 24.0);
  // Without -o a sequence is named after the scene, numbered.
  EXPECT_EQ(parse({"walk.glb", "--frames", "0:1"}).output, "walk_%04d.png");
  EXPECT_FALSE(parse({"s.gltf"}).time);
}

TEST(FrameSequence, CommandLineRefusesWhatMeansNothing) {
  EXPECT_EQ(usageError([] { parse({"--fps", "30"}); }), "--fps: only with --frames");
  EXPECT_EQ(usageError([] {
              parse({"--animation", "1"});
            }),
            "--animation: only with --time or --frames");
  EXPECT_EQ(usageError([] {
              parse({"--time", "1", "--frames", "0:1", "-o", "o_%d.png"});
            }),
            "--time: not with --frames (which sets each frame's)");
  EXPECT_EQ(usageError([] {
              parse({"--frames", "0:1", "-o", "o.png"});
            }),
            "-o: 'o.png' is not a frame pattern for --frames: it has no frame number (e.g. "
            "out_%04d.png)");
  EXPECT_NE(usageError([] {
              parse({"--frames", "0:1", "-o", "o_%d.png", "--aov", "depth=d.exr"});
            }).find("--aov depth: 'd.exr' is not a frame pattern"),
            std::string::npos);
  EXPECT_NE(usageError([] {
              parse({"--time", "nan"});
            }).find("expected a finite number"),
            std::string::npos);
  EXPECT_NE(usageError([] {
              parse({"--frames", "0:1", "--fps", "0"});
            }).find("--fps"),
            std::string::npos);
}

TEST(FrameSequence, ALiteralPercentOutsideASequenceIsWarnedAbout) {
  const Options o = parse({"-o", "out_%04d.png"});
  EXPECT_EQ(o.output, "out_%04d.png");
  ASSERT_EQ(o.warnings.size(), 1u);
  EXPECT_NE(o.warnings[0].find("no --frames"), std::string::npos);
}

TEST(FrameSequence, ProgressLineCountsFrames) {
  EXPECT_EQ(formatProgressLine(0.5, 1.0, 1.0, "frame 3 of 6"),
            "gridrt: [############............]  50%  frame 3 of 6, 1.0 s elapsed, about 1.0 s "
            "left");
}

}  // namespace
}  // namespace gridrt
