// Tests sandbox/scenes/rolling_balls.cpp, the paper's rolling ball sculpture (Figs. 1, 14):
// every marble goes round the whole circuit within 60 s, lifted by the paddle wheel, spaced out
// by the gate's wheel and moved by nothing else; none leaves the sculpture in 120 s nor sinks
// into a wire by more than 0.5 mm; and in the spring the fastest marble's path turns by 90° or
// more within one frame while it stays on the wires (paper section 4); the see-saw switch of
// the drop sends the marbles alternately into its left and right branch, which rejoin at the
// funnel, every marble in turn. Everything is measured on the marbles' own states against the
// wires' curves (their closest points), not taken from the script.
// The 10-minute run is rolling_balls_soak_test.cpp (label `stability`).

#include "scenes/live_scene.h"
#include "scenes/scene_registry.h"

#include "physics/collision/spline_tube.h"
#include "physics/contact.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace substep {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;

const SceneEntry& rollingBalls() {
    const SceneEntry* entry = findBuiltinScene("rolling_balls");
    EXPECT_NE(entry, nullptr);
    return *entry;
}

/// The sculpture as the tests see it: its wires, marbles and bounds.
struct Sculpture {
    std::vector<const SplineTube*> wires;  ///< every tube: wires and pipes
    std::array<std::vector<const SplineTube*>, 2> branches;  ///< the drop's left and right wires
    std::vector<BodyId> marbles;
    double marbleRadius = 0.0;
    Aabb bounds;     ///< of the wires, grown by a marble diameter
    double top = 0;  ///< the highest point of the wires' centre lines (m)
};

Sculpture findSculpture(const SceneInstance& scene) {
    Sculpture s;
    for (const Body& b : scene.world().bodies())
        if (b.alive && b.shape.type == ShapeType::Spline) {
            // The wires are static bodies at the origin: their curves are in world coordinates.
            EXPECT_LT(b.x.norm() + (b.userPosition() - b.x).norm(), 1e-12);
            s.wires.push_back(b.shape.spline.get());
            s.bounds.grow(b.shape.spline->tree.bounds());
        }
    for (const auto& [name, id] : scene.namedBodyIds()) {
        if (name.starts_with("marble_") && scene.world().isValid(id)) s.marbles.push_back(id);
        for (int b = 0; b < 2; ++b)
            if (name.starts_with(b == 0 ? "left_" : "right_"))
                s.branches[b].push_back(scene.world().body(id).shape.spline.get());
    }
    if (!s.marbles.empty()) s.marbleRadius = scene.world().body(s.marbles[0]).shape.radius;
    s.top = s.bounds.max.y();
    s.bounds = s.bounds.inflated(2.0 * s.marbleRadius);
    return s;
}

/// The gap between a marble and the nearest wire or pipe surface (negative: sunk into it).
double nearestGap(const std::vector<const SplineTube*>& wires, double marbleRadius, const Vec3& centre) {
    double gap = std::numeric_limits<double>::infinity();
    for (const SplineTube* wire : wires) {
        const SplinePoint p = wire->closestPoint(centre, 0.1);
        if (p.segment < 0) continue;
        const double d = std::sqrt(p.distanceSquared);
        if (!wire->hollow) {
            gap = std::min(gap, d - wire->radius - marbleRadius);
        } else if (d < wire->radius && p.t > 0.0 && p.t < 1.0) {
            // Inside a pipe (a centre outside it or past its open ends does not meet it).
            gap = std::min(gap, wire->radius - marbleRadius - d);
        }
    }
    return gap;
}

double nearestGap(const Sculpture& s, const Vec3& centre) { return nearestGap(s.wires, s.marbleRadius, centre); }

/// A marble entering one of the drop's branches: when, and which (0 left, 1 right).
struct Passage {
    double time;
    int branch;
};

/// What a run did to the marbles.
struct CircuitRun {
    std::vector<double> circuitTime;  ///< per marble: when it first came back to its start after
                                      ///< passing the top of the lift (s); infinity if never
    double deepestSink = 0.0;         ///< largest overlap of a marble with a wire (m)
    Vec3 deepestAt = Vec3::Zero();    ///< where that marble was then
    int framesOutside = 0;            ///< marble-frames outside the sculpture's bounds
    double largestTurn = 0.0;         ///< largest turn of a velocity in one frame, on the wires (rad)
    double speedAtLargestTurn = 0.0;  ///< that marble's speed then (m/s)
    double fastestOnTurn = 0.0;       ///< turn of the fastest marble whose path turned > 45° (rad)
    std::vector<Passage> passages;    ///< through the switch, in time order
    bool finite = true;
};

