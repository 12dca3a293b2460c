// Stability of hard joints under large mass ratios (docs/STABILITY.md): a light body holding a
// heavy one below it, a chain of alternating masses, and the steady gap of ERRATA item 7
// against the substep count.

#include "stability_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace substep::stability {
namespace {

const Vec3 kCeiling(0.0, 2.0, 0.0);
constexpr double kHeavyMass = 1.0;
const Vec3 kLightSize(0.04, 0.04, 0.04);
const Vec3 kHeavySize(0.2, 0.2, 0.2);

/// A light box hung from the ceiling by a hard attachment at its top face, holding a heavy box
/// by a second one at its bottom face (Fig. 6 with α = 0), the pair turned by `tilt` about z
/// around the ceiling anchor.
struct HangingPair {
    World world;
    BodyId light, heavy;

    HangingPair(double ratio, int substeps, double tilt, bool blockSolve = true)
        : world(WorldSettings{.gravity = Vec3(0, -kG, 0), .substeps = substeps, .blockSolve = blockSolve}) {
        const Quat turn(Eigen::AngleAxisd(tilt, Vec3::UnitZ()));
        const Vec3 lightCentre = kCeiling + turn * Vec3(0, -kLightSize.y() / 2, 0);
        const Vec3 heavyCentre = kCeiling + turn * Vec3(0, -kLightSize.y() - kHeavySize.y() / 2, 0);
        light = world.createBody({.shape = boxShape(kLightSize),
                                  .mass = kHeavyMass / ratio,
                                  .position = lightCentre,
                                  .orientation = turn});
        heavy = world.createBody({.shape = boxShape(kHeavySize),
                                  .mass = kHeavyMass,
                                  .position = heavyCentre,
                                  .orientation = turn});
        world.createJoint({.type = JointType::Distance,
                           .body1 = light,
                           .anchor0 = kCeiling,
                           .anchor1 = Vec3(0, kLightSize.y() / 2, 0)});
        world.createJoint({.type = JointType::Distance,
                           .body0 = light,
                           .body1 = heavy,
                           .anchor0 = Vec3(0, -kLightSize.y() / 2, 0),
                           .anchor1 = Vec3(0, kHeavySize.y() / 2, 0)});
    }

    /// Gap between the ceiling anchor and the light box's top (m).
    double topGap() const {
        return (test::userPoint(world.body(light), Vec3(0, kLightSize.y() / 2, 0)) - kCeiling)
            .norm();
    }
};

std::string ratioTag(double ratio) {
    return "1e" + std::to_string(static_cast<int>(std::lround(std::log10(ratio))));
}

std::string ratioName(const ::testing::TestParamInfo<double>& param) {
    return ratioTag(param.param);
}

/// The value for the ratio 1e3, 1e4 or 1e6.
int byRatio(double ratio, int at1e3, int at1e4, int at1e6) {
    return ratio < 5e3 ? at1e3 : (ratio < 1e5 ? at1e4 : at1e6);
}

// A light box holding a heavy one, swinging from 30°, 5 s. Holds: finite, no energy gained beyond
// 0.5 % of m_heavy g L (L = 0.24 m, the pair's length), every joint within 1 cm.
// A hard joint whose lighter body has mass m behaves as a spring of compliance h²/m when it holds
// a heavier one (each substep the heavy body recovers m/(m + M) of the gap): the gap sags to about
// (M/m) g h² and rings around it with period 2π h sqrt(M/m). So the joint error grows as the mass
// ratio times h², and a 1 cm bound needs h < sqrt(0.01 m / (2 (M/m) g)).
// Measured (docs/STABILITY.md): no longer blows up; the 1 mg box of 1e6 gains at most 1.2 J
// (0.5x its 2.35 J, at 320 substeps; 62 J at 80 before the exact-rotation fix).
class MassRatioPairTest : public ::testing::TestWithParam<double> {};

TEST_P(MassRatioPairTest, LightBodyHoldsHeavyBody) {
    const double ratio = GetParam();
    const double scale = kHeavyMass * kG * 0.24;
    const Bounds bounds{.energyGain = 0.005 * scale, .jointError = 0.01};
    const std::string name = "pair_" + ratioTag(ratio);
    const Sweep sweep =
        sweepSubsteps(name, {5, 10, 20, 40, 80, 160, 320, 640, 1280}, bounds, [&](int substeps) {
            HangingPair rig(ratio, substeps, kPi / 6);
            return watch(rig.world, 5.0);
        });
    // Predicted: 1 cm of joint error is reached at h² = 0.01 / (2 (M/m) g): 1e3 needs 24
    // substeps, 1e4 needs 75, 1e6 needs 750; measured: 40, 80 and 1280 of the list.
    const double predicted = kDt / std::sqrt(0.01 / (2.0 * ratio * kG));
    report(name + "_predicted_substeps", predicted);
    expectStable(name, sweep, scale, byRatio(ratio, 40, 80, 1280));
    EXPECT_LE(sweep.holdsFrom, 2.0 * predicted + 1.0);
}

INSTANTIATE_TEST_SUITE_P(Ratios, MassRatioPairTest, ::testing::Values(1e3, 1e4, 1e6), ratioName);

/// A chain of `links` bars (0.1 x 0.02 x 0.02 m) on hard hinges about z, alternating light and
/// heavy (light at the top), released horizontally from a world pivot.
struct AlternatingChain {
    static constexpr double kLength = 0.1;
    World world;

