// Tests sandbox/scenes/rc_car.cpp and rc_car_script.cpp, the RC car (paper Figs. 1, 16): the
// paper's masses and sizes; the steering linkage's parallelograms turning the knuckles by the
// servo's angle at the 1:760 mass ratio; the autopilot over the obstacles (finite, tyres keep
// their volume, the chassis clears the terrain); holding on a slope below the tyres' grip and
// sliding above it (the friction threshold with the load on the braked rear axle); coasting to a
// stop with energy only decreasing; and the rolling radius (ω times the axle's height matches
// the chassis' speed). Every figure is measured on the bodies' states, not read from the
// script's readouts. Two whole laps are rc_car_soak_test.cpp (label `stability`).

#include "scenes/live_scene.h"
#include "scenes/rc_car.h"
#include "scenes/scene_registry.h"

#include "ecs/components.h"
#include "ecs/soft_body_component.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace substep {
namespace {

namespace car = scenes::rc_car;
constexpr double kDegree = M_PI / 180.0;

const SceneEntry& rcCar() {
    const SceneEntry* entry = findBuiltinScene("rc_car");
    EXPECT_NE(entry, nullptr);
    return *entry;
}

/// The scene with knobs set (autopilot off unless asked) and, optionally, another gravity.
LiveScene makeCar(std::initializer_list<std::pair<const char*, double>> knobs, const Vec3* gravity = nullptr) {
    LiveScene scene(rcCar().build(), &rcCar());
    EXPECT_TRUE(scene.setKnob("autopilot", 0.0));
    for (const auto& [name, value] : knobs) EXPECT_TRUE(scene.setKnob(name, value)) << name;
    if (gravity != nullptr) {
        ecs::PhysicsSystem physics = scene.physics();
        WorldSettings settings = physics.settings();
        settings.gravity = *gravity;
        physics.setSettings(settings);
    }
    return scene;
}

const ecs::Joint& joint(const LiveScene& scene, const char* name) {
    return scene.instance().registry.get<ecs::Joint>(scene.instance().jointNamed(name));
}
const ecs::RigidBody& body(const LiveScene& scene, const std::string& name) {
    return scene.instance().registry.get<ecs::RigidBody>(scene.instance().bodyNamed(name));
}
const ecs::Transform& pose(const LiveScene& scene, const std::string& name) {
    return scene.instance().registry.get<ecs::Transform>(scene.instance().bodyNamed(name));
}
const ecs::SoftBody& tyre(const LiveScene& scene, int corner) {
    return scene.instance().registry.get<ecs::SoftBody>(
        scene.instance().softBodyNamed("tyre_" + std::string(car::kCorners[corner])));
}

/// The largest tie-rod joint error (m).
double tieRodError(const LiveScene& scene) {
    double error = 0.0;
    for (const char* name : {"tie_rod_l_servo", "tie_rod_l_knuckle", "tie_rod_r_servo", "tie_rod_r_knuckle"})
        error = std::max(error, joint(scene, name).readout.error);
    return error;
}

void run(LiveScene& scene, double seconds) {
    const long long frames = std::llround(seconds / scene.description().dt);
    for (long long i = 0; i < frames; ++i) {
        scene.step();
        ASSERT_TRUE(scene.world().isFinite()) << "frame " << scene.frame();
    }
}

TEST(RcCar, HasThePapersMassRatioSizesAndTyres) {
    LiveScene scene(rcCar().build(), &rcCar());
    const double arm = body(scene, "servo_arm").simulatedMass;
    for (const char* wheel : {"wheel_fl", "wheel_fr", "wheel_rl", "wheel_rr"})
        EXPECT_NEAR(body(scene, wheel).simulatedMass / arm, 760.0, 1e-9);
    // "The servo arm is 3 cm long": from the servo's pivot to the rods' ball joints.
    const Vec3 pivot = pose(scene, "servo_arm").position;
    const ecs::Transform& rod = pose(scene, "tie_rod_l");
    const Vec3 rodEnd = rod.position + rod.rotation * joint(scene, "tie_rod_l_servo").def.anchor1;
    EXPECT_NEAR((rodEnd - pivot).norm(), 0.03, 1e-12);
    for (int corner = 0; corner < 4; ++corner) {
        const SoftBodyReadout& readout = tyre(scene, corner).readout;
        EXPECT_GE(readout.elements, 1000);
        EXPECT_LE(readout.elements, 1200);
        // 15 cm across (the particles' spheres included): a particle lies on each end of the
        // horizontal diameter.
        EXPECT_NEAR(readout.extent.x() + 2.0 * car::kParticleRadius, 0.15, 1e-9);
    }
}

// Driving straight ahead, up to 2 m/s over the flat ground before the bumps, at the 1:760 mass
// ratio: the linkage stays closed (every tie-rod ball joint within 1 mm) and holds both knuckles
// within 1° of the servo's 0°.
TEST(RcCar, LinkageHoldsTheWheelsStraightAtSpeed) {
    LiveScene scene = makeCar({{"throttle", 0.5}});
    double worstRod = 0.0;
    double worstAngle = 0.0;
    for (int frame = 0; frame < 80; ++frame) {
        scene.step();
        worstRod = std::max(worstRod, tieRodError(scene));
        if (frame >= 40)
            for (const char* kingpin : {"kingpin_fl", "kingpin_fr"})
                worstAngle = std::max(worstAngle, std::abs(joint(scene, kingpin).readout.coordinate));
    }
    EXPECT_LT(pose(scene, "chassis").position.x(), -1.0) << "left the flat ground";
    EXPECT_GT(body(scene, "chassis").velocity.norm(), 1.5);
    EXPECT_LT(worstRod, 1e-3);
    EXPECT_LT(worstAngle / kDegree, 1.0);
}

// The linkage's parallelograms turn each knuckle by the servo's angle at 1:760. Projected joint
// by joint, the 0.1 g arm passed on too little of each correction (a light body between two
// constraints passes on m_light/(m_light + m_heavy) per Gauss-Seidel pass): weightless, the
// knuckles swung undamped between −34° and +33° about the commanded 20°. The block solve of the
// joints around the light arm and rods (physics/joint_block_solve.h) solves them together;
// measured: 20.3° and 19.7°, the tie rods closed within 2e-8 m.
TEST(RcCar, ServoTurnsTheKnucklesWeightless) {
    const Vec3 weightless = Vec3::Zero();
    LiveScene scene = makeCar({{"steer", 20.0}}, &weightless);
    run(scene, 1.0);
    std::printf("[ measured ] %zu joint clusters; weightless knuckles %.3f° %.3f°, tie rods %.3g m\n",
                scene.world().jointClusterCount(), joint(scene, "kingpin_fl").readout.coordinate / kDegree,
                joint(scene, "kingpin_fr").readout.coordinate / kDegree, tieRodError(scene));
    EXPECT_NEAR(joint(scene, "kingpin_fl").readout.coordinate / kDegree, 20.0, 1.0);
    EXPECT_NEAR(joint(scene, "kingpin_fr").readout.coordinate / kDegree, 20.0, 1.0);
    EXPECT_LT(tieRodError(scene), 1e-3);
}

// The claim at speed against the ground, 20 substeps x 1 iteration: commanded 14° at
// 1.85 m/s, the servo arm at 14.0°, the knuckles at 14.02° and 13.97°, the tie rods closed within
// 2e-6 m (joint by joint the knuckles reached only 1.3° and 0.7°, the rods stretched 6 mm).
TEST(RcCar, ServoTurnsTheFrontWheelsAtSpeedAgainstTheGround) {
    LiveScene scene = makeCar({{"throttle", 0.5}});
    run(scene, 1.5);
    ASSERT_TRUE(scene.setKnob("steer", 14.0));
    run(scene, 1.0);
    std::printf("[ measured ] at %.2f m/s: servo %.3f°, knuckles %.3f° %.3f°, tie rods %.3g m\n",
                body(scene, "chassis").velocity.norm(), joint(scene, "servo").readout.coordinate / kDegree,
                joint(scene, "kingpin_fl").readout.coordinate / kDegree,
                joint(scene, "kingpin_fr").readout.coordinate / kDegree, tieRodError(scene));
    EXPECT_GT(body(scene, "chassis").velocity.norm(), 1.5);
    EXPECT_NEAR(joint(scene, "kingpin_fl").readout.coordinate / kDegree, 14.0, 1.0);
    EXPECT_NEAR(joint(scene, "kingpin_fr").readout.coordinate / kDegree, 14.0, 1.0);
    EXPECT_LT(tieRodError(scene), 1e-3);
}

/// The chassis box's lowest corner above the terrain under it (m).
double chassisClearance(const LiveScene& scene) {
    const ecs::Transform& chassis = pose(scene, "chassis");
    double clearance = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 8; ++i) {
        const Vec3 corner = chassis.position + chassis.rotation * (0.5 * car::kChassisSize.cwiseProduct(Vec3(
                                                                             i & 1 ? 1 : -1, i & 2 ? 1 : -1,
                                                                             i & 4 ? 1 : -1)));
        clearance = std::min(clearance, corner.y() - car::terrainHeight(corner.x(), corner.z()));
    }
    return clearance;
}

