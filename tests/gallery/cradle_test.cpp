// Tests sandbox/scenes/cradle.cpp, the paper's Fig. 12: with the velocity pass (paper 3.6) the
// striker's speed passes through the row of three to the far marble and the rest stop; with
// plain PBD velocities (the "velocity pass" toggle off) the marbles share the striker's momentum
// and the far one gets much less. tests/physics/contact_test.cpp checks the bare impulse
// transfer in zero gravity; this checks the scene as it runs, rolling on its ground, through its
// knobs.

#include "scenes/live_scene.h"
#include "scenes/scene_registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>

namespace substep {
namespace {

BodyId namedBody(const SceneInstance& scene, std::string_view name) {
    for (const auto& [bodyName, id] : scene.namedBodyIds())
        if (bodyName == name) return id;
    return {};
}

/// Velocities of the four marbles, far marble first, striker last.
struct Snapshot {
    std::array<Vec3, 4> v;
    std::array<Vec3, 4> omega;
};

struct CradleRun {
    Snapshot before;  ///< the frame before the far marble moved
    Snapshot after;   ///< the frame its speed peaked: the hit is over, friction only slows it
    double radius = 0.0;
    double pairFriction = 0.0;  ///< marble on ground: the average of the two (paper 3.5)
    double dt = 0.0;
};

/// Runs the scene with the given knobs for 1.5 s and catches the hit.
CradleRun runCradle(bool velocityPass, double speed, double restitution) {
    const SceneEntry* entry = findBuiltinScene("cradle");
    EXPECT_NE(entry, nullptr);
    LiveScene scene(entry->build(), entry);
    SceneScript* script = scene.script();
    EXPECT_NE(script, nullptr);
    EXPECT_TRUE(script->setKnob(scene.instance(), "velocity_pass", velocityPass ? 1.0 : 0.0));
    EXPECT_TRUE(script->setKnob(scene.instance(), "striker_speed", speed));
    EXPECT_TRUE(script->setKnob(scene.instance(), "restitution", restitution));
    EXPECT_EQ(scene.world().settings().velocityPass, velocityPass);

    const std::array<BodyId, 4> ids{
        namedBody(scene.instance(), "marble0"), namedBody(scene.instance(), "marble1"),
        namedBody(scene.instance(), "marble2"), namedBody(scene.instance(), "striker")};
    for (BodyId id : ids)
        EXPECT_TRUE(scene.world().isValid(id));
    const Body& far = scene.world().body(ids[0]);
    const auto snapshot = [&] {
        Snapshot s;
        for (size_t i = 0; i < ids.size(); ++i) {
            s.v[i] = scene.world().body(ids[i]).v;
            s.omega[i] = scene.world().body(ids[i]).omega;
        }
        return s;
    };
    // Equal marbles: momentum and energy compare as sums of velocities.
    for (BodyId id : ids)
        EXPECT_DOUBLE_EQ(scene.world().body(id).mass, far.mass);

    CradleRun run{.radius = far.shape.radius, .dt = scene.description().dt};
    for (const Body& b : scene.world().bodies())
        if (b.shape.type == ShapeType::Plane)
            run.pairFriction = 0.5 * (std::max(b.staticFriction, b.dynamicFriction) +
                                      std::max(far.staticFriction, far.dynamicFriction));
    Snapshot previous = snapshot();
    bool moving = false;
    const int frames = static_cast<int>(1.5 / scene.description().dt);
    for (int frame = 0; frame < frames; ++frame) {
        scene.step();
        const double farSpeed = far.v.norm();
        if (!moving && farSpeed > 0.01 * speed) {
            moving = true;
            run.before = previous;
        }
        if (moving && farSpeed < previous.v[0].norm() - 1e-12) break;  // past its peak
        previous = snapshot();
        if (moving && frame + 1 == frames) break;
    }
    EXPECT_TRUE(moving) << "the striker never reached the row";
    run.after = previous;
    return run;
}

/// Σ v (per unit mass) and Σ ½ v² + ½ (2/5 r²) ω² (a solid sphere, per unit mass).
Vec3 momentum(const Snapshot& s) {
    return s.v[0] + s.v[1] + s.v[2] + s.v[3];
}
double translationalEnergy(const Snapshot& s) {
    double e = 0.0;
    for (const Vec3& v : s.v)
        e += 0.5 * v.squaredNorm();
    return e;
}
double kineticEnergy(const Snapshot& s, double radius) {
    double e = translationalEnergy(s);
    for (const Vec3& w : s.omega)
        e += 0.5 * 0.4 * radius * radius * w.squaredNorm();
    return e;
}

/// The ground's friction acts while the marbles slip: the far marble and the spinning striker
/// change speed by up to μ g dt each in the hit's frame, so momentum along the row holds within
/// that (g = 10, the paper's).
double frictionTolerance(const CradleRun& run) {
    return 2.0 * run.pairFriction * 10.0 * run.dt;
}

class CradleWithVelocityPass : public testing::TestWithParam<double> {};

// Fig. 12 middle: "The impulse is correctly transferred" — the far marble leaves with the
// striker's speed (the issue asks at least 90 %), the striker and the two in between stop.
TEST_P(CradleWithVelocityPass, FarMarbleLeavesWithTheStrikersSpeedAndTheRestStop) {
    const double speed = GetParam();
    const CradleRun run = runCradle(true, speed, 1.0);
    ASSERT_GT(run.radius, 0.0);
    const Snapshot& s = run.after;
    // The striker came from the right (+x), so the far marble leaves to the left.
    EXPECT_LT(s.v[0].x(), -0.9 * speed);
    EXPECT_LE(s.v[0].norm(), 1.0 * speed + 1e-9);
    for (int i = 1; i < 4; ++i)
        EXPECT_LT(s.v[i].norm(), 0.05 * speed) << "marble " << i;
    // Measured at 2 m/s: far marble 1.952 (friction already took 0.05 in the hit's frame),
    // others below 0.05 m/s; momentum 2.003 for 2.
    EXPECT_NEAR(momentum(s).x(), momentum(run.before).x(), frictionTolerance(run) + 0.01 * speed);
    EXPECT_NEAR(momentum(s).y(), 0.0, 0.01 * speed);
    EXPECT_LE(kineticEnergy(s, run.radius), kineticEnergy(run.before, run.radius) * (1.0 + 1e-6));
}

INSTANTIATE_TEST_SUITE_P(StrikerSpeeds, CradleWithVelocityPass, testing::Values(1.0, 2.0, 5.0));

// Fig. 12 bottom: "the situation after the hit when using the velocity derivation of PBD".
// Position corrections alone only push the overlaps apart; restitution 1 is ignored, the
// marbles share the striker's momentum and all move on, and kinetic energy is lost.
TEST(CradleTest, PlainPbdVelocitiesShareTheMomentumInsteadOfPassingIt) {
    const double speed = 2.0;
    const CradleRun run = runCradle(false, speed, 1.0);
    const Snapshot& s = run.after;
    // Measured: far marble 0.50 v0, the next ones 0.25 and 0.125 v0, the striker 0.125 v0 (each
    // push halves what it passes on).
    EXPECT_LT(s.v[0].norm(), 0.6 * speed);
    for (int i = 1; i < 4; ++i)
        EXPECT_LT(s.v[i].x(), -0.1 * speed) << "marble " << i << " stopped";
    // Plain PBD has no dynamic friction either (it lives in the velocity pass): momentum holds.
    EXPECT_NEAR(momentum(s).x(), momentum(run.before).x(), frictionTolerance(run) + 0.01 * speed);
    // Restitution 1 would keep ½ v0² of translational energy; measured 34 % of it.
    EXPECT_LT(translationalEnergy(s), 0.5 * translationalEnergy(run.before));
}

// The restitution knob: at 0 the hit is perfectly inelastic. With equal masses and momentum m v0
// conserved, the least kinetic energy four marbles can keep is (m v0)² / (2 · 4m), a quarter of
// the striker's translational ½ m v0²: the velocity pass reaches it (measured 24.7 %).
TEST(CradleTest, RestitutionZeroLosesWhatAPerfectlyInelasticHitLoses) {
    const double speed = 2.0;
    const CradleRun run = runCradle(true, speed, 0.0);
    const Snapshot& s = run.after;
    EXPECT_NEAR(translationalEnergy(s) / translationalEnergy(run.before), 0.25, 0.03);
    EXPECT_LT(s.v[0].norm(), 0.5 * speed);
    EXPECT_NEAR(momentum(s).x(), momentum(run.before).x(), frictionTolerance(run) + 0.01 * speed);
}

// The toggle survives a restart: start() puts the knobs back into the rebuilt world.
TEST(CradleTest, KnobsAreAppliedAgainAfterARestart) {
    const SceneEntry* entry = findBuiltinScene("cradle");
    ASSERT_NE(entry, nullptr);
    LiveScene scene(entry->build(), entry);
    ASSERT_TRUE(scene.script()->setKnob(scene.instance(), "velocity_pass", 0.0));
    ASSERT_TRUE(scene.script()->setKnob(scene.instance(), "striker_speed", 3.0));
    scene.step();
    scene.restart();
    EXPECT_FALSE(scene.world().settings().velocityPass);
    const BodyId striker = namedBody(scene.instance(), "striker");
    ASSERT_TRUE(scene.world().isValid(striker));
    EXPECT_NEAR(scene.world().body(striker).v.x(), -3.0, 1e-12);
}

}  // namespace
}  // namespace substep

