// Tests sandbox/scenes/marbles_on_wire.cpp, the paper's Fig. 13: marbles created penetrating a
// two-wire track are "pushed up gently and remain on the track" with the velocity pass, while
// "regular PBD creates large velocities causing the marbles to jump off the track" (the
// "velocity pass" toggle off). Where a marble is on the track is measured against the wires'
// own curves (their closest points), not against the scene's numbers.

#include "scenes/live_scene.h"
#include "scenes/scene_registry.h"

#include "physics/collision/spline_tube.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace substep {
namespace {

constexpr double kG = 10.0;  // the paper's gravity, which the scene uses

struct Track {
    std::vector<const SplineTube*> wires;
    std::vector<BodyId> marbles;
    double marbleRadius = 0.0;
};

Track findTrack(const SceneInstance& scene) {
    Track track;
    for (const Body& b : scene.world().bodies())
        if (b.shape.type == ShapeType::Spline) {
            // The wires are static bodies at the origin: their curves are in world coordinates.
            EXPECT_LT(b.x.norm() + (b.userPosition() - b.x).norm(), 1e-12);
            track.wires.push_back(b.shape.spline.get());
        }
    for (const auto& [name, id] : scene.namedBodyIds())
        if (name.starts_with("marble")) track.marbles.push_back(id);
    EXPECT_EQ(track.wires.size(), 2u);
    EXPECT_GE(track.marbles.size(), 3u);
    if (!track.marbles.empty())
        track.marbleRadius = scene.world().body(track.marbles[0]).shape.radius;
    return track;
}

/// How a marble sits on the track: its gap to each wire's surface (negative: overlap) and
/// whether its centre is between the wires.
struct Seat {
    double highestGap = 0.0;  ///< the larger of the two gaps: how far it is off the track
    double deepestGap = 0.0;  ///< the smaller: how far it still overlaps a wire
    bool between = false;
};

Seat seatOf(const Track& track, const Vec3& centre) {
    Seat seat{.highestGap = -std::numeric_limits<double>::infinity(),
              .deepestGap = std::numeric_limits<double>::infinity()};
    double zMin = std::numeric_limits<double>::infinity();
    double zMax = -zMin;
    for (const SplineTube* wire : track.wires) {
        const SplinePoint p = wire->closestPoint(centre, 1e3);
        const double gap = p.segment < 0
                               ? std::numeric_limits<double>::infinity()
                               : std::sqrt(p.distanceSquared) - wire->radius - track.marbleRadius;
        seat.highestGap = std::max(seat.highestGap, gap);
        seat.deepestGap = std::min(seat.deepestGap, gap);
        if (p.segment >= 0) {
            zMin = std::min(zMin, p.point.z());
            zMax = std::max(zMax, p.point.z());
        }
    }
    seat.between = centre.z() > zMin && centre.z() < zMax;
    return seat;
}

/// What a run of the scene did to its marbles.
struct WireRun {
    double highestGap = 0.0;         ///< over every marble and frame (m)
    double highestGapSettled = 0.0;  ///< the same after the first 0.5 s
    std::vector<double> jumps;       ///< per marble: its highest gap above the wires (m)
    double fastestRise = 0.0;        ///< largest upward speed in the first 0.5 s (m/s)
    bool alwaysBetween = true;       ///< every centre stayed between the two wires
    double deepestAtEnd = 0.0;       ///< largest overlap with a wire after 5 s (m, positive)
    int onTrackAtEnd = 0;            ///< marbles touching both wires after 5 s
    double wireRadius = 0.0;
};

WireRun runWires(bool velocityPass) {
    const SceneEntry* entry = findBuiltinScene("marbles_on_wire");
    EXPECT_NE(entry, nullptr);
    LiveScene scene(entry->build(), entry);
    EXPECT_NE(scene.script(), nullptr);
    EXPECT_TRUE(
        scene.script()->setKnob(scene.instance(), "velocity_pass", velocityPass ? 1.0 : 0.0));
    EXPECT_EQ(scene.world().settings().velocityPass, velocityPass);
    const Track track = findTrack(scene.instance());

    WireRun run;
    run.jumps.assign(track.marbles.size(), -1.0);
    if (!track.wires.empty()) run.wireRadius = track.wires[0]->radius;
    // The marbles start overlapping the wires (the figure's premise).
    for (BodyId id : track.marbles)
        EXPECT_LT(seatOf(track, scene.world().body(id).x).deepestGap, -1e-3);

    const int frames = static_cast<int>(std::lround(5.0 / scene.description().dt));
    for (int frame = 0; frame < frames; ++frame) {
        scene.step();
        for (size_t i = 0; i < track.marbles.size(); ++i) {
            const Body& marble = scene.world().body(track.marbles[i]);
            const Seat seat = seatOf(track, marble.x);
            run.jumps[i] = std::max(run.jumps[i], seat.highestGap);
            run.highestGap = std::max(run.highestGap, seat.highestGap);
            if (scene.time() > 0.5)
                run.highestGapSettled = std::max(run.highestGapSettled, seat.highestGap);
            run.alwaysBetween = run.alwaysBetween && seat.between;
            if (scene.time() <= 0.5) run.fastestRise = std::max(run.fastestRise, marble.v.y());
        }
    }
    for (BodyId id : track.marbles) {
        const Seat seat = seatOf(track, scene.world().body(id).x);
        run.deepestAtEnd = std::max(run.deepestAtEnd, -seat.deepestGap);
        run.onTrackAtEnd += seat.between && seat.highestGap < 1e-3;
    }
    return run;
}

// Fig. 13 bottom: every marble stays on the track for 5 s. Its centre stays between the wires
// and it never lifts off either wire by more than the wire's radius (a marble resting on both
// has gap 0): measured 2.9 mm in the first frames, when the push-out rocks each marble 2.6 mm
// sideways onto one wire (Gauss-Seidel meets one wire first), and after 0.5 s, rolling in the
// valley and knocking into the others, under 3 mm (measured 1.0 mm, a marble hit on the slope).
// By the end the overlaps it was created with are pushed out.
TEST(MarblesOnWireTest, WithTheVelocityPassEveryMarbleStaysOnTheTrackForFiveSeconds) {
    const WireRun run = runWires(true);
    ASSERT_FALSE(run.jumps.empty());
    EXPECT_LT(run.highestGap, run.wireRadius);
    EXPECT_LT(run.highestGapSettled, 3e-3);
    EXPECT_TRUE(run.alwaysBetween);
    EXPECT_LT(run.deepestAtEnd, 5e-4);
    EXPECT_EQ(run.onTrackAtEnd, static_cast<int>(run.jumps.size()));
}

// Fig. 13 bottom: "pushed up gently". An upward speed v carries a marble v²/2g above the wires
// once it leaves them; 0.25 m/s is a 3 mm hop, under the 2-4 mm the marbles were sunk and far
// below what would lift one off the track. Measured: 0.05 m/s.
TEST(MarblesOnWireTest, WithTheVelocityPassTheMarblesRiseGently) {
    const WireRun run = runWires(true);
    const double gentle = 0.25;
    EXPECT_LT(gentle * gentle / (2.0 * kG), 3.2e-3);
    EXPECT_LT(run.fastestRise, gentle);
}

// Fig. 13 top: "Regular PBD creates large velocities causing the marbles to jump off the track."
// Plain PBD pushes each overlap d out in one substep and keeps v = d/h: 2-4 mm at h = 1/1200 s
// is 2.4-4.8 m/s. Measured: upward speeds to 6.1 m/s, every marble at least 0.4 m above the
// wires, all five on the floor after 5 s.
TEST(MarblesOnWireTest, PlainPbdVelocitiesThrowTheMarblesOffTheTrack) {
    const WireRun run = runWires(false);
    EXPECT_GT(run.fastestRise, 10.0 * 0.25);  // ten times the gentle bound above
    for (size_t i = 0; i < run.jumps.size(); ++i)
        EXPECT_GT(run.jumps[i], 0.2) << "marble " << i;
    EXPECT_LE(run.onTrackAtEnd, static_cast<int>(run.jumps.size()) / 2);
}

// The toggle survives a restart: start() puts it back into the rebuilt world.
TEST(MarblesOnWireTest, VelocityPassToggleIsAppliedAgainAfterARestart) {
    const SceneEntry* entry = findBuiltinScene("marbles_on_wire");
    ASSERT_NE(entry, nullptr);
    LiveScene scene(entry->build(), entry);
    ASSERT_TRUE(scene.script()->setKnob(scene.instance(), "velocity_pass", 0.0));
    scene.step();
    scene.restart();
    EXPECT_FALSE(scene.world().settings().velocityPass);
}

}  // namespace
}  // namespace substep
