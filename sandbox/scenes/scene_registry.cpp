#include "scenes/scene_registry.h"

#include "scenes/scenes.h"

#include <array>

namespace substep {
namespace {

/// The gallery, in listing order (DESIGN.md's, then the benchmark scenes). Add a scene here and
/// in scenes.h; nothing else registers it. Made on first use: the gallery scenes' entries come
/// from their own files.
const auto& sceneTable() {
    static const std::array kScenes{
    SceneEntry{.name = "boxes3",
               .description = "Fig. 4: three boxes on springs (compliance 0.01 m/N)",
               .build = scenes::boxes3,
               .paperMsPerFrame = 0.34},
    SceneEntry{.name = "boxes7",
               .description = "Fig. 4: seven boxes on springs (compliance 0.01 m/N)",
               .build = scenes::boxes7,
               .paperMsPerFrame = 0.44},
    SceneEntry{.name = "hinge_bar",
               .description = "Fig. 5: a bar held level by a hinge with target angle 0",
               .build = scenes::hingeBar},
    SceneEntry{.name = "mass_ratio",
               .description = "Fig. 6: 1 g boxes holding 1 kg boxes, compliances 0.01, 0.001, 0",
               .build = scenes::massRatio},
    scenes::jointTypesEntry(),
    // Table 1 gives 0.07, 0.09 and 0.2 ms for its three pendulum scenes; this one holds all three.
    SceneEntry{.name = "pendula",
               .description = "Fig. 8: double, triple and closed-loop pendulum",
               .build = scenes::pendula,
               .paperMsPerFrame = 0.07 + 0.09 + 0.2},
    scenes::bunnyChainEntry(),
    scenes::cradleEntry(),
    scenes::marblesOnWireEntry(),
    scenes::coinEntry(),
    scenes::robotArmEntry(),
    scenes::twistedRopeEntry(),
    scenes::rollingBallsEntry(),
    scenes::rcCarEntry(),
    // PEERS.md measures pendulum3's energy error against m g L with m = 1 kg, L = 1 m, g = 10.
    SceneEntry{.name = "pendulum3",
               .description = "Benchmark: triple pendulum released horizontal (PEERS.md)",
               .build = scenes::pendulum3,
               .energyScale = 10.0},
    SceneEntry{.name = "chain100",
               .description = "Benchmark: 100 boxes hanging on ball joints (PEERS.md)",
               .build = scenes::chain100,
               .chain = {.endBody = "link100",
                         .anchor = {0.0, 30.0, 0.0},
                         .endPoint = {0.0, 0.0, 0.0},
                         .restLength = 0.25 * 99.5}},
    SceneEntry{.name = "rope100",
               .description = "Benchmark: 100 capsules on ball joints released horizontal (PEERS.md)",
               .build = scenes::rope100,
               .paperMsPerFrame = 3.5},
    SceneEntry{.name = "stack10",
               .description = "Benchmark: 10 unit cubes stacked on the ground (PEERS.md)",
               .build = scenes::stack10},
    SceneEntry{.name = "pyramid10",
               .description = "A pyramid of 10 rows of unit cubes (55 boxes)",
               .build = scenes::pyramid10},
    SceneEntry{.name = "spheres1000",
               .description = "Benchmark: 1000 spheres dropped into a walled box (PEERS.md)",
               .build = scenes::spheres1000},
    };
    return kScenes;
}

}  // namespace

std::span<const SceneEntry> builtinScenes() { return sceneTable(); }

const SceneEntry* findBuiltinScene(std::string_view name) {
    for (const SceneEntry& entry : sceneTable())
        if (entry.name == name) return &entry;
    return nullptr;
}

}  // namespace substep