// The first 6 s of the autopilot: over the bump strip, both planks, the curb and the ramp.
TEST(RcCar, DrivesOverTheObstaclesOnAutopilot) {
    LiveScene scene(rcCar().build(), &rcCar());
    std::array<double, 4> restVolume{};
    // The volume on demand (the step's readout leaves it NaN, which std::min would skip).
    const auto volume = [&](int corner) { return ecs::softBodyReadout(scene.world(), tyre(scene, corner)).volume; };
    for (int corner = 0; corner < 4; ++corner) restVolume[corner] = volume(corner);
    double lowestVolume = 1.0;
    double lowestClearance = std::numeric_limits<double>::infinity();
    const Vec3 start = pose(scene, "chassis").position;
    for (int frame = 0; frame < 360; ++frame) {
        scene.step();
        ASSERT_TRUE(scene.world().isFinite()) << "frame " << scene.frame();
        for (int corner = 0; corner < 4; ++corner)
            lowestVolume = std::min(lowestVolume, volume(corner) / restVolume[corner]);
        lowestClearance = std::min(lowestClearance, chassisClearance(scene));
    }
    const Vec3 end = pose(scene, "chassis").position;
    EXPECT_GT(end.x(), 6.0) << "the car did not get past the ramp";
    EXPECT_GT((end - start).norm(), 9.0);
    EXPECT_GT(lowestVolume, 0.7);
    EXPECT_GT(lowestClearance, 0.0);
}

