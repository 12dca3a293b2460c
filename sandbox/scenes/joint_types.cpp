// PLACEHOLDER until the scene lands: an empty ground, so the gallery table builds.

#include "scenes/scenes.h"

namespace substep::scenes {

SceneEntry jointTypesEntry() {
    return {.name = "joint_types",
            .description = "Fig. 7: prismatic, hinge and spherical joints with hard and soft limits and drives",
            .build = [] {
                SceneDescription scene{.name = "joint_types", .gravity = kPaperGravity};
                addGroundPlane(scene, 0.5);
                return scene;
            },
            .paperMsPerFrame = 0};
}

}  // namespace substep::scenes