CircuitRun runCircuit(LiveScene& scene, double seconds) {
    const Sculpture s = findSculpture(scene.instance());
    const World& world = scene.world();
    const size_t n = s.marbles.size();
    CircuitRun run;
    run.circuitTime.assign(n, std::numeric_limits<double>::infinity());
    std::vector<Vec3> start(n), previousVelocity(n);
    std::vector<bool> passedTop(n, false), leftStart(n, false);
    std::vector<double> previousGap(n);
    std::vector<double> lastInBranch(n, -1e9);
    for (size_t i = 0; i < n; ++i) {
        start[i] = world.body(s.marbles[i]).x;
        previousVelocity[i] = world.body(s.marbles[i]).v;
        previousGap[i] = nearestGap(s, start[i]);
    }
    const long long frames = std::lround(seconds / scene.description().dt);
    for (long long frame = 1; frame <= frames; ++frame) {
        scene.step();
        if (!world.isFinite()) {
            run.finite = false;
            return run;
        }
        double fastest = 0.0, fastestTurn = 0.0;
        for (size_t i = 0; i < n; ++i) {
            const Body& marble = world.body(s.marbles[i]);
            const Vec3& x = marble.x;
            if (!s.bounds.contains({x, x})) ++run.framesOutside;
            const double gap = nearestGap(s, x);
            if (-gap > run.deepestSink) {
                run.deepestSink = -gap;
                run.deepestAt = x;
            }
            // A circuit: up the lift to the top, then round to where it started.
            if (x.y() > s.top - 0.05) passedTop[i] = true;
            const double fromStart = (x - start[i]).norm();
            if (fromStart > 0.1) leftStart[i] = true;
            if (passedTop[i] && leftStart[i] && fromStart < 0.02 && !std::isfinite(run.circuitTime[i]))
                run.circuitTime[i] = scene.time();
            // The turn of its path over the frame, counted while it touches a wire (within
            // 1 mm) at both ends of the frame, faster than 1 m/s ...
            const double turn = std::atan2(previousVelocity[i].cross(marble.v).norm(),
                                           previousVelocity[i].dot(marble.v));
            // and runs on at nearly its speed (a turn along the wires, not a knock).
            const double speed = marble.v.norm();
            const double speedBefore = previousVelocity[i].norm();
            if (gap < 0.001 && previousGap[i] < 0.001 && speedBefore > 1.0 &&
                std::abs(speed - speedBefore) < 0.25 * speedBefore) {
                if (turn > run.largestTurn) {
                    run.largestTurn = turn;
                    run.speedAtLargestTurn = marble.v.norm();
                }
                if (turn > 45.0 * kDegree && marble.v.norm() > fastest) {
                    fastest = marble.v.norm();
                    fastestTurn = turn;
                }
            }
            previousVelocity[i] = marble.v;
            previousGap[i] = gap;
            // A passage: touching a branch's wires for the first time in a second.
            for (int b = 0; b < 2; ++b) {
                if (s.branches[b].empty() || nearestGap(s.branches[b], s.marbleRadius, x) > 0.001) continue;
                if (scene.time() - lastInBranch[i] > 1.0) run.passages.push_back({scene.time(), b});
                lastInBranch[i] = scene.time();
            }
        }
        run.fastestOnTurn = std::max(run.fastestOnTurn, fastestTurn);
    }
    return run;
}

/// One 120 s run shared by the tests that only watch it.
const CircuitRun& defaultRun() {
    static const CircuitRun run = [] {
        LiveScene scene(rollingBalls().build(), &rollingBalls());
        return runCircuit(scene, 120.0);
    }();
    return run;
}

TEST(RollingBalls, BuildsTwentyOrMoreNamedMarblesOnWireTubes) {
    LiveScene scene(rollingBalls().build(), &rollingBalls());
    const Sculpture s = findSculpture(scene.instance());
    EXPECT_GE(s.marbles.size(), 20u);
    EXPECT_GE(s.wires.size(), 2u);
    EXPECT_TRUE(scene.instance().world().isValid(scene.instance().bodyIdNamed("marble_00")));
    EXPECT_EQ(scene.description().substeps, 10);  // Table 1
    // Every marble starts resting on the wires: touching, not sunk.
    for (BodyId id : s.marbles) {
        const double gap = nearestGap(s, scene.world().body(id).x);
        EXPECT_LT(std::abs(gap), 1e-4);
    }
}

