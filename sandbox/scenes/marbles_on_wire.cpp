// PLACEHOLDER until the scene lands: an empty ground, so the gallery table builds.

#include "scenes/scenes.h"

namespace substep::scenes {

SceneEntry marblesOnWireEntry() {
    return {.name = "marbles_on_wire",
            .description = "Fig. 13: marbles created penetrating a two-wire track stay on it",
            .build = [] {
                SceneDescription scene{.name = "marbles_on_wire", .gravity = kPaperGravity};
                addGroundPlane(scene, 0.5);
                return scene;
            },
            .paperMsPerFrame = 0};
}

}  // namespace substep::scenes
