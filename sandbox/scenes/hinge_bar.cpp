// Fig. 5: a bar attached at its left end by a hinge with target angle 0 and zero compliance.
// Gravity pulls the bar down; the hinge's drive holds it level with torque m g L/2.

#include "scenes/scenes.h"

namespace substep::scenes {

SceneDescription hingeBar() {
    SceneDescription scene{.name = "hinge_bar", .gravity = kPaperGravity, .substeps = 20, .iterations = 1};
    const Vec3 pivot(0.0, 1.0, 0.0);
    const double length = 0.4;
    addStaticBox(scene, "mount", Vec3(0.04, 0.2, 0.1), pivot - Vec3(0.03, 0.0, 0.0));
    addBox(scene, "bar", Vec3(length, 0.04, 0.04), 1.0, pivot + Vec3(length / 2, 0.0, 0.0));
    addJoint(scene, "hinge", "", "bar",
             {.type = JointType::Hinge,
              .anchor0 = pivot,
              .anchor1 = Vec3(-length / 2, 0.0, 0.0),
              .axis0 = Vec3::UnitZ(),
              .axis1 = Vec3::UnitZ(),
              .targetAngle = 0.0,
              .driveCompliance = 0.0});
    scene.camera = SceneCamera{.position = Vec3(0.2, 1.1, 1.2), .target = Vec3(0.2, 1.0, 0.0)};
    return scene;
}

}  // namespace substep::scenes
