// sandbox/view/timeline.cpp: the frames kept, the cursor, resuming from an earlier frame (the
// later history dropped) and the capacity from seconds and from the memory budget. That a
// restored frame repeats the run is live_scene_test's and view_window_test's.

#include "view/timeline.h"

#include <gtest/gtest.h>

namespace substep::view {
namespace {

LiveSceneSnapshot frameState(long long frame) {
    LiveSceneSnapshot snapshot;
    snapshot.frame = frame;
    return snapshot;
}

TEST(TimelineTest, KeepsTheLastSecondsOfFrames) {
    Timeline timeline(1.0);  // 1 s of 0.1 s frames: 10 kept
    for (long long f = 0; f <= 25; ++f) timeline.record(frameState(f), 0.1);
    EXPECT_EQ(timeline.capacity(), 10u);
    EXPECT_EQ(timeline.size(), 10u);
    EXPECT_EQ(timeline.firstFrame(), 16);
    EXPECT_EQ(timeline.lastFrame(), 25);
    EXPECT_EQ(timeline.cursorFrame(), 25);
    EXPECT_FALSE(timeline.scrubbed());
}

TEST(TimelineTest, SeekClampsToTheKeptFramesAndResumingDropsTheLaterOnes) {
    Timeline timeline(10.0);
    for (long long f = 0; f <= 20; ++f) timeline.record(frameState(f), 0.1);
    ASSERT_NE(timeline.seek(12), nullptr);
    EXPECT_EQ(timeline.seek(12)->frame, 12);
    EXPECT_TRUE(timeline.scrubbed());
    EXPECT_EQ(timeline.seek(-5)->frame, 0);
    EXPECT_EQ(timeline.seek(99)->frame, 20);
    EXPECT_FALSE(timeline.scrubbed());

    timeline.seek(12);
    timeline.record(frameState(13), 0.1);  // a step from frame 12
    EXPECT_EQ(timeline.lastFrame(), 13);
    EXPECT_EQ(timeline.size(), 14u);
    EXPECT_FALSE(timeline.scrubbed());
}

TEST(TimelineTest, TheMemoryBudgetLimitsTheFramesKept) {
    const std::size_t frameBytes = frameState(0).world.bytes();
    Timeline timeline(100.0, frameBytes * 5);
    for (long long f = 0; f < 50; ++f) timeline.record(frameState(f), 0.01);
    EXPECT_EQ(timeline.capacity(), 5u);
    EXPECT_EQ(timeline.size(), 5u);
    EXPECT_EQ(timeline.firstFrame(), 45);
}

TEST(TimelineTest, AnEmptyTimelineSeeksNothing) {
    Timeline timeline;
    EXPECT_EQ(timeline.seek(3), nullptr);
    timeline.record(frameState(0), 0.01);
    timeline.clear();
    EXPECT_TRUE(timeline.empty());
    EXPECT_EQ(timeline.seek(0), nullptr);
}

}  // namespace
}  // namespace substep::view
