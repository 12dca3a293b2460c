// Every built-in scene runs for 5 simulated seconds with its script and stays finite: one CTest
// per scene (issue 5). The figures each scene stands for are checked in its own suite.

#include "scenes/live_scene.h"
#include "scenes/scene_registry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace substep {
namespace {

class GalleryScene : public testing::TestWithParam<std::string> {};

TEST_P(GalleryScene, RunsFiveSecondsAndStaysFinite) {
    const SceneEntry* entry = findBuiltinScene(GetParam());
    ASSERT_NE(entry, nullptr);
    LiveScene scene(entry->build(), entry);
    const long long frames = static_cast<long long>(std::ceil(5.0 / scene.description().dt));
    for (long long frame = 0; frame < frames; ++frame) {
        scene.step();
        ASSERT_TRUE(scene.world().isFinite()) << GetParam() << " turned non-finite at frame " << scene.frame();
    }
    EXPECT_NEAR(scene.time(), 5.0, scene.description().dt);
}

std::vector<std::string> sceneNames() {
    std::vector<std::string> names;
    for (const SceneEntry& entry : builtinScenes()) names.emplace_back(entry.name);
    return names;
}

INSTANTIATE_TEST_SUITE_P(Builtin, GalleryScene, testing::ValuesIn(sceneNames()),
                         [](const testing::TestParamInfo<std::string>& paramInfo) { return paramInfo.param; });

}  // namespace
}  // namespace substep
