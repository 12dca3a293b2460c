// Fig. 6: a 1 g box hangs from the ceiling on a distance joint and holds a 1 kg box on a second
// one, for compliances 0.01, 0.001 and 0 m/N side by side. The boxes start at the stretch the
// compliances predict (α x the weight carried); with α = 0 the joints stay closed up to the
// steady gap of ERRATA item 7.

#include "scenes/scenes.h"

#include <array>

namespace substep::scenes {

SceneDescription massRatio() {
    SceneDescription scene{.name = "mass_ratio", .gravity = kPaperGravity, .substeps = 20, .iterations = 1};
    constexpr std::array kCompliances{0.01, 0.001, 0.0};
    constexpr double kLightMass = 0.001;
    constexpr double kHeavyMass = 1.0;
    const Vec3 lightSize(0.04, 0.04, 0.04);
    const Vec3 heavySize(0.2, 0.2, 0.2);
    const double ceilingBottom = 1.9;
    const double g = -kPaperGravity.y();
    addStaticBox(scene, "ceiling", Vec3(1.8, 0.1, 0.4), Vec3(0.0, ceilingBottom + 0.05, 0.0));
    for (size_t i = 0; i < kCompliances.size(); ++i) {
        const double alpha = kCompliances[i];
        const std::string id = std::to_string(i + 1);
        const double x = (static_cast<double>(i) - 1.0) * 0.6;
        const double lightTop = ceilingBottom - alpha * (kLightMass + kHeavyMass) * g;
        const double heavyTop = lightTop - lightSize.y() - alpha * kHeavyMass * g;
        addBox(scene, "light" + id, lightSize, kLightMass, Vec3(x, lightTop - lightSize.y() / 2, 0.0));
        addBox(scene, "heavy" + id, heavySize, kHeavyMass, Vec3(x, heavyTop - heavySize.y() / 2, 0.0));
        addJoint(scene, "top" + id, "ceiling", "light" + id,
                 {.type = JointType::Distance,
                  .anchor0 = Vec3(x, -0.05, 0.0),
                  .anchor1 = Vec3(0.0, lightSize.y() / 2, 0.0),
                  .compliance = alpha});
        addJoint(scene, "bottom" + id, "light" + id, "heavy" + id,
                 {.type = JointType::Distance,
                  .anchor0 = Vec3(0.0, -lightSize.y() / 2, 0.0),
                  .anchor1 = Vec3(0.0, heavySize.y() / 2, 0.0),
                  .compliance = alpha});
    }
    scene.camera = SceneCamera{.position = Vec3(0.0, 1.4, 2.6), .target = Vec3(0.0, 1.4, 0.0)};
    return scene;
}

}  // namespace substep::scenes
