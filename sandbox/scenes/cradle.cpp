// PLACEHOLDER until the scene lands: an empty ground, so the gallery table builds.

#include "scenes/scenes.h"

namespace substep::scenes {

SceneEntry cradleEntry() {
    return {.name = "cradle",
            .description = "Fig. 12: a marble hits a row of three; the impulse reaches the far one",
            .build = [] {
                SceneDescription scene{.name = "cradle", .gravity = kPaperGravity};
                addGroundPlane(scene, 0.5);
                return scene;
            },
            .paperMsPerFrame = 0};
}

}  // namespace substep::scenes
