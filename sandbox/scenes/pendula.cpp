// Fig. 8: a double, a triple and a closed-loop pendulum made of hinged links, 40 substeps
// (Table 1). The closed loop is a parallelogram linkage: two links hang from world hinges and a
// coupler joins their lower ends, a loop a reduced-coordinate solver cannot express directly.

#include "scenes/scenes.h"

#include <cmath>

namespace substep::scenes {
namespace {

constexpr double kLinkLength = 1.0;
constexpr double kLinkMass = 1.0;
const Vec3 kLinkSize(kLinkLength, 0.1, 0.1);

JointDef hinge(const Vec3& anchor0, const Vec3& anchor1) {
    return {.type = JointType::Hinge,
            .anchor0 = anchor0,
            .anchor1 = anchor1,
            .axis0 = Vec3::UnitZ(),
            .axis1 = Vec3::UnitZ()};
}

/// A chain of `links` links released horizontally to the right of a world pivot.
void addOpenPendulum(SceneDescription& scene, const std::string& prefix, const Vec3& pivot, int links) {
    const Vec3 halfLink(kLinkLength / 2, 0.0, 0.0);
    for (int i = 0; i < links; ++i) {
        const std::string name = prefix + std::to_string(i + 1);
        addBox(scene, name, kLinkSize, kLinkMass, pivot + Vec3(kLinkLength * (i + 0.5), 0.0, 0.0));
        if (i == 0)
            addJoint(scene, prefix + "_hinge1", "", name, hinge(pivot, -halfLink));
        else
            addJoint(scene, prefix + "_hinge" + std::to_string(i + 1), prefix + std::to_string(i), name,
                     hinge(halfLink, -halfLink));
    }
}

}  // namespace

/// The triple pendulum on its own: PEERS.md's pendulum3 scene.
SceneDescription pendulum3() {
    SceneDescription scene{.name = "pendulum3", .gravity = kPaperGravity, .substeps = 40, .iterations = 1};
    addOpenPendulum(scene, "link", Vec3(0.0, 3.5, 0.0), 3);
    scene.camera = SceneCamera{.position = Vec3(0.0, 2.0, 7.5), .target = Vec3(0.0, 2.0, 0.0)};
    return scene;
}

SceneDescription pendula() {
    SceneDescription scene{.name = "pendula", .gravity = kPaperGravity, .substeps = 40, .iterations = 1};
    addOpenPendulum(scene, "double", Vec3(-4.0, 3.5, 0.0), 2);
    addOpenPendulum(scene, "triple", Vec3(0.0, 3.5, 0.0), 3);

    // Closed loop: side links tilted 45° from the vertical, joined by a horizontal coupler.
    const Vec3 pivotA(4.5, 3.5, 0.0);
    const Vec3 pivotB(5.7, 3.5, 0.0);
    const double tilt = -M_PI / 4;  // link x axis points down and to the right
    const Quat linkOrientation(Eigen::AngleAxisd(tilt, Vec3::UnitZ()));
    const Vec3 down = linkOrientation * Vec3(kLinkLength, 0.0, 0.0);
    const Vec3 halfLink(kLinkLength / 2, 0.0, 0.0);
    addBox(scene, "loop_left", kLinkSize, kLinkMass, pivotA + down / 2, linkOrientation);
    addBox(scene, "loop_right", kLinkSize, kLinkMass, pivotB + down / 2, linkOrientation);
    const double couplerLength = (pivotB - pivotA).norm();
    addBox(scene, "loop_coupler", Vec3(couplerLength, 0.1, 0.1), kLinkMass,
           (pivotA + pivotB) / 2 + down);
    const Vec3 halfCoupler(couplerLength / 2, 0.0, 0.0);
    addJoint(scene, "loop_hinge1", "", "loop_left", hinge(pivotA, -halfLink));
    addJoint(scene, "loop_hinge2", "", "loop_right", hinge(pivotB, -halfLink));
    addJoint(scene, "loop_hinge3", "loop_left", "loop_coupler", hinge(halfLink, -halfCoupler));
    addJoint(scene, "loop_hinge4", "loop_right", "loop_coupler", hinge(halfLink, halfCoupler));
    scene.camera = SceneCamera{.position = Vec3(0.5, 2.0, 11.0), .target = Vec3(0.5, 2.0, 0.0)};
    return scene;
}

}  // namespace substep::scenes
