// Fig. 4: boxes hanging from a static ceiling on zero-rest-length springs of compliance
// 0.01 m/N; large boxes 1 kg, small boxes 1/8 kg, gravity 10. Each box starts where its springs
// are stretched by compliance x the weight they carry, so a correct solver keeps it still.

#include "scenes/scenes.h"

namespace substep::scenes {
namespace {

constexpr double kSpringCompliance = 0.01;
constexpr double kLargeMass = 1.0;
constexpr double kSmallMass = 1.0 / 8.0;
const Vec3 kLargeSize(0.2, 0.2, 0.2);
const Vec3 kSmallSize(0.1, 0.1, 0.1);  // half the edge, an eighth of the mass
constexpr double kCeilingBottom = 1.95;

struct Hanger {
    std::string name;  ///< the body to hang from
    Vec3 anchor;       ///< its local anchor point
    Vec3 anchorWorld;  ///< that point in the world at rest
};

/// Hangs a box whose top face centre is stretched `carried x g x α` below the anchor.
Hanger hangBox(SceneDescription& scene, const Hanger& from, const std::string& name,
               const std::string& spring, bool large, double carriedMass) {
    const Vec3 size = large ? kLargeSize : kSmallSize;
    const double stretch = kSpringCompliance * carriedMass * -kPaperGravity.y();
    const Vec3 centre = from.anchorWorld - Vec3(0.0, stretch + size.y() / 2, 0.0);
    addBox(scene, name, size, large ? kLargeMass : kSmallMass, centre);
    addJoint(scene, spring, from.name, name,
             {.type = JointType::Distance,
              .anchor0 = from.anchor,
              .anchor1 = Vec3(0.0, size.y() / 2, 0.0),
              .compliance = kSpringCompliance});
    return {name, Vec3(0.0, -size.y() / 2, 0.0), centre - Vec3(0.0, size.y() / 2, 0.0)};
}

SceneDescription ceilingScene(const std::string& name) {
    SceneDescription scene{.name = name, .gravity = kPaperGravity, .substeps = 20, .iterations = 1};
    addStaticBox(scene, "ceiling", Vec3(1.0, 0.1, 0.4), Vec3(0.0, kCeilingBottom + 0.05, 0.0));
    scene.camera = SceneCamera{.position = Vec3(0.0, 1.3, 2.2), .target = Vec3(0.0, 1.3, 0.0)};
    return scene;
}

}  // namespace

SceneDescription boxes3() {
    SceneDescription scene = ceilingScene("boxes3");
    const Hanger ceiling{"ceiling", Vec3(0.0, -0.05, 0.0), Vec3(0.0, kCeilingBottom, 0.0)};
    const Hanger large = hangBox(scene, ceiling, "large", "spring1", true, kLargeMass + 2 * kSmallMass);
    const Hanger small1 = hangBox(scene, large, "small1", "spring2", false, 2 * kSmallMass);
    hangBox(scene, small1, "small2", "spring3", false, kSmallMass);
    return scene;
}

SceneDescription boxes7() {
    SceneDescription scene = ceilingScene("boxes7");
    const Hanger ceiling{"ceiling", Vec3(0.0, -0.05, 0.0), Vec3(0.0, kCeilingBottom, 0.0)};
    const Hanger large = hangBox(scene, ceiling, "large", "spring1", true, kLargeMass + 6 * kSmallMass);
    // Two branches from the large box's bottom corners, each a chain of three small boxes.
    for (int side = 0; side < 2; ++side) {
        const double x = side == 0 ? -0.08 : 0.08;
        const std::string branch = side == 0 ? "left" : "right";
        Hanger corner{large.name, Vec3(x, -0.1, 0.0), large.anchorWorld + Vec3(x, 0.0, 0.0)};
        for (int level = 0; level < 3; ++level) {
            const std::string id = std::to_string(level + 1);
            corner = hangBox(scene, corner, branch + id, branch + "_spring" + id, false,
                             (3 - level) * kSmallMass);
        }
    }
    return scene;
}

}  // namespace substep::scenes
