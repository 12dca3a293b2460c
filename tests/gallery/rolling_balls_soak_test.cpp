// Tests sandbox/scenes/rolling_balls.cpp over 10 simulated minutes (CTest label `stability`):
// the sculpture stays finite, every marble stays inside it, and the marbles keep circulating
// (laps still being completed in the last minute). The short claims are in rolling_balls_test.cpp.

#include "scenes/live_scene.h"
#include "scenes/scene_registry.h"

#include "physics/collision/spline_tube.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

namespace substep {
namespace {

double lapsCompleted(const LiveScene& scene) {
    std::vector<SceneReadout> out;
    scene.script()->readouts(scene.instance(), out);
    EXPECT_EQ(out[0].label, "laps completed");
    return out[0].value;
}

TEST(RollingBallsSoak, TenMinutesStayFiniteAndCirculating) {
    const SceneEntry* entry = findBuiltinScene("rolling_balls");
    ASSERT_NE(entry, nullptr);
    LiveScene scene(entry->build(), entry);
    Aabb bounds;
    for (const Body& b : scene.world().bodies())
        if (b.alive && b.shape.type == ShapeType::Spline) bounds.grow(b.shape.spline->tree.bounds());
    bounds = bounds.inflated(0.05);
    std::vector<BodyId> marbles;
    for (const auto& [name, id] : scene.instance().namedBodyIds())
        if (name.starts_with("marble_")) marbles.push_back(id);

    double lapsBeforeLastMinute = 0.0;
    for (int minute = 1; minute <= 10; ++minute) {
        if (minute == 10) lapsBeforeLastMinute = lapsCompleted(scene);
        for (int frame = 0; frame < 60 * 60; ++frame) {
            scene.step();
            ASSERT_TRUE(scene.world().isFinite()) << "minute " << minute;
        }
        for (BodyId id : marbles) {
            const Vec3& x = scene.world().body(id).x;
            ASSERT_TRUE(bounds.contains({x, x})) << "minute " << minute;
        }
        std::printf("minute %d: %.0f laps\n", minute, lapsCompleted(scene));
    }
    // 24 marbles lapping in well under a minute each: many laps in the last minute.
    EXPECT_GE(lapsCompleted(scene) - lapsBeforeLastMinute, 24.0);
}

}  // namespace
}  // namespace substep