// On a slope the car faces up, the rear motors holding the wheels (throttle 0, brake on), the
// front wheels free. The braked rear axle carries N_r = M g (cos θ / 2 + h sin θ / L) with the
// centre of mass h above the ground and wheelbase L, and must supply M g sin θ along the slope:
// the car holds while tan θ < μ (1/2 + (h/L) tan θ) and slides beyond (μ = 1: up to 47°).
// Measured short of that with each particle's friction judged on its own (the default): at
// 25° it slides 0.93 m in 1.5 s (the lightly loaded particles let go first), so this test
// holds at 10°; the next one holds at 25° with the friction judged over each tyre's patch.
TEST(RcCar, HoldsOnASlopeBelowTheGripAndSlidesAbove) {
    for (const double degrees : {10.0, 55.0}) {
        const double theta = degrees * kDegree;
        const Vec3 gravity = 10.0 * Vec3(-std::sin(theta), -std::cos(theta), 0.0);
        LiveScene scene = makeCar({{"brake", 1.0}}, &gravity);
        run(scene, 1.0);
        const Vec3 settled = pose(scene, "chassis").position;
        run(scene, 1.5);
        const double moved = (pose(scene, "chassis").position - settled).norm();
        if (degrees < 40.0)
            EXPECT_LT(moved, 2e-3) << degrees << "°";
        else
            EXPECT_GT(moved, 0.1) << degrees << "°";
    }
}

