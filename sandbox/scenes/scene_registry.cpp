#include "scenes/scene_registry.h"

#include "scenes/scenes.h"

#include <array>

namespace substep {
namespace {

/// The gallery, in listing order. Add a scene here and in scenes.h; nothing else registers it.
constexpr std::array kScenes{
    SceneEntry{"boxes3", "Fig. 4: three boxes on springs (compliance 0.01 m/N)", scenes::boxes3},
    SceneEntry{"boxes7", "Fig. 4: seven boxes on springs (compliance 0.01 m/N)", scenes::boxes7},
    SceneEntry{"hinge_bar", "Fig. 5: a bar held level by a hinge with target angle 0", scenes::hingeBar},
    SceneEntry{"mass_ratio", "Fig. 6: 1 g boxes holding 1 kg boxes, compliances 0.01, 0.001, 0",
               scenes::massRatio},
    SceneEntry{"pendula", "Fig. 8: double, triple and closed-loop pendulum", scenes::pendula},
    SceneEntry{"pendulum3", "Benchmark: triple pendulum released horizontal (PEERS.md)", scenes::pendulum3},
    SceneEntry{"chain100", "Benchmark: 100 boxes hanging on ball joints (PEERS.md)", scenes::chain100},
    SceneEntry{"rope100", "Benchmark: 100 capsules on ball joints released horizontal (PEERS.md)",
               scenes::rope100},
};

}  // namespace

std::span<const SceneEntry> builtinScenes() { return kScenes; }

const SceneEntry* findBuiltinScene(std::string_view name) {
    for (const SceneEntry& entry : kScenes)
        if (entry.name == name) return &entry;
    return nullptr;
}

}  // namespace substep
