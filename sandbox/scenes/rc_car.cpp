// Paper Figs. 1 and 16, section 4: "We simulate the entire steering mechanism from servo to
// wheels ... The mass ratio between the servo arm and the wheels is 1:760. The servo arm is 3 cm
// long while the wheels have a diameter of 15 cm." The tyres use "per element shape matching
// on the 1100 hexahedral elements". Table 1: 20 substeps, 18 ms per frame.
//
// The car (x forward, y up, left −z):
// - a chassis carrying four wheel carriers ("uprights") on prismatic joints along y: springs
//   (a position drive about the ride height, preloaded by the chassis' weight) with damping
//   (Eq. 31) and compliant stops;
// - the rear wheels on hinge motors on their carriers; the front wheels on free hinges on
//   steering knuckles, which turn on vertical hinges (kingpins) on their carriers;
// - the steering linkage: the servo arm (3 cm, 0.1 g) on a hinge with a target angle, two tie
//   rods (light rods with ball joints at both ends, since the engine's distance joint is a
//   rope that only pulls) to 3 cm steering arms on the knuckles. Horn, rods and steering arms
//   form two parallelograms, so a knuckle turns by the servo's angle;
// - rigid rims inside soft tyres of 1104 hexahedra held on their inner layer.
// The terrain: a heightfield, flat where the car starts, with bumps after it, two planks, a
// curb and a ramp along the first straight.

#include "scenes/rc_car.h"

#include "scenes/scenes.h"

#include "physics/collision/heightfield.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace substep::scenes::rc_car {

namespace {

/// Collision filter: the car's colliding parts (chassis, rims, tyres) do not meet one another.
constexpr uint32_t kCarGroup = 2;

// The terrain (m).
constexpr double kFieldSize = 48.0;
constexpr int kFieldSamples = 401;  ///< per side: 10 cm cells
constexpr double kBumpHeight = 0.015;
constexpr double kBumpLengthX = 0.9;
constexpr double kBumpLengthZ = 1.4;

/// An axis-aligned static box obstacle standing on flat ground: centre (x, z), size, height.
struct Block {
    const char* name;
    double x, z;
    double lengthX, lengthZ, height;
};
constexpr std::array<Block, 3> kBlocks{{
    {"plank_0", 1.5, -0.10, 0.25, 0.40, 0.012},
    {"plank_1", 2.4, 0.12, 0.25, 0.40, 0.016},
    {"curb", 3.6, 0.0, 0.30, 3.00, 0.025},
}};
// The ramp: a box tilted up along +x whose top face starts at ground level at x = kRampStart.
constexpr double kRampStart = 5.0;
constexpr double kRampLength = 0.8;
constexpr double kRampWidth = 0.8;
constexpr double kRampThickness = 0.2;
constexpr double kRampAngle = 5.0 * M_PI / 180.0;

/// 0 to 1 and back: where the bumps are (a strip before the obstacles, and everything past
/// the ramp), with smooth edges so the ground has no step.
double bumpWeight(double x) {
    const auto smooth = [](double u) {
        u = std::clamp(u, 0.0, 1.0);
        return u * u * (3.0 - 2.0 * u);
    };
    const double strip = smooth((x + 1.0) / 0.5) * smooth((1.0 - x) / 0.5);
    const double beyond = smooth((x - 7.0) / 1.0);
    return std::max(strip, beyond);
}

double groundHeight(double x, double z) {
    const double sx = std::sin(M_PI * x / kBumpLengthX);
    return kBumpHeight * bumpWeight(x) * sx * sx * (0.6 + 0.4 * std::cos(2.0 * M_PI * z / kBumpLengthZ));
}

}  // namespace

double terrainHeight(double x, double z) {
    double h = groundHeight(x, z);
    for (const Block& b : kBlocks)
        if (std::abs(x - b.x) <= 0.5 * b.lengthX && std::abs(z - b.z) <= 0.5 * b.lengthZ) h = std::max(h, b.height);
    const double along = x - kRampStart;
    if (along >= 0.0 && along <= kRampLength * std::cos(kRampAngle) && std::abs(z) <= 0.5 * kRampWidth)
        h = std::max(h, along * std::tan(kRampAngle));
    return h;
}

Quat rimOrientation() { return Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX())); }

SoftBodyDef tyreDef(const Vec3& centre, const Quat& rimOrientation, const Vec3& velocity,
                    const Vec3& angularVelocity, double compliance) {
    return SoftBodyDef{.type = SoftBodyType::Tyre,
                       .outerRadius = kTyreRadius - kParticleRadius,
                       .innerRadius = kRimRadius,
                       .width = kTyreWidth,
                       .cells = kTyreCells,
                       .position = centre,
                       .orientation = rimOrientation,
                       .velocity = velocity,
                       .angularVelocity = angularVelocity,
                       .density = kTyreDensity,
                       .compliance = compliance,
                       .damping = kTyreDamping,
                       .staticFriction = kTyreFriction,
                       .dynamicFriction = 0.9 * kTyreFriction,
                       .particleRadius = kParticleRadius,
                       .collisionGroup = kCarGroup,
                       .collisionMask = ~kCarGroup,
                       .attachments = {SoftAttachmentDef{.particles = SoftAttachmentParticles::Inner}}};
}

