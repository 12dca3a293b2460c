// Tests sandbox/scenes/live_scene.cpp's snapshot and restore, the timeline's rewind: every
// built-in scene, scripted or not, scrubbed back 10 frames and resumed, repeats its original
// frames byte for byte (bodies through the components, scripts' readouts, the frame count).

#include "scenes/live_scene.h"
#include "scenes/scene_registry.h"

#include "ecs/components.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

namespace substep {
namespace {

/// What the outputs read of a frame: every body's Transform and velocities as the components
/// hold them, the script's readouts and the time, as raw doubles.
std::vector<double> frameBits(LiveScene& scene) {
    std::vector<double> out{scene.time()};
    const ecs::Registry& registry = scene.instance().registry;
    for (const ecs::Entity entity : scene.instance().bodyEntities) {
        const ecs::Transform& t = registry.get<ecs::Transform>(entity);
        const ecs::RigidBody& b = registry.get<ecs::RigidBody>(entity);
        out.insert(out.end(), {t.position.x(), t.position.y(), t.position.z(), t.rotation.w(),
                               t.rotation.x(), t.rotation.y(), t.rotation.z(), b.velocity.x(),
                               b.velocity.y(), b.velocity.z(), b.angularVelocity.x(),
                               b.angularVelocity.y(), b.angularVelocity.z()});
    }
    for (const ecs::Entity entity : scene.instance().jointEntities)
        out.push_back(registry.get<ecs::Joint>(entity).readout.force);
    if (const SceneScript* script = scene.script()) {
        std::vector<SceneReadout> readouts;
        script->readouts(scene.instance(), readouts);
        for (const SceneReadout& r : readouts) out.push_back(r.value);
    }
    return out;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

class LiveSceneRewind : public testing::TestWithParam<std::string> {};

TEST_P(LiveSceneRewind, ScrubbingBackTenFramesAndResumingRepeatsTheRun) {
    const SceneEntry* entry = findBuiltinScene(GetParam());
    ASSERT_NE(entry, nullptr);
    LiveScene scene(entry->build(), entry);
    ASSERT_TRUE(scene.canSnapshot()) << "every built-in script can be copied";
    // Keep a snapshot per frame, as the timeline does, and the outputs of each frame.
    std::vector<LiveSceneSnapshot> history;
    std::vector<std::vector<double>> outputs;
    for (int f = 0; f < 40; ++f) {
        history.push_back(scene.snapshot());
        outputs.push_back(frameBits(scene));
        scene.step();
    }
    history.push_back(scene.snapshot());
    outputs.push_back(frameBits(scene));
    const long long last = scene.frame();

    // Scrub back 10 frames (one at a time, as the panel's slider does), then resume.
    for (int back = 1; back <= 10; ++back) scene.restore(history[history.size() - 1 - back]);
    ASSERT_EQ(scene.frame(), last - 10);
    EXPECT_TRUE(sameBits(frameBits(scene), outputs[last - 10])) << "the restored state";
    for (long long f = last - 10; f < last; ++f) {
        scene.step();
        EXPECT_TRUE(sameBits(frameBits(scene), outputs[f + 1])) << "frame " << f + 1;
    }
}

std::vector<std::string> sceneNames() {
    std::vector<std::string> names;
    for (const SceneEntry& entry : builtinScenes())
        if (entry.name != "spheres1000") names.emplace_back(entry.name);  // the same as pyramid10, 40 s slower
    return names;
}

INSTANTIATE_TEST_SUITE_P(Builtin, LiveSceneRewind, testing::ValuesIn(sceneNames()),
                         [](const testing::TestParamInfo<std::string>& paramInfo) { return paramInfo.param; });

}  // namespace
}  // namespace substep
