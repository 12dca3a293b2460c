// PLACEHOLDER until the scene lands: an empty ground, so the gallery table builds.

#include "scenes/scenes.h"

namespace substep::scenes {

SceneEntry robotArmEntry() {
    return {.name = "robot_arm",
            .description = "Fig. 17: a robot arm with joint limits whose gripper follows a box",
            .build = [] {
                SceneDescription scene{.name = "robot_arm", .gravity = kPaperGravity};
                addGroundPlane(scene, 0.5);
                return scene;
            },
            .paperMsPerFrame = 0.4};
}

}  // namespace substep::scenes