    AlternatingChain(double ratio, int substeps, int links)
        : world(WorldSettings{.gravity = Vec3(0, -kG, 0), .substeps = substeps}) {
        const Vec3 half(kLength / 2, 0, 0);
        BodyId previous;
        for (int i = 0; i < links; ++i) {
            const double mass = i % 2 == 0 ? kHeavyMass / ratio : kHeavyMass;
            const BodyId link =
                world.createBody({.shape = boxShape(Vec3(kLength, 0.02, 0.02)),
                                  .mass = mass,
                                  .position = kCeiling + Vec3(kLength * (i + 0.5), 0, 0),
                                  .collide = false});  // a joint case: links pass through each other
            world.createJoint({.type = JointType::Hinge,
                               .body0 = previous,
                               .body1 = link,
                               .anchor0 = i == 0 ? kCeiling : Vec3(half),
                               .anchor1 = -half,
                               .axis0 = Vec3::UnitZ(),
                               .axis1 = Vec3::UnitZ()});
            previous = link;
        }
    }
};

// Ten hinged bars alternating light and heavy, released horizontally, 5 s. Holds: finite, no
// energy gained beyond 0.5 % of the heavy links' potential energy above their lowest (27 J),
// every joint within 1 cm. Below that, each light link sits between two heavy ones whose pull
// (several times their weight while the chain whips) opens both its joints by the steady gap;
// once the gaps pass the link's own length the link is thrown about by the projections.
// ENGINE WEAK SPOT, still present (docs/STABILITY.md): this throws the light links about and
// spins the heavy ones. Measured on the current engine: 1e3 gains 261 J at 20 substeps (9.7x the
// 27 J) and nothing from 40; 1e4 gains 1.5 kJ at 80 (56x) and nothing from 160; 1e6 gains 340 J
// at 40 (12.6x), 40-150 J (1.3-5.5x) from 80 to 640 and 0.01 J at 1280. The motion is chaotic (a
// 1e-12 m/s nudge moved the gains between 290 and 670 J on the older engine), so the blow-up
// check applies from the present limit: 40 (1e3; 20 sits at the 10x line), 160 (1e4) and 80
// (1e6) substeps. It still fails if the chain blows up there, or holds later than documented.
class MassRatioChainTest : public ::testing::TestWithParam<double> {};

TEST_P(MassRatioChainTest, AlternatingChainSwings) {
    const double ratio = GetParam();
    constexpr int kLinks = 10;
    double scale = 0.0;  // Σ m g (L i + L/2) over the heavy (odd) links: 27 J
    for (int i = 1; i < kLinks; i += 2)
        scale += kHeavyMass * kG * AlternatingChain::kLength * (i + 0.5);
    const Bounds bounds{.energyGain = 0.005 * scale, .jointError = 0.01};
    const std::vector<int> counts{10, 20, 40, 80, 160, 320, 640, 1280};
    const std::string name = "chain_" + ratioTag(ratio);
    const Sweep sweep = sweepSubsteps(name, counts, bounds, [&](int substeps) {
        AlternatingChain rig(ratio, substeps, kLinks);
        return watch(rig.world, 5.0);
    });
    // Measured: 1e3 holds from 160, 1e4 from 640, 1e6 at no count up to 1280 (6.6 cm there).
    expectStable(name, sweep, scale, byRatio(ratio, 160, 640, 0), kDt, byRatio(ratio, 40, 160, 80));
}

INSTANTIATE_TEST_SUITE_P(Ratios, MassRatioChainTest, ::testing::Values(1e3, 1e4, 1e6), ratioName);

// ERRATA item 7: 1 g holding 1 kg, hanging still. With one pass per substep the top joint is
// solved first and closes; the bottom joint then drags the light box down by w_light λ, and at
// the fixed point (the heavy box recovers m/(m + M) of the bottom joint's (1 + M/m) g h² each
// substep, exactly the g h² it fell) the top gap at the end of every substep is (M/m) g h².
// The bottom joint is closed. ERRATA's "(1 + M/m) g h²" is the gap the bottom joint sees before
// its correction; the two differ by m/M = 0.1 %. Means over 10-20 s (the gap rings around its
// fixed point with period 2π h sqrt(M/m) and settles slowly). This is the joint-by-joint
// projection (WorldSettings::blockSolve off); the default block solve closes both joints
// (tests/physics/joint_block_solve_test.cpp).
TEST(SteadyGapTest, GapFollowsTheMassRatioTimesGHSquared) {
    const double ratio = 1000.0;
    double previous = 0.0;
    for (const int substeps : {10, 20, 40, 80}) {
        HangingPair rig(ratio, substeps, 0.0, /*blockSolve=*/false);
        const double h = kDt / substeps;
        double sum = 0.0;
        int samples = 0;
        test::runFor(rig.world, 20.0, [&](double t) {
            if (t <= 10.0) return;
            sum += rig.topGap();
            ++samples;
        });
        ASSERT_TRUE(rig.world.isFinite());
        const double gap = sum / samples;
        const double fixedPoint = ratio * kG * h * h;
        const double errata = (1.0 + ratio) * kG * h * h;
        const std::string tag = std::to_string(substeps);
        report("steady_gap_m_" + tag, gap);
        report("steady_gap_over_Mm_gh2_" + tag, gap / fixedPoint);
        report("steady_gap_over_errata_1_plus_Mm_gh2_" + tag, gap / errata);
        EXPECT_NEAR(gap, fixedPoint, 0.01 * fixedPoint) << substeps << " substeps";
        EXPECT_NEAR(gap, errata, 0.01 * errata) << substeps << " substeps";
        if (previous > 0.0) {
            report("steady_gap_ratio_to_half_the_substeps_" + tag, previous / gap);
            EXPECT_NEAR(previous / gap, 4.0, 0.1);  // h²
        }
        previous = gap;
    }
}

}  // namespace
}  // namespace substep::stability
