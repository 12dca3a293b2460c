// PLACEHOLDER until the scene lands: an empty ground, so the gallery table builds.

#include "scenes/scenes.h"

namespace substep::scenes {

SceneEntry twistedRopeEntry() {
    return {.name = "twisted_rope",
            .description = "Fig. 18: 100 capsules on ball joints with swing and twist limits, one end turned",
            .build = [] {
                SceneDescription scene{.name = "twisted_rope", .gravity = kPaperGravity};
                addGroundPlane(scene, 0.5);
                return scene;
            },
            .paperMsPerFrame = 3.5};
}

}  // namespace substep::scenes