namespace {

void addTerrain(SceneDescription& scene) {
    std::vector<double> heights(kFieldSamples * kFieldSamples);
    const double cell = kFieldSize / (kFieldSamples - 1);
    for (int row = 0; row < kFieldSamples; ++row)
        for (int column = 0; column < kFieldSamples; ++column)
            heights[row * kFieldSamples + column] =
                groundHeight(-0.5 * kFieldSize + column * cell, -0.5 * kFieldSize + row * cell);
    const Vec3 groundColour(0.42, 0.45, 0.36);
    scene.bodies.push_back(
        {"ground",
         BodyDef{.shape = heightfieldShape(makeHeightfield(kFieldSamples, kFieldSamples, std::move(heights),
                                                           kFieldSize, kFieldSize)),
                 .type = BodyType::Static,
                 .staticFriction = kTyreFriction,
                 .dynamicFriction = 0.9 * kTyreFriction},
         groundColour});
    // The obstacles reach 10 cm into the ground, so their tops are their heights.
    constexpr double kBuried = 0.1;
    for (const Block& b : kBlocks)
        scene.bodies.push_back(
            {b.name,
             BodyDef{.shape = boxShape(Vec3(b.lengthX, b.height + kBuried, b.lengthZ)),
                     .type = BodyType::Static,
                     .position = Vec3(b.x, 0.5 * (b.height - kBuried), b.z),
                     .staticFriction = kTyreFriction,
                     .dynamicFriction = 0.9 * kTyreFriction},
             Vec3(0.6, 0.55, 0.5)});
    // The ramp's top face runs from (kRampStart, 0) up along its length.
    const double c = std::cos(kRampAngle);
    const double s = std::sin(kRampAngle);
    const Vec3 centre(kRampStart + 0.5 * kRampLength * c + 0.5 * kRampThickness * s,
                      0.5 * kRampLength * s - 0.5 * kRampThickness * c, 0.0);
    scene.bodies.push_back({"ramp",
                            BodyDef{.shape = boxShape(Vec3(kRampLength, kRampThickness, kRampWidth)),
                                    .type = BodyType::Static,
                                    .position = centre,
                                    .orientation = Quat(Eigen::AngleAxisd(kRampAngle, Vec3::UnitZ())),
                                    .staticFriction = kTyreFriction,
                                    .dynamicFriction = 0.9 * kTyreFriction},
                            Vec3(0.55, 0.45, 0.35)});
}

/// A dynamic body of the car that only gives mass and a look (it meets nothing).
SceneBody part(std::string name, const Shape& shape, double mass, const Vec3& position,
               const Quat& orientation, const Vec3& colour) {
    return {std::move(name), BodyDef{.shape = shape,
                                     .mass = mass,
                                     .position = position,
                                     .orientation = orientation,
                                     .collide = false},
            colour};
}

}  // namespace

