// Tests sandbox/capture/run_digest.cpp: the one-line digest of a run.

#include "capture/run_digest.h"

#include <gtest/gtest.h>

#include <cmath>

namespace substep::capture {
namespace {

std::string digestOf(const std::vector<CaptureState>& frames) {
    RunDigest digest;
    for (const CaptureState& state : frames)
        digest.add(state);
    return digest.line();
}

std::vector<CaptureState> run() {
    std::vector<CaptureState> frames(3);
    for (int i = 0; i < 3; ++i) {
        frames[i].frame = i;
        frames[i].time = i / 60.0;
        frames[i].bodies.push_back(
            {.name = "b", .position = {0, 1.0 - 0.01 * i, 0}, .orientation = {1, 0, 0, 0}});
        frames[i].joints.push_back({.name = "j", .force = 20.0 + i});
    }
    return frames;
}

TEST(RunDigest, SameRunSameLine) {
    EXPECT_EQ(digestOf(run()), digestOf(run()));
    EXPECT_EQ(digestOf(run()).substr(0, 8), "fnv1a64 ");
    EXPECT_EQ(digestOf(run()).substr(24), " frames 0-2\n");
    // FNV-1a 64 of nothing is its offset basis.
    EXPECT_EQ(RunDigest().line(), "fnv1a64 cbf29ce484222325 frames -1--1\n");
}

TEST(RunDigest, OneUlpAnywhereInAnyFrameChangesIt) {
    const std::string reference = digestOf(run());
    std::vector<CaptureState> frames = run();
    frames[1].bodies[0].position[1] = std::nextafter(frames[1].bodies[0].position[1], 2.0);
    EXPECT_NE(digestOf(frames), reference);
    frames = run();
    frames[2].joints[0].error = 5e-324;
    EXPECT_NE(digestOf(frames), reference);
    // Two values swapped is a different run too (FNV is order-sensitive).
    frames = run();
    std::swap(frames[0].bodies[0].position[0], frames[0].bodies[0].position[1]);
    EXPECT_NE(digestOf(frames), reference);
}

}  // namespace
}  // namespace substep::capture