// Braked on 25° with μ = 1 (N_r μ = 0.57 M g against M g sin θ = 0.42 M g) and the static
// friction judged over each tyre's patch (WorldSettings::softPatchFriction): it holds.
TEST(RcCar, HoldsOn25DegreesWithPatchFriction) {
    const double theta = 25.0 * kDegree;
    const Vec3 gravity = 10.0 * Vec3(-std::sin(theta), -std::cos(theta), 0.0);
    LiveScene scene = makeCar({{"brake", 1.0}}, &gravity);
    ecs::PhysicsSystem physics = scene.physics();
    WorldSettings settings = physics.settings();
    settings.softPatchFriction = true;
    physics.setSettings(settings);
    run(scene, 1.0);
    const Vec3 settled = pose(scene, "chassis").position;
    run(scene, 1.5);
    const double moved = (pose(scene, "chassis").position - settled).norm();
    std::printf("[ measured ] moved on 25° in 1.5 s: %.3g mm\n", 1e3 * moved);
    EXPECT_LT(moved, 2e-3);
}

// Motors off on flat ground (reversing away from the bumps), from three speeds: the car rolls
// on, loses its energy to the tyres' damping and stops. While it rolls (faster than 0.3 m/s) the
// world's energy (kinetic, potential and elastic, rigid and soft) never rises. Once the tyres
// stick and the stopped car rocks on them, the measured total swings from frame to frame by up
// to about 2 % of the kinetic energy it had (measured at throttles −0.25 to −0.6, with the
// element kernel's one Newton step and with the two it took before alike); the car still ends
// with that energy gone.
TEST(RcCar, CoastsToAStopWithTheMotorsOff) {
    for (const double throttle : {-0.3, -0.4, -0.5}) {
        LiveScene scene = makeCar({{"throttle", throttle}});
        run(scene, 1.5);
        const double kinetic = scene.world().energies().kinetic;
        EXPECT_GT(body(scene, "chassis").velocity.norm(), 1.0) << throttle;
        ASSERT_TRUE(scene.setKnob("throttle", 0.0));
        const double start = scene.world().energies().total();
        double previous = start;
        double risingWhileRolling = -kinetic, risingAfter = -kinetic;
        for (int frame = 0; frame < 120; ++frame) {
            const bool rolling = body(scene, "chassis").velocity.norm() > 0.3;
            scene.step();
            const double energy = scene.world().energies().total();
            double& rising = rolling ? risingWhileRolling : risingAfter;
            rising = std::max(rising, energy - previous);
            previous = energy;
        }
        EXPECT_LE(risingWhileRolling, 0.0) << throttle;
        EXPECT_LT(risingAfter, 0.03 * kinetic) << throttle;
        EXPECT_LT(previous, start - 0.9 * kinetic) << throttle;
        EXPECT_LT(body(scene, "chassis").velocity.norm(), 0.02) << throttle;
    }
}

// At a steady speed on flat ground each wheel's spin times its axle's height above the ground
// matches the chassis' speed: the free front tyres roll without slip, the driven rear ones slip
// by a few percent.
TEST(RcCar, WheelSpinTimesRollingRadiusMatchesTheSpeed) {
    LiveScene scene = makeCar({{"throttle", -0.4}});
    run(scene, 2.0);
    const Vec3 velocity = body(scene, "chassis").velocity;
    for (int corner = 0; corner < 4; ++corner) {
        const std::string wheel = "wheel_" + std::string(car::kCorners[corner]);
        const double spin = std::abs(body(scene, wheel).angularVelocity.z());
        const double radius = pose(scene, wheel).position.y();  // flat ground at y = 0
        const double tolerance = car::isFront(corner) ? 0.03 : 0.05;
        EXPECT_NEAR(spin * radius / velocity.norm(), 1.0, tolerance) << wheel;
    }
}

}  // namespace
}  // namespace substep
