// Stability on degenerate joint geometry (docs/STABILITY.md): anti-parallel swing axes, anchors
// at the centres of mass, a hinge whose normal lies along its axis, a hinge about a thin rod's
// own long axis, and a spherical twist limit while the swing passes through 180°.

#include "stability_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace substep::stability {
namespace {

const Vec3 kPivot(0.0, 2.0, 0.0);
const std::vector<int> kCounts{1, 2, 5, 10, 20, 40, 80};

/// Angle between the world axes of joint frames 0 and 1 of a joint (rad).
double axisAngle(const World& world, const Joint& joint) {
    const Vec3 a0 = world.bodies()[joint.body0].q * (joint.frame0 * Vec3::UnitX());
    const Vec3 a1 = world.bodies()[joint.body1].q * (joint.frame1 * Vec3::UnitX());
    return test::angleBetween(a0, a1);
}

// --- Anti-parallel swing axes -----------------------------------------------------------------

// A 0.5 m rod (1 kg) hangs from a spherical joint at its top whose swing cone (0.5 rad) opens
// downward, and starts standing straight up: its axis is anti-parallel to the cone's (a0 + a1 = 0,
// no unique swing plane), with twist limits ±0.3 rad that are undefined there. The swing limit
// must turn it about some perpendicular without NaN and bring it inside the cone, releasing at
// most the potential energy it loses. Holds: finite, no energy gained beyond 0.5 % of m g L over
// the start, joint error < 1 mm, swing within 0.5 + 0.01 rad after 1 s.
TEST(AntiParallelSwingTest, RodStandingUpTurnsIntoTheCone) {
    const double length = 0.5, mass = 1.0, limit = 0.5;
    const Bounds bounds{
        .energyGain = 0.005 * mass * kG * length, .jointError = 1e-3, .measure = 0.01};
    const Sweep sweep = sweepSubsteps("anti_parallel_swing", kCounts, bounds, [&](int substeps) {
        World world(WorldSettings{.gravity = Vec3(0, -kG, 0), .substeps = substeps});
        const Vec3 top(0, length / 2, 0);
        const Quat up(Eigen::AngleAxisd(kPi, Vec3::UnitZ()));  // upside down
        const BodyId rod = world.createBody({.shape = boxShape(Vec3(0.05, length, 0.05)),
                                             .mass = mass,
                                             .position = kPivot - up * top,
                                             .orientation = up});
        const JointId joint = world.createJoint({.type = JointType::Spherical,
                                                 .body1 = rod,
                                                 .anchor0 = kPivot,
                                                 .anchor1 = top,
                                                 .axis0 = -Vec3::UnitY(),
                                                 .axis1 = -Vec3::UnitY(),
                                                 .swingLimit = limit,
                                                 .twistLimits = Range{-0.3, 0.3}});
        return watch(world, 2.0, kDt, [&](double t) {
            if (t < 1.0) return 0.0;
            return std::max(0.0, axisAngle(world, world.joint(joint)) - limit);
        });
    });
    expectStable("anti_parallel_swing", sweep, mass * kG * length, 1);
}

// --- Zero anchor offsets ----------------------------------------------------------------------

/// The pair of ZeroOffsetTest joined by `type`.
World zeroOffsetPair(JointType type, int substeps) {
    World world(WorldSettings{.gravity = Vec3(0, -kG, 0), .substeps = substeps});
    const Vec3 centre(0, 5, 0);
    const Vec3 tumble(2, 0, 0);
    const BodyId hub = world.createBody({.shape = boxShape(Vec3(0.1, 0.2, 0.3)),
                                         .mass = 1.0,
                                         .position = centre,
                                         .angularVelocity = tumble});
    const Vec3 spin = type == JointType::Hinge ? Vec3(0, 0, 20) : Vec3::Zero();
    const Vec3 slide = type == JointType::Prismatic ? Vec3(1, 0, 0) : Vec3::Zero();
    const BodyId wheel = world.createBody({.shape = boxShape(Vec3(0.3, 0.3, 0.05)),
                                           .mass = 2.0,
                                           .position = centre,
                                           .velocity = slide,
                                           .angularVelocity = tumble + spin});
    const Vec3 axis = type == JointType::Prismatic ? Vec3::UnitX() : Vec3::UnitZ();
    world.createJoint({.type = type, .body0 = hub, .body1 = wheel, .axis0 = axis, .axis1 = axis});
    return world;
}

// Two boxes joined at their common centre of mass (r0 = r1 = 0) by each joint type, falling
// freely while the pair tumbles at 2 rad/s about x: the wheel of the hinge also spins at 20 rad/s
// about the hinge axis, that of the prismatic slides along its axis at 1 m/s. Nothing acts on
// the pair but gravity, so the energy is kept. Holds: finite, no energy gained beyond 0.5 % of
// the kinetic energy, joint error < 1 mm.
TEST(ZeroOffsetTest, JointsAtTheCentresOfMass) {
    const JointType types[] = {JointType::Hinge, JointType::Spherical, JointType::Fixed,
                               JointType::Prismatic};
    const char* names[] = {"hinge", "spherical", "fixed", "prismatic"};
    for (int k = 0; k < 4; ++k) {
        const std::string name = std::string("zero_offset_") + names[k];
        const double kinetic = zeroOffsetPair(types[k], 20).energies().kinetic;
        const Bounds bounds{.energyGain = 0.005 * kinetic, .jointError = 1e-3};
        const Sweep sweep = sweepSubsteps(name, kCounts, bounds, [&](int substeps) {
            World world = zeroOffsetPair(types[k], substeps);
            return watch(world, 2.0);
        });
        expectStable(name, sweep, kinetic, 1);
    }
}

// --- A hinge whose normal lies along its axis -------------------------------------------------

// A 0.5 m bar (2 kg) hinged level about z at one end, its joint normals given along the axis
// itself (b = a: no perpendicular part). The frame falls back to a fixed perpendicular on both
// sides, so the angle is still defined (0 at the start), and a hard target angle 0 holds the bar
// level against gravity; with limits ±0.3 instead it falls onto −0.3 and rests. Holds: finite, no
// energy gained beyond 0.5 % of m g L, joint error < 1 mm, angle within 1e-3 rad of where it
// should rest over the last second.
TEST(NormalAlongAxisTest, HingeWithItsNormalAlongItsAxis) {
    const double length = 0.5, mass = 2.0;
    for (const bool limits : {false, true}) {
        const std::string name = std::string("normal_along_axis_") + (limits ? "limits" : "drive");
        const double rest = limits ? -0.3 : 0.0;
        const Bounds bounds{
            .energyGain = 0.005 * mass * kG * length, .jointError = 1e-3, .measure = 1e-3};
        const Sweep sweep = sweepSubsteps(name, kCounts, bounds, [&](int substeps) {
            World world(WorldSettings{.gravity = Vec3(0, -kG, 0), .substeps = substeps});
            const BodyId bar = world.createBody({.shape = boxShape(Vec3(length, 0.04, 0.04)),
                                                 .mass = mass,
                                                 .position = kPivot + Vec3(length / 2, 0, 0)});
            JointDef def{.type = JointType::Hinge,
                         .body1 = bar,
                         .anchor0 = kPivot,
                         .anchor1 = Vec3(-length / 2, 0, 0),
                         .axis0 = Vec3::UnitZ(),
                         .axis1 = Vec3::UnitZ(),
                         .normal0 = Vec3::UnitZ(),
                         .normal1 = Vec3::UnitZ()};
            if (limits) {
                def.limits = Range{-0.3, 0.3};
            } else {
                def.targetAngle = 0.0;
            }
            world.createJoint(def);
            return watch(world, 3.0, kDt, [&](double t) {
                if (t < 2.0) return 0.0;
                const Vec3 x = test::userAxis(world.body(bar), Vec3::UnitX());
                return std::abs(std::atan2(x.y(), x.x()) - rest);
            });
        });
        expectStable(name, sweep, mass * kG * length, 10);
    }
}

// --- A hinge about a thin rod's own long axis --------------------------------------------------

// A 1 m rod of 1 cm square section (1 kg: its moment about its long axis is 1/5000 of the others)
// is held at one end by a hinge about its own long axis and turned by the motor at 100 rad/s,
// cantilevered horizontally under gravity: the alignment must hold the heavy transverse inertia
// while the spin runs about the tiny one. Driven, so energy is not bounded. Holds: finite, joint
// error < 1 mm, the rod's axis within 0.01 rad of the hinge's, spin within 1 % of the motor's
// after 0.5 s.
TEST(SpindleTest, MotorTurnsAThinRodAboutItsLongAxis) {
    const double length = 1.0, rate = 100.0;
    const Bounds bounds{.jointError = 1e-3, .measure = 0.01};
    const Sweep sweep = sweepSubsteps("spindle", kCounts, bounds, [&](int substeps) {
        World world(WorldSettings{.gravity = Vec3(0, -kG, 0), .substeps = substeps});
        const BodyId rod = world.createBody({.shape = boxShape(Vec3(length, 0.01, 0.01)),
                                             .mass = 1.0,
                                             .position = kPivot + Vec3(length / 2, 0, 0)});
        const JointId hinge = world.createJoint({.type = JointType::Hinge,
                                                 .body1 = rod,
                                                 .anchor0 = kPivot,
                                                 .anchor1 = Vec3(-length / 2, 0, 0),
                                                 .axis0 = Vec3::UnitX(),
                                                 .axis1 = Vec3::UnitX(),
                                                 .targetVelocity = rate});
        return watch(world, 2.0, kDt, [&](double t) {
            const Body& b = world.body(rod);
            const double tilt = axisAngle(world, world.joint(hinge));
            if (t < 0.5) return tilt;
            const double spin = b.omega.dot(test::userAxis(b, Vec3::UnitX()));
            return std::max(tilt, std::abs(spin - rate) / rate);
        });
    });
    expectStable("spindle", sweep, 0.0, 2);
}

// --- A spherical twist limit while the swing passes 180° ---------------------------------------

// A 1 m rod (1 kg) on a spherical joint at its top end, twist limits ±0.2 rad about its axis and
// no swing limit, is started hanging down at 10 rad/s about a horizontal axis and twisting at
// 1 rad/s, so it loops over the top (swing 0 -> 180° -> 0 every turn). The twist axis of Eq. 22,
// (a0 + a1)/|a0 + a1|, turns through 180° as the swing passes 180°, where twist is undefined (the
// limit waits there). The twist must not jump into a large violation that the limit then
// corrects in one substep. Holds: finite, no energy gained beyond 0.5 % of m g L, joint error
// < 1 mm.
// FIXED weak spot (spherical_joint.cpp, twistFrame; docs/STABILITY.md): near a swing of 180° the
// projected normals n0, n1 of Eqs. 23-24 shrink towards zero and their angle is arbitrary. With
// the old guard (|a0 + a1| < 1e-9) a substep at 320 substeps landed within 1e-3 of the half turn
// and the hard limit turned 9.8 J into 1.7 MJ. The twist limit now rests for |a0 + a1| < 0.05
// (beyond ~177° of swing): the rod gains nothing at every count and holds from 1 substep.
// Seen on the way (not judged): hitting the twist limit at a swing of 135° turns the rod's spin
// about its own axis from −1.0 to +3.8 rad/s (a super-elastic bounce of the twist, 3 mJ here):
// the limit's scalar correction about the bisector n, which at large swing lies far from the
// rod's axis, turns the rod mostly about its axis of least inertia.
TEST(TwistNearHalfTurnTest, RodLoopsOverTheTopWithTwistLimits) {
    const double length = 1.0, mass = 1.0;
    const Bounds bounds{.energyGain = 0.005 * mass * kG * length, .jointError = 1e-3};
    const std::vector<int> counts{1, 2, 5, 10, 20, 40, 80, 160, 320};
    const Sweep sweep = sweepSubsteps("twist_near_half_turn", counts, bounds, [&](int substeps) {
        World world(WorldSettings{.gravity = Vec3(0, -kG, 0), .substeps = substeps});
        const Vec3 top(0, length / 2, 0);
        const double swing = 10.0;  // rad/s about z: 1/2 I ω² = 16.7 J > m g L = 9.81 J
        const BodyId rod = world.createBody({.shape = boxShape(Vec3(0.05, length, 0.05)),
                                             .mass = mass,
                                             .position = kPivot - top,
                                             .velocity = Vec3(swing * length / 2, 0, 0),
                                             .angularVelocity = Vec3(0, 1.0, swing)});
        world.createJoint({.type = JointType::Spherical,
                           .body1 = rod,
                           .anchor0 = kPivot,
                           .anchor1 = top,
                           .axis0 = -Vec3::UnitY(),
                           .axis1 = -Vec3::UnitY(),
                           .twistLimits = Range{-0.2, 0.2}});
        return watch(world, 3.0);
    });
    expectStable("twist_near_half_turn", sweep, mass * kG * length, 1);
}

// --- Anchors far apart along a prismatic axis --------------------------------------------------

// Two 0.5 m bars (2 kg) in series on prismatic joints along x: the first on the world's rail (or
// welded to the world), the second on the first, under gravity, the second sliding at 1 m/s along
// the first, so its anchor moves away from the first bar's along the axis. Nothing drives the
// pair. Holds: finite, no energy gained beyond 0.5 % of m g L, joint error < 1 mm.
// FIXED weak spot (prismatic_joint.cpp, docs/STABILITY.md): the off-axis correction used to move
// body 0 at its own anchor p0, where the constraint acts at p1 = p0 + (slide along the axis), and
// the pair blew up at every count (6.4e5 J rail / 3.3e6 J welded at 20 substeps). Corrections now
// act where the bodies meet: no energy gained at any count, joint error 0.27 mm at 20 substeps
// (1.1 mm at 10), so both hold from 20.
TEST(PrismaticSlideTest, SecondBarSlidesAlongTheFirst) {
    const double length = 0.5, mass = 2.0, speed = 1.0;
    for (const bool welded : {false, true}) {
        const std::string name = std::string("prismatic_slide_") + (welded ? "welded" : "rail");
        const Bounds bounds{.energyGain = 0.005 * mass * kG * length, .jointError = 1e-3};
        const Sweep sweep = sweepSubsteps(name, {5, 10, 20, 40, 80}, bounds, [&](int substeps) {
            World world(WorldSettings{.gravity = Vec3(0, -kG, 0), .substeps = substeps});
            const Vec3 half(length / 2, 0, 0);
            const BodyId first = world.createBody({.shape = boxShape(Vec3(length, 0.1, 0.1)),
                                                   .mass = mass,
                                                   .position = kPivot + half});
            const BodyId second = world.createBody({.shape = boxShape(Vec3(length, 0.1, 0.1)),
                                                    .mass = mass,
                                                    .position = kPivot + 3 * half,
                                                    .velocity = Vec3(speed, 0, 0)});
            world.createJoint({.type = welded ? JointType::Fixed : JointType::Prismatic,
                               .body1 = first,
                               .anchor0 = kPivot,
                               .anchor1 = -half,
                               .axis0 = Vec3::UnitX(),
                               .axis1 = Vec3::UnitX()});
            world.createJoint({.type = JointType::Prismatic,
                               .body0 = first,
                               .body1 = second,
                               .anchor0 = half,
                               .anchor1 = -half,
                               .axis0 = Vec3::UnitX(),
                               .axis1 = Vec3::UnitX()});
            return watch(world, 3.0);
        });
        expectStable(name, sweep, mass * kG * length, 20);
    }
}

}  // namespace
}  // namespace substep::stability
