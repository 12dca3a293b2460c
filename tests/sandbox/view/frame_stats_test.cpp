// sandbox/view/frame_stats.cpp: frame rate from whole frames (the swap included) and the
// real-time factor, simulated seconds per wall second, over the last second of frames.

#include "view/frame_stats.h"

#include <gtest/gtest.h>

namespace substep::view {
namespace {

TEST(FrameStatsTest, FrameRateCountsTheWholeFrameWithItsSwap) {
    FrameStats stats;
    for (int i = 0; i < 10; ++i) {
        stats.record({.frameMs = 160.0, .physicsMs = 5.0, .renderMs = 35.0, .swapMs = 120.0});
    }
    EXPECT_DOUBLE_EQ(stats.frameMs(), 160.0);
    EXPECT_DOUBLE_EQ(stats.fps(), 6.25);  // not 1000 / 35, the draw calls alone
    EXPECT_DOUBLE_EQ(stats.swapMs(), 120.0);
    EXPECT_DOUBLE_EQ(stats.physicsMs(), 5.0);
}

TEST(FrameStatsTest, RealTimeFactorIsSimulatedOverWallTime) {
    // A scene of dt 1/60 s stepping at most 4 frames per 160 ms frame: 4/60 s in 0.16 s.
    FrameStats stats;
    for (int i = 0; i < 20; ++i) stats.record({.frameMs = 160.0, .simulatedSeconds = 4.0 / 60.0, .playing = true});
    EXPECT_NEAR(stats.realTimeFactor(), (4.0 / 60.0) / 0.16, 1e-12);
    EXPECT_TRUE(slowerThanRealTime(stats.realTimeFactor(), 1.0));
    EXPECT_FALSE(slowerThanRealTime(stats.realTimeFactor(), 0.25));  // asked for a quarter speed, gets 0.42

    // Keeping up: 60 fps, one dt each.
    FrameStats fast;
    for (int i = 0; i < 120; ++i) fast.record({.frameMs = 1000.0 / 60.0, .simulatedSeconds = 1.0 / 60.0, .playing = true});
    EXPECT_NEAR(fast.realTimeFactor(), 1.0, 1e-9);
    EXPECT_FALSE(slowerThanRealTime(fast.realTimeFactor(), 1.0));
}

TEST(FrameStatsTest, PausedFramesDoNotCountAsSlow) {
    FrameStats stats;
    for (int i = 0; i < 10; ++i) stats.record({.frameMs = 16.0, .simulatedSeconds = 0.0, .playing = false});
    EXPECT_LT(stats.realTimeFactor(), 0.0);
    EXPECT_FALSE(slowerThanRealTime(stats.realTimeFactor(), 1.0));
}

TEST(FrameStatsTest, KeepsOnlyTheLastSecond) {
    FrameStats stats(1.0);
    for (int i = 0; i < 100; ++i) stats.record({.frameMs = 10.0, .simulatedSeconds = 0.01, .playing = true});
    for (int i = 0; i < 10; ++i) stats.record({.frameMs = 100.0, .simulatedSeconds = 0.01, .playing = true});
    // The last 10 frames fill the second: the fast ones before have left the window.
    EXPECT_DOUBLE_EQ(stats.frameMs(), 100.0);
    EXPECT_NEAR(stats.realTimeFactor(), 0.1, 1e-12);
    // A single frame longer than the window is still kept.
    stats.record({.frameMs = 5000.0});
    EXPECT_DOUBLE_EQ(stats.frameMs(), 5000.0);
    stats.clear();
    EXPECT_DOUBLE_EQ(stats.fps(), 0.0);
}

}  // namespace
}  // namespace substep::view
