#pragma once
/// The RC car scene (paper Figs. 1 and 16, section 4): its dimensions, its terrain and its
/// builder (rc_car.cpp), shared with its script (rc_car_script.cpp) and its tests. The car
/// drives along +x, y is up, its left is −z; a positive steering angle turns it left.

#include "scene/scene.h"

#include <array>
#include <string_view>

namespace substep::scenes::rc_car {

// The wheels: 15 cm across (paper section 4), a rigid rim inside a soft tyre.
constexpr double kTyreRadius = 0.075;        ///< m, to the particles' outer surface
constexpr double kParticleRadius = 0.005;    ///< m: the tyre's particles collide as spheres of it
constexpr double kRimRadius = 0.05;          ///< m: the tyre's inner radius
constexpr double kTyreWidth = 0.06;          ///< m
constexpr std::array<int, 3> kTyreCells = {46, 4, 6};  ///< around, radial, across: 1104 elements
constexpr double kTyreDensity = 200.0;       ///< kg/m³ (a foam-filled tyre: 0.11 kg)
constexpr double kTyreCompliance = 2e-6;     ///< 1/Pa: Young's modulus 1/(3 α) ≈ 170 kPa
constexpr double kTyreDamping = 20.0;        ///< 1/s, of the tyre's deformation
constexpr double kTyreFriction = 1.0;        ///< static; dynamic 0.9
constexpr double kWheelMass = 0.076;         ///< kg, a rim with its hub
/// Paper section 4: "The mass ratio between the servo arm and the wheels is 1:760."
constexpr double kServoArmMass = kWheelMass / 760.0;
constexpr double kServoArm = 0.03;           ///< m: "The servo arm is 3 cm long"
constexpr double kTieRodMass = 1e-3;         ///< kg

// The chassis and where the wheels sit on it.
constexpr double kWheelbase = 0.32;          ///< m, front to rear axle
constexpr double kKingpinTrack = 0.26;       ///< m between the left and right kingpins
constexpr double kStubAxle = 0.0;            ///< m from a kingpin out to its wheel's centre (none: no scrub radius)
constexpr double kChassisMass = 1.2;         ///< kg
const Vec3 kChassisSize(0.44, 0.04, 0.10);   ///< m
constexpr double kWheelHeight = kTyreRadius + 0.001;  ///< m: the wheels' centres at the start
constexpr double kChassisHeight = 0.085;     ///< m: the chassis' centre at the start
constexpr double kMaxSteer = 0.5;            ///< rad: the steering stops

// Suspension: each wheel's carrier slides on the chassis along y on a sprung, damped
// prismatic joint with compliant stops.
constexpr double kSuspensionCompliance = 2e-3;  ///< m/N: 500 N/m per wheel
constexpr double kSuspensionDamping = 200.0;    ///< 1/s
constexpr double kSuspensionTravel = 0.025;     ///< m either way to the stops
constexpr double kBumpStopCompliance = 1e-4;    ///< m/N

// Drive: the rear wheels' hinge motors.
constexpr double kMaxWheelSpeed = 60.0;      ///< rad/s at full throttle (4.5 m/s)
constexpr double kMotorCompliance = 0.02;    ///< rad/(N·m)
constexpr double kServoCompliance = 1e-3;    ///< rad/(N·m)

/// The four corners in the order of the names below: front left, front right, rear left, rear
/// right.
constexpr std::array<std::string_view, 4> kCorners = {"fl", "fr", "rl", "rr"};
constexpr bool isFront(int corner) { return corner < 2; }
/// −1 on the left (−z), +1 on the right.
constexpr double side(int corner) { return corner % 2 == 0 ? -1.0 : 1.0; }

/// Where the car starts: its chassis centre on the ground's flat part, heading +x.
const Vec3 kStart(-3.0, 0.0, 0.0);

/// The terrain's height at (x, z) (m): the heightfield's bumps and the obstacles' tops (ramp,
/// boxes, curb), for the tests' clearance checks. The ground is flat for x < 0.
double terrainHeight(double x, double z);

/// The scene: terrain, obstacles and the car.
SceneDescription build();

/// A tyre as it is built around its rim (the script rebuilds the tyres when their compliance
/// changes), at the rim's pose and motion.
SoftBodyDef tyreDef(const Vec3& centre, const Quat& rimOrientation, const Vec3& velocity,
                    const Vec3& angularVelocity, double compliance);

/// The rims' orientation at the start: their local y (the cylinder's axis) along world z.
Quat rimOrientation();

}  // namespace substep::scenes::rc_car
