// Tests sandbox/scenes/live_scene.cpp's substep stepping (stepSubstep, finishFrame) and with it
// World::beginFrame / substep / endFrame and the corrections recorder: on every built-in scene a
// run stepped a substep at a time, recording each constraint's corrections, gives the same bytes
// frame after frame as a run stepped whole frames (bodies in the world and in the components,
// joint readouts, scripts' readouts), whether it finishes a frame with finishFrame or step().

#include "scenes/live_scene.h"
#include "scenes/scene_registry.h"

#include "ecs/components.h"
#include "physics/substep_corrections.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

namespace substep {
namespace {

/// Every double a frame's outputs read, the world's own state included.
std::vector<double> frameBits(const LiveScene& scene) {
    std::vector<double> out{scene.time()};
    const ecs::Registry& registry = scene.instance().registry;
    for (const ecs::Entity entity : scene.instance().bodyEntities) {
        const ecs::Transform& t = registry.get<ecs::Transform>(entity);
        const ecs::RigidBody& b = registry.get<ecs::RigidBody>(entity);
        out.insert(out.end(),
                   {t.position.x(), t.position.y(), t.position.z(), t.rotation.w(), t.rotation.x(),
                    t.rotation.y(), t.rotation.z(), b.velocity.x(), b.velocity.y(), b.velocity.z(),
                    b.angularVelocity.x(), b.angularVelocity.y(), b.angularVelocity.z()});
    }
    for (const ecs::Entity entity : scene.instance().jointEntities) {
        const JointReadout& r = registry.get<ecs::Joint>(entity).readout;
        out.insert(out.end(), {r.force, r.torque, r.error});
    }
    for (const Body& body : scene.world().bodies())
        out.insert(out.end(), {body.x.x(), body.x.y(), body.x.z(), body.q.w(), body.q.x(),
                               body.q.y(), body.q.z(), body.v.x(), body.v.y(), body.v.z(),
                               body.omega.x(), body.omega.y(), body.omega.z()});
    out.push_back(static_cast<double>(scene.world().activeContactCount()));
    if (const SceneScript* script = scene.script()) {
        std::vector<SceneReadout> readouts;
        script->readouts(scene.instance(), readouts);
        for (const SceneReadout& r : readouts)
            out.push_back(r.value);
    }
    return out;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

class LiveSceneSubsteps : public testing::TestWithParam<std::string> {};

TEST_P(LiveSceneSubsteps, SteppingASubstepAtATimeGivesTheWholeFramesBytes) {
    const SceneEntry* entry = findBuiltinScene(GetParam());
    ASSERT_NE(entry, nullptr);
    LiveScene whole(entry->build(), entry);
    LiveScene split(entry->build(), entry);
    split.physics().recordCorrections(true);
    const int frames = GetParam() == "spheres1000" ? 6 : 24;
    for (int f = 0; f < frames; ++f) {
        whole.step();
        const int substeps = split.world().settings().substeps;
        switch (f % 3) {
            case 0:  // every substep by hand, then the frame's end
                for (int s = 1; s <= substeps; ++s) {
                    ASSERT_TRUE(split.stepSubstep()) << "frame " << f << ", substep " << s;
                    ASSERT_EQ(split.frameSubstepsDone(), s);
                    ASSERT_EQ(split.frameSubsteps(), substeps);
                    ASSERT_EQ(split.world().corrections()->substep(), s);
                    ASSERT_EQ(split.frame(), f) << "an open frame is not counted";
                }
                EXPECT_FALSE(split.stepSubstep());
                split.finishFrame();
                break;
            case 1:  // a few substeps, then a whole-frame step finishes the frame
                for (int s = 0; s < std::min(3, substeps); ++s)
                    ASSERT_TRUE(split.stepSubstep());
                split.step();
                break;
            default:
                split.step();
                break;
        }
        ASSERT_FALSE(split.frameOpen());
        ASSERT_EQ(split.frame(), whole.frame());
        ASSERT_TRUE(sameBits(frameBits(split), frameBits(whole)))
            << GetParam() << ", frame " << f + 1;
    }
}

TEST(LiveSceneSubsteps, RestoringASnapshotAbandonsTheOpenFrame) {
    const SceneEntry* entry = findBuiltinScene("cradle");
    ASSERT_NE(entry, nullptr);
    LiveScene scene(entry->build(), entry);
    LiveScene reference(entry->build(), entry);
    for (int f = 0; f < 5; ++f) {
        scene.step();
        reference.step();
    }
    const LiveSceneSnapshot kept = scene.snapshot();
    ASSERT_TRUE(scene.stepSubstep());
    ASSERT_TRUE(scene.stepSubstep());
    scene.restore(kept);
    EXPECT_FALSE(scene.frameOpen());
    EXPECT_EQ(scene.frameSubstepsDone(), 0);
    scene.step();
    reference.step();
    EXPECT_TRUE(sameBits(frameBits(scene), frameBits(reference)));
}

std::vector<std::string> sceneNames() {
    std::vector<std::string> names;
    for (const SceneEntry& entry : builtinScenes())
        names.emplace_back(entry.name);
    return names;
}

INSTANTIATE_TEST_SUITE_P(Builtin, LiveSceneSubsteps, testing::ValuesIn(sceneNames()),
                         [](const testing::TestParamInfo<std::string>& paramInfo) {
                             return paramInfo.param;
                         });

}  // namespace
}  // namespace substep
