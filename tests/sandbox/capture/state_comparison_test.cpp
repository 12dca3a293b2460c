// Tests sandbox/capture/state_comparison.cpp: |a − b| ≤ abs + rel·|b| per value, per-body and
// per-joint tolerances, and differences in what the states list.

#include "capture/state_comparison.h"

#include <gtest/gtest.h>

#include <cmath>

namespace substep::capture {
namespace {

CaptureState twoBodies() {
    CaptureState state;
    state.time = 1.0;
    state.bodies.push_back({.name = "calm", .position = {0, 2, 0}, .orientation = {1, 0, 0, 0}});
    state.bodies.push_back({.name = "wild", .position = {0, 4, 0}, .orientation = {1, 0, 0, 0}});
    state.joints.push_back({.name = "j", .force = 100.0});
    return state;
}

TEST(StateComparison, IdenticalStatesMatchExactly) {
    const StateComparison result = compareStates(twoBodies(), twoBodies(), {});
    EXPECT_TRUE(result.matches());
    EXPECT_EQ(result.compared, 1u + 2u * 13u + 3u);
}

TEST(StateComparison, AllowsAbsPlusRelTimesTheGoldenValue) {
    // Golden y = 4; allowed 0.1 + 0.05·4 = 0.3. Differences on either side of it (0.25, 0.35).
    const StateCheck check{.tolerance = {.abs = 0.1, .rel = 0.05}};
    CaptureState fresh = twoBodies();
    fresh.bodies[1].position[1] = 4.25;
    EXPECT_TRUE(compareStates(twoBodies(), fresh, check).matches());
    fresh.bodies[1].position[1] = 4.35;
    const StateComparison result = compareStates(twoBodies(), fresh, check);
    EXPECT_FALSE(result.matches());
    EXPECT_EQ(result.outOfTolerance, 1u);
    EXPECT_EQ(result.worst.what, "bodies[1] \"wild\".position[1]");
    EXPECT_EQ(result.worst.golden, 4.0);
    EXPECT_EQ(result.worst.fresh, 4.35);
    EXPECT_DOUBLE_EQ(result.worst.allowed, 0.3);
    // The relative part scales with the golden, not the new value: a golden of 0 allows abs only.
    fresh = twoBodies();
    fresh.bodies[0].position[0] = 0.11;
    EXPECT_FALSE(compareStates(twoBodies(), fresh, check).matches());
}

TEST(StateComparison, PerBodyAndPerJointTolerancesOverrideTheCaptures) {
    StateCheck check;  // exact for everything not named
    check.bodies["wild"] = {.abs = 1e-3};
    check.joints["j"] = {.rel = 0.01};
    CaptureState fresh = twoBodies();
    fresh.bodies[1].velocity[0] = 9e-4;
    fresh.joints[0].force = 100.9;
    EXPECT_TRUE(compareStates(twoBodies(), fresh, check).matches());
    EXPECT_FALSE(check.exact());
    // The same change on the body without its own tolerance is a difference.
    fresh.bodies[0].velocity[0] = 1e-15;
    const StateComparison result = compareStates(twoBodies(), fresh, check);
    ASSERT_EQ(result.outOfTolerance, 1u);
    EXPECT_EQ(result.differences[0].what, "bodies[0] \"calm\".velocity[0]");
}

TEST(StateComparison, TheWorstIsTheLargestExcessAndNanAlwaysDiffers) {
    CaptureState fresh = twoBodies();
    fresh.bodies[0].position[2] = 1e-3;
    fresh.joints[0].error = 0.5;
    fresh.bodies[1].angularVelocity[1] = 1e-9;
    const StateComparison result = compareStates(twoBodies(), fresh, {});
    EXPECT_EQ(result.outOfTolerance, 3u);
    EXPECT_EQ(result.worst.what, "joints[0] \"j\".error");
    fresh.bodies[1].orientation[0] = NAN;
    EXPECT_EQ(compareStates(twoBodies(), fresh, {.tolerance = {.abs = 1e300}}).worst.what,
              "bodies[1] \"wild\".orientation[0]");
}

TEST(StateComparison, DifferentBodiesOrJointsAreAStructureDifference) {
    CaptureState fresh = twoBodies();
    fresh.bodies.pop_back();
    EXPECT_EQ(compareStates(twoBodies(), fresh, {}).structure,
              "the scene has 1 bodies, the golden 2");
    fresh = twoBodies();
    fresh.joints[0].name.back() = 'k';  // "j" becomes "k"
    EXPECT_EQ(compareStates(twoBodies(), fresh, {}).structure,
              "joints[0] is named \"k\", the golden's \"j\"");
    EXPECT_FALSE(compareStates(twoBodies(), fresh, {}).matches());
}

TEST(StateComparison, ListsAtMostALimitButCountsAll) {
    CaptureState golden;
    CaptureState fresh;
    for (int i = 0; i < 100; ++i) {
        std::string name = std::to_string(i);
        golden.bodies.push_back({.name = name});
        fresh.bodies.push_back({.name = name, .position = {1, 1, 1}, .velocity = {1, 1, 1}});
    }
    const StateComparison result = compareStates(golden, fresh, {});
    EXPECT_EQ(result.outOfTolerance, 600u);
    EXPECT_EQ(result.differences.size(), kMaxListedDifferences);
}

}  // namespace
}  // namespace substep::capture