namespace substep {
namespace {

double readout(LiveScene& scene, std::string_view label) {
    std::vector<SceneReadout> out;
    scene.script()->readouts(scene.instance(), out);
    for (const SceneReadout& each : out)
        if (each.label.rfind(label, 0) == 0) return each.value;
    ADD_FAILURE() << "no readout " << label;
    return 0.0;
}

// The window's readout is the paper's measure: the far marble's speed as it leaves (Fig. 12:
// 0.98 of the striker's), not its speed after the ground's friction has slowed it; plain PBD
// velocities pass on half (0.5). A restart measures afresh.
TEST(CradleReadout, ShowsTheFarMarblesLeavingSpeed) {
    const SceneEntry* entry = findBuiltinScene("cradle");
    LiveScene scene(entry->build(), entry);
    EXPECT_EQ(readout(scene, "far marble's leaving speed"), 0.0);  // before the hit
    for (int frame = 0; frame < 150; ++frame) scene.step();  // 2.5 s: hit at about 0.3 s
    const double leaving = readout(scene, "far marble's leaving speed");
    EXPECT_GT(leaving, 0.95);
    EXPECT_LE(leaving, 1.0);
    EXPECT_LT(readout(scene, "far marble speed / striker's initial"), leaving - 0.1);  // friction since

    ASSERT_TRUE(scene.script()->setKnob(scene.instance(), "velocity_pass", 0));
    scene.restart();
    EXPECT_EQ(readout(scene, "far marble's leaving speed"), 0.0);
    for (int frame = 0; frame < 60; ++frame) scene.step();
    EXPECT_NEAR(readout(scene, "far marble's leaving speed"), 0.5, 0.05);
}

}  // namespace
}  // namespace substep
