// PLACEHOLDER until the scene lands: an empty ground, so the gallery table builds.

#include "scenes/scenes.h"

namespace substep::scenes {

SceneEntry bunnyChainEntry() {
    return {.name = "bunny_chain",
            .description = "Figs. 10-11: 100 bunnies hanging from the ceiling as a chain",
            .build = [] {
                SceneDescription scene{.name = "bunny_chain", .gravity = kPaperGravity};
                addGroundPlane(scene, 0.5);
                return scene;
            },
            .paperMsPerFrame = 2.3};
}

}  // namespace substep::scenes
