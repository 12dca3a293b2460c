// PLACEHOLDER until the scene lands: an empty ground, so the gallery table builds.

#include "scenes/scenes.h"

namespace substep::scenes {

SceneEntry coinEntry() {
    return {.name = "coin",
            .description = "Fig. 15: a coin spun on a table wobbles faster and faster before it rests",
            .build = [] {
                SceneDescription scene{.name = "coin", .gravity = kPaperGravity};
                addGroundPlane(scene, 0.5);
                return scene;
            },
            .paperMsPerFrame = 0.3};
}

}  // namespace substep::scenes