TEST(RollingBalls, EveryMarbleCompletesACircuitWithinAMinute) {
    const CircuitRun& run = defaultRun();
    ASSERT_TRUE(run.finite);
    for (size_t i = 0; i < run.circuitTime.size(); ++i) {
        std::printf("marble_%02zu: circuit after %.1f s\n", i, run.circuitTime[i]);
        EXPECT_LE(run.circuitTime[i], 60.0) << "marble_" << i;
    }
}

TEST(RollingBalls, NoMarbleLeavesTheSculptureOrSinksIntoAWire) {
    const CircuitRun& run = defaultRun();
    ASSERT_TRUE(run.finite);
    std::printf("deepest sink into a wire over 120 s: %.3f mm, at (%.3f, %.3f, %.3f)\n", 1e3 * run.deepestSink,
                run.deepestAt.x(), run.deepestAt.y(), run.deepestAt.z());
    EXPECT_EQ(run.framesOutside, 0);
    EXPECT_LE(run.deepestSink, 0.0005);
}

// Failed first: with the restitution sweeps (the scene key "restitution": "swept"), a
// resting contact's push was replaced with nothing, and the marbles sank 1.5 mm into the
// wires while only 198 of 220 passages through the switch alternated.
TEST(RollingBalls, WithSweptRestitutionNoMarbleSinksAndTheSwitchStillAlternates) {
    LiveScene scene(rollingBalls().build(), &rollingBalls());
    ecs::PhysicsSystem physics = scene.physics();
    WorldSettings settings = physics.settings();
    settings.sweptRestitution = true;
    physics.setSettings(settings);
    const CircuitRun run = runCircuit(scene, 120.0);
    ASSERT_TRUE(run.finite);
    ASSERT_TRUE(scene.world().settings().sweptRestitution);
    std::printf("swept: deepest sink %.3f mm; %zu passages\n", 1e3 * run.deepestSink, run.passages.size());
    EXPECT_LE(run.deepestSink, 0.0005);
    int alternated = 0;
    for (size_t k = 1; k < run.passages.size(); ++k) alternated += run.passages[k].branch != run.passages[k - 1].branch;
    ASSERT_GE(run.passages.size(), 100u);
    EXPECT_GE(alternated, 0.95 * static_cast<double>(run.passages.size() - 1));
}

// Failed first: with six spokes 60° apart the gate's entering spoke met the marble queued
// behind the held one on its uphill flank, pinned it sideways against the far wires and,
// its drive's target running on, pressed 4.4 mm into it within 10 s with the restitution
// sweeps (gate_1 on marble_13 at frame 546) and 3.2 mm without (gate_1 on marble_14, frame
// 545), past the gallery capture's 4 mm bound. Eight spokes 45° apart push it back uphill.
TEST(RollingBalls, TheGateNeverPressesIntoAQueuedMarble) {
    for (const bool swept : {false, true}) {
        SCOPED_TRACE(swept ? "swept restitution" : "the paper's restitution");
        LiveScene scene(rollingBalls().build(), &rollingBalls());
        ecs::PhysicsSystem physics = scene.physics();
        WorldSettings settings = physics.settings();
        settings.sweptRestitution = swept;
        physics.setSettings(settings);
        std::vector<bool> gate(scene.world().bodies().size(), false);
        int spokes = 0;
        for (const auto& [name, id] : scene.instance().namedBodyIds())
            if (name.starts_with("gate_")) gate[id.index] = true, ++spokes;
        ASSERT_GT(spokes, 0);
        double deepest = 0.0;
        for (int frame = 0; frame < 600; ++frame) {  // the gallery capture's 10 s
            scene.step();
            const World& world = scene.world();
            const std::span<const Body> bodies = world.bodies();
            for (const ContactPair& pair : world.contactPairs()) {
                if (!gate[pair.body0] && !gate[pair.body1]) continue;
                for (uint32_t i = pair.first; i < pair.first + pair.count; ++i)
                    deepest = std::max(deepest, contactDepth(world.contacts()[i], bodies[pair.body0], bodies[pair.body1]));
            }
        }
        std::printf("%s: deepest spoke-marble overlap over 10 s %.3f mm\n", swept ? "swept" : "paper", 1e3 * deepest);
        EXPECT_LT(deepest, 0.001);
    }
}