SceneDescription build() {
    SceneDescription scene{.name = "rc_car", .gravity = kPaperGravity, .substeps = 20};
    addTerrain(scene);

    const Vec3 dark(0.15, 0.15, 0.17);
    const Vec3 chassisCentre = kStart + Vec3(0.0, kChassisHeight, 0.0);
    scene.bodies.push_back({"chassis",
                            BodyDef{.shape = boxShape(kChassisSize),
                                    .mass = kChassisMass,
                                    .position = chassisCentre,
                                    .collisionGroup = kCarGroup,
                                    .collisionMask = ~kCarGroup},
                            Vec3(0.8, 0.12, 0.08)});

    // The servo sits on the front axle's line; its horn points back, as the knuckles' arms do.
    const Vec3 servoPivot = kStart + Vec3(0.5 * kWheelbase, kWheelHeight, 0.0);
    // A two-sided horn centred on its pivot (its centre of mass there: the hinge's attachment
    // then never turns it), the rods on one arm of 3 cm.
    scene.bodies.push_back(part("servo_arm", boxShape(Vec3(2.0 * kServoArm, 0.004, 0.008)), kServoArmMass,
                                servoPivot, Quat::Identity(), Vec3(0.9, 0.9, 0.9)));
    // The sprung weight each spring carries, so its target can preload it to the ride height.
    const double sprungLoad = 0.25 * (kChassisMass + kServoArmMass) * -kPaperGravity.y();
    for (int corner = 0; corner < 4; ++corner) {
        const std::string suffix(kCorners[corner]);
        const double z = side(corner);
        const Vec3 kingpin = kStart + Vec3((isFront(corner) ? 0.5 : -0.5) * kWheelbase, kWheelHeight,
                                           z * 0.5 * kKingpinTrack);
        const Vec3 wheelCentre = kingpin + Vec3(0.0, 0.0, z * kStubAxle);
        const std::string upright = "upright_" + suffix;
        const std::string wheel = "wheel_" + suffix;
        scene.bodies.push_back(part(upright, boxShape(Vec3(0.02, 0.03, 0.02)), 0.03, kingpin, Quat::Identity(), dark));
        addJoint(scene, "suspension_" + suffix, "chassis", upright,
                 JointDef{.type = JointType::Prismatic,
                          .anchor0 = kingpin - chassisCentre,
                          .axis0 = Vec3::UnitY(),
                          .axis1 = Vec3::UnitY(),
                          .limits = Range{-kSuspensionTravel, kSuspensionTravel},
                          .limitCompliance = kBumpStopCompliance,
                          .targetOffset = -sprungLoad * kSuspensionCompliance,
                          .driveCompliance = kSuspensionCompliance,
                          .linearDamping = kSuspensionDamping});
        // The wheel's carrier: the upright itself at the rear, a steering knuckle at the front.
        std::string carrier = upright;
        if (isFront(corner)) {
            carrier = "knuckle_" + suffix;
            scene.bodies.push_back(part(carrier, boxShape(Vec3(0.04, 0.015, 0.015)), 0.02, kingpin,
                                        Quat::Identity(), dark));
            addJoint(scene, "kingpin_" + suffix, upright, carrier,
                     JointDef{.type = JointType::Hinge,
                              .axis0 = Vec3::UnitY(),
                              .axis1 = Vec3::UnitY(),
                              .limits = Range{-kMaxSteer - 0.1, kMaxSteer + 0.1}});
        }
        scene.bodies.push_back({wheel,
                                BodyDef{.shape = cylinderShape(kRimRadius, kTyreWidth),
                                        .mass = kWheelMass,
                                        .position = wheelCentre,
                                        .orientation = rimOrientation(),
                                        .collisionGroup = kCarGroup,
                                        .collisionMask = ~kCarGroup},
                                Vec3(0.75, 0.75, 0.78)});
        // About −z, so a positive angle rolls the car forward.
        addJoint(scene, "axle_" + suffix, carrier, wheel,
                 JointDef{.type = JointType::Hinge,
                          .anchor0 = Vec3(0.0, 0.0, z * kStubAxle),
                          .axis0 = -Vec3::UnitZ(),
                          .axis1 = -Vec3::UnitY()});
        scene.softBodies.push_back({"tyre_" + suffix,
                                    tyreDef(wheelCentre, rimOrientation(), Vec3::Zero(), Vec3::Zero(),
                                            kTyreCompliance),
                                    {wheel},
                                    Vec3(0.08, 0.08, 0.09)});
    }

    // The tie rods: from the servo horn's tip to each knuckle's steering arm, kServoArm behind
    // its kingpin. Each rod is as long as the kingpin is far from the servo's pivot, and the
    // horn as long as the steering arms: two parallelograms.
    const Vec3 hornTip = servoPivot - Vec3(kServoArm, 0.0, 0.0);
    const double rodLength = 0.5 * kKingpinTrack;
    for (const double z : {-1.0, 1.0}) {
        const std::string rod = z < 0 ? "tie_rod_l" : "tie_rod_r";
        const std::string knuckle = z < 0 ? "knuckle_fl" : "knuckle_fr";
        scene.bodies.push_back(part(rod, capsuleShape(0.003, rodLength), kTieRodMass,
                                    hornTip + Vec3(0.0, 0.0, 0.5 * z * rodLength), rimOrientation(),
                                    Vec3(0.85, 0.85, 0.2)));
        // The rod's local y runs along world z.
        addJoint(scene, rod + "_knuckle", knuckle, rod,
                 JointDef{.type = JointType::Spherical,
                          .anchor0 = Vec3(-kServoArm, 0.0, 0.0),
                          .anchor1 = Vec3(0.0, 0.5 * z * rodLength, 0.0)});
        addJoint(scene, rod + "_servo", "servo_arm", rod,
                 JointDef{.type = JointType::Spherical,
                          .anchor0 = Vec3(-kServoArm, 0.0, 0.0),
                          .anchor1 = Vec3(0.0, -0.5 * z * rodLength, 0.0)});
    }

    // The servo's hinge after the rods' ball joints: the 0.1 g arm ends each substep's
    // Gauss-Seidel pass on its pivot, not wherever the last rod pulled it.
    addJoint(scene, "servo", "chassis", "servo_arm",
             JointDef{.type = JointType::Hinge,
                      .anchor0 = servoPivot - chassisCentre,
                      .axis0 = Vec3::UnitY(),
                      .axis1 = Vec3::UnitY(),
                      .targetAngle = 0.0,
                      .driveCompliance = kServoCompliance});

    scene.camera = SceneCamera{.position = chassisCentre + Vec3(-1.1, 0.45, 0.35),
                               .target = chassisCentre + Vec3(0.2, 0.0, 0.0),
                               .fov = 0.9};
    return scene;
}

}  // namespace substep::scenes::rc_car
