// Tests sandbox/scenes/rc_car.cpp, rc_car_script.cpp and rc_car_autopilot.cpp over two
// autopilot laps, 50 s (label `stability`: about 35 s of CPU): the car covers more than 40 m
// over the bumps and obstacles, forwards and in reverse, and stays on the terrain (it drove off
// its edge within the first lap when the lap was a timed list of commands); every value stays
// finite, every tyre keeps more than 70 % of its volume and the chassis never reaches the
// terrain under it.

#include "scenes/live_scene.h"
#include "scenes/rc_car.h"
#include "scenes/scene_registry.h"

#include "ecs/components.h"
#include "ecs/soft_body_component.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace substep {
namespace {

namespace car = scenes::rc_car;

TEST(RcCarSoak, AutopilotLapsCoverFortyMetresAndStayOnTheTerrain) {
    const SceneEntry* entry = findBuiltinScene("rc_car");
    ASSERT_NE(entry, nullptr);
    LiveScene scene(entry->build(), entry);
    const SceneInstance& s = scene.instance();
    const ecs::Entity chassis = s.bodyNamed("chassis");
    std::array<ecs::Entity, 4> tyres{};
    std::array<double, 4> restVolume{};
    for (int corner = 0; corner < 4; ++corner) {
        tyres[corner] = s.softBodyNamed("tyre_" + std::string(car::kCorners[corner]));
        restVolume[corner] = ecs::softBodyReadout(s.world(), s.registry.get<ecs::SoftBody>(tyres[corner])).volume;
    }
    double travelled = 0.0;
    double lowestVolume = 1.0;
    double lowestClearance = std::numeric_limits<double>::infinity();
    double farthest = 0.0;  // m: the largest |x| or |z| of the chassis (the field ends at 24)
    Vec3 last = s.registry.get<ecs::Transform>(chassis).position;
    for (int frame = 0; frame < 3000; ++frame) {
        scene.step();
        ASSERT_TRUE(scene.world().isFinite()) << "frame " << scene.frame();
        const ecs::Transform& pose = s.registry.get<ecs::Transform>(chassis);
        travelled += (pose.position - last).norm();
        last = pose.position;
        farthest = std::max({farthest, std::abs(pose.position.x()), std::abs(pose.position.z())});
        for (int corner = 0; corner < 4; ++corner)
            lowestVolume = std::min(
                lowestVolume,
                ecs::softBodyReadout(s.world(), s.registry.get<ecs::SoftBody>(tyres[corner])).volume / restVolume[corner]);
        for (int i = 0; i < 8; ++i) {
            const Vec3 corner = pose.position + pose.rotation * (0.5 * car::kChassisSize.cwiseProduct(Vec3(
                                                                     i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1)));
            lowestClearance = std::min(lowestClearance, corner.y() - car::terrainHeight(corner.x(), corner.z()));
        }
    }
    EXPECT_GT(travelled, 40.0);
    EXPECT_LT(farthest, 20.0);
    EXPECT_GT(lowestVolume, 0.7);
    EXPECT_GT(lowestClearance, 0.0);
}

}  // namespace
}  // namespace substep