TEST(RollingBalls, TheFastestMarbleTurnsAQuarterTurnPerFrameInTheSpring) {
    // Paper section 4: "the marbles perform a quarter turn in a single time step". Only turns
    // made on the wires count (a marble touching a wire at both ends of the frame).
    const CircuitRun& run = defaultRun();
    ASSERT_TRUE(run.finite);
    std::printf("largest turn per frame on the wires: %.0f deg at %.2f m/s; fastest marble: %.0f deg\n",
                run.largestTurn / kDegree, run.speedAtLargestTurn, run.fastestOnTurn / kDegree);
    EXPECT_GE(run.fastestOnTurn, 90.0 * kDegree);
}

TEST(RollingBalls, TheSwitchSendsMarblesAlternatelyLeftAndRight) {
    // The see-saw switch turns each marble to the side its beam is raised on and is tipped over
    // by it, so the next marble goes the other way. Every passage counts: marbles lifted
    // together by one arm (25 mm apart, 35 ms at the arm's speed) are spaced out by the gate
    // before they reach the switch, which needs the beam to have tipped before the next lands.
    const CircuitRun& run = defaultRun();
    ASSERT_TRUE(run.finite);
    int alternated = 0;
    std::array<int, 2> taken{0, 0};
    for (size_t k = 1; k < run.passages.size(); ++k) {
        ++taken[run.passages[k].branch];
        alternated += run.passages[k].branch != run.passages[k - 1].branch;
    }
    std::printf("%zu passages in 120 s, %d of %zu alternated; left %d, right %d\n", run.passages.size(),
                alternated, run.passages.size() - 1, taken[0], taken[1]);
    ASSERT_GE(run.passages.size(), 100u);
    // Without the gate 85-92 % alternated (pairs from one arm follow each other).
    EXPECT_GE(alternated, 0.95 * static_cast<double>(run.passages.size() - 1));
    // Both branches carry their share.
    EXPECT_GE(taken[0], static_cast<int>(0.4 * run.passages.size()));
    EXPECT_GE(taken[1], static_cast<int>(0.4 * run.passages.size()));
}

TEST(RollingBalls, TheScriptReportsTheSpringTurnAndLaps) {
    LiveScene scene(rollingBalls().build(), &rollingBalls());
    for (int frame = 0; frame < 40 * 60; ++frame) scene.step();
    std::vector<SceneReadout> out;
    scene.script()->readouts(scene.instance(), out);
    ASSERT_EQ(out.size(), 5u);
    EXPECT_GE(out[0].value, 1.0);   // laps completed
    EXPECT_EQ(out[1].value, 24.0);  // marbles on the track
    EXPECT_GE(out[4].value, 90.0);  // largest turn per frame in the spring (deg)
}

TEST(RollingBalls, WithTheLiftStoppedNoMarbleReachesTheTop) {
    // Nothing but the paddle wheel brings the marbles up: stopped, they all gather at its foot.
    LiveScene scene(rollingBalls().build(), &rollingBalls());
    ASSERT_TRUE(scene.script()->setKnob(scene.instance(), "lift_speed", 0.0));
    const Sculpture s = findSculpture(scene.instance());
    double highest = 0.0;
    for (int frame = 0; frame < 30 * 60; ++frame) {
        scene.step();
        if (frame > 20 * 60)
            for (BodyId id : s.marbles) highest = std::max(highest, scene.world().body(id).x.y());
    }
    EXPECT_LT(highest, s.top - 0.8);
}

TEST(RollingBalls, TheMarblesKnobTakesMarblesOut) {
    LiveScene scene(rollingBalls().build(), &rollingBalls());
    ASSERT_TRUE(scene.script()->setKnob(scene.instance(), "marbles", 20));
    EXPECT_EQ(findSculpture(scene.instance()).marbles.size(), 20u);
    scene.restart();
    EXPECT_EQ(findSculpture(scene.instance()).marbles.size(), 20u);
    for (int frame = 0; frame < 60; ++frame) scene.step();
    EXPECT_TRUE(scene.world().isFinite());
}

TEST(RollingBalls, FollowingAMarbleAimsTheCameraAtIt) {
    LiveScene scene(rollingBalls().build(), &rollingBalls());
    EXPECT_FALSE(scene.script()->camera(scene.instance()).has_value());
    ASSERT_TRUE(scene.script()->setKnob(scene.instance(), "follow", 4));  // marble_03
    for (int frame = 0; frame < 30; ++frame) scene.step();
    const std::optional<SceneCamera> camera = scene.script()->camera(scene.instance());
    ASSERT_TRUE(camera.has_value());
    const Vec3& marble = scene.world().body(scene.instance().bodyIdNamed("marble_03")).x;
    EXPECT_LT((camera->target - marble).norm(), 1e-12);
    EXPECT_LT((camera->position - marble).norm(), 0.5);
}

}  // namespace
}  // namespace substep
