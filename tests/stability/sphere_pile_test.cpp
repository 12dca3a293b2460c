// Tests the claims of the sphere-pile tests of tests/physics/sleep_islands_test.cpp and
// tests/physics/contact_restitution_test.cpp (engine/physics/sleep_islands.cpp,
// contact_restitution.cpp, contact.cpp) over layouts they were not tuned for: each pile dropped
// from starts shifted by up to 1 cm (sphere_piles.h, `seed`). A pile is
// chaotic, so what the tests of the default run state for one layout is stated here as a
// statistic over several, with bounds that say why.

#include "sphere_piles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace substep {
namespace {

constexpr uint32_t kLayouts = 6;  ///< seeds 1 to kLayouts, and spheres1000's own layout (seed 0)

// SleepIslandsTest.SettledSpherePileSleepsAndWakesWhenHit on seven layouts under either rule:
// what the sleep system owes every layout (to fall asleep once every ball rests, to wake the
// whole island no later than the frame of the first contact, never to let a pair link a
// sleeping body to an awake one, to sleep again) holds for each. The sleep thresholds are
// raised above the settled pile's creep (kPileSleep, sphere_piles.h): with the default ones,
// when the last ball of the creeping pile stops is the arrangement's business (at 372059e under
// the sweeps, 21.85 s for spheres1000's own layout, the first shifted layout still awake at 60 s).
void settledPilesOverLayouts(bool swept) {
    for (uint32_t seed = 0; seed <= kLayouts; ++seed) {
        const test::SettledPileRun run = test::settledSpherePile(
            {.sweptRestitution = swept, .seed = seed, .sleep = test::kPileSleep});
        std::printf("%s, layout %u: asleep at %.2f s, hit at frame %d, woke at %d, asleep again %.2f s after\n",
                    swept ? "swept" : "Eq. 34", seed, run.asleepAt, run.hitAt, run.wokeAt, run.againAt);
        std::fflush(stdout);
        SCOPED_TRACE("layout " + std::to_string(seed));
        ASSERT_GT(run.asleepAt, 0.0);
        ASSERT_GT(run.hitAt, 0);
        EXPECT_GT(run.wokeAt, 0);
        EXPECT_LE(run.wokeAt, run.hitAt);
        EXPECT_FALSE(run.hitTouchedSleeper);
        EXPECT_FALSE(run.sleepingMetAwake);
        EXPECT_EQ(run.sleepingAfterHit, 0);
        ASSERT_GT(run.againAt, 0.0);
        EXPECT_FALSE(run.contactsWhileAsleep);
        EXPECT_LT(run.ballAboveTop, 0.2 + 5e-3);
        EXPECT_TRUE(run.finite);
    }
}

TEST(SpherePileStabilityTest, SettledPilesSleepAndWakeWhenHitUnderTheSweeps) { settledPilesOverLayouts(true); }
TEST(SpherePileStabilityTest, SettledPilesSleepAndWakeWhenHitUnderEq34) { settledPilesOverLayouts(false); }

/// The median of `values` (the mean of the middle two for an even count).
double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// ContactRestitutionTest.APileOfSpheresComesToRestUnderEitherRule over eight layouts of each
// pile, the frictionless one included. A pile that keeps colliding (the bug that test records:
// 1.2e-3 J per sphere after 6 s, most spheres moving) moves the median; a layout that leaves a
// ball rolling (no rolling resistance) moves one sample. So: the median layout within the
// default test's bounds (1e-3 J per sphere, a fifth of the spheres above 2 cm/s) with a margin
// (a tenth), and of the piles with friction at most one layout in eight past those bounds.
// Measured at 372059e: at most 7.5e-4 J per sphere and 12 % moving with friction; without, the
// sweeps left 31 and 63 of 75 spheres moving in two layouts (the second 48 still after 12 s).
TEST(SpherePileStabilityTest, PilesComeToRestOverLayouts) {
    const test::Pile piles[] = {{},
                                {.side = 4, .layers = 4, .restitution = 0.5},
                                {.side = 6, .layers = 4, .restitution = 0.3, .mixed = true},
                                {.side = 5, .layers = 3, .restitution = 0.8, .friction = 0.0}};
    constexpr uint32_t kPileLayouts = 8;
    for (test::Pile pile : piles)
        for (bool sweep : {false, true}) {
            std::vector<double> moving, kinetic;
            int past = 0;
            for (uint32_t seed = 1; seed <= kPileLayouts; ++seed) {
                pile.seed = seed;
                const test::PileRun run = test::runPile(pile, sweep, 6.0);
                moving.push_back(double(run.moving) / run.spheres);
                kinetic.push_back(run.kinetic / run.spheres);
                past += kinetic.back() >= 1e-3 || moving.back() > 0.2;
                std::printf("%s pile of %zu, e %.1f%s%s, layout %u: kinetic %.3g J, %zu moving after 6 s\n",
                            sweep ? "swept" : "paper", run.spheres, pile.restitution, pile.mixed ? " mixed" : "",
                            pile.friction > 0.0 ? "" : " frictionless", seed, run.kinetic, run.moving);
            }
            std::fflush(stdout);
            SCOPED_TRACE(std::string(sweep ? "swept" : "paper") + ", e " + std::to_string(pile.restitution));
            EXPECT_LT(median(kinetic), 1e-3);
            EXPECT_LE(median(moving), 0.1);
            if (pile.friction > 0.0) {
                EXPECT_LE(past, 1);
            }
        }
}

// ContactRestitutionTest.AFrictionlessPileComesToRestWithoutGainingEnergy over eight layouts
// at e 0.5 and 0.8, with and without friction: under the sweeps no frame after landing gains
// more than that test's 0.03 J (Eq. 34 alone left up to 0.025 J over the sixteen frictionless
// layouts), and every frictionless layout is at rest by 6 s (the fixed sweeps: by 5.4 s; at
// 9e6f443 layout 5 at e 0.8 and layout 1 at e 0.5 still had 48 and 28 spheres moving at 12 s,
// rises after landing of 0.131 and 0.074 J). With friction a ball may roll for ever (no rolling
// resistance), so there only the energy is bounded.
TEST(SpherePileStabilityTest, PilesGainNoEnergyUnderTheSweepsOverLayouts) {
    for (const double friction : {0.0, 0.5})
        for (const double restitution : {0.8, 0.5})
            for (uint32_t seed = 1; seed <= 8; ++seed) {
                const test::Pile pile{.side = 5, .layers = 3, .restitution = restitution, .friction = friction,
                                      .seed = seed};
                const test::PileRun run = test::runPile(pile, true, 8.0);
                std::printf("pile of 75, e %.1f, friction %.1f, layout %u: last moving at %.2f s, largest rise %.3g J\n",
                            restitution, friction, seed, run.lastMovingAt, run.largestRise);
                std::fflush(stdout);
                SCOPED_TRACE("e " + std::to_string(restitution) + ", friction " + std::to_string(friction) +
                             ", layout " + std::to_string(seed));
                EXPECT_LT(run.largestRise, 0.03);
                if (friction == 0.0) {
                    EXPECT_LT(run.lastMovingAt, 6.0);
                }
            }
}

// ContactRestitutionTest.AMixedPileFallsAsleepUnderEitherRule over six layouts of the 192 and
// of a 196 (e 0.5): that the sweeps do not delay sleeping is a claim about the typical pile, so
// the median time under the sweeps is at most 5 s past the median under Eq. 34 (the bug that
// test records doubled it: 15.9 s against 32.0 s), and at least four layouts in six fall
// asleep within 45 s under Eq. 34 (at 372059e all twelve did, 3.7 to 39.1 s). Under the sweeps
// the 196 stayed awake at 45 s in two layouts of six (372059e), so there only the median is
// bounded; a layout that never sleeps counts as 45 s in it.
TEST(SpherePileStabilityTest, MixedPilesFallAsleepOverLayouts) {
    const test::Pile piles[] = {{.side = 8, .layers = 3, .restitution = 0.3, .mixed = true, .sleeping = true},
                                {.side = 7, .layers = 4, .restitution = 0.5, .mixed = true, .sleeping = true}};
    for (test::Pile pile : piles) {
        std::vector<double> paper, swept;
        for (uint32_t seed = 1; seed <= 6; ++seed) {
            pile.seed = seed;
            const test::PileRun a = test::runPile(pile, false, 45.0);
            const test::PileRun b = test::runPile(pile, true, 45.0);
            std::printf("mixed pile of %zu, e %.1f, layout %u: asleep at %.2f s under Eq. 34, %.2f s under the sweeps\n",
                        a.spheres, pile.restitution, seed, a.asleepAt, b.asleepAt);
            std::fflush(stdout);
            paper.push_back(a.asleepAt < 0.0 ? 45.0 : a.asleepAt);
            swept.push_back(b.asleepAt < 0.0 ? 45.0 : b.asleepAt);
        }
        SCOPED_TRACE("e " + std::to_string(pile.restitution));
        const auto asleep = [](const std::vector<double>& times) {
            return std::count_if(times.begin(), times.end(), [](double t) { return t < 45.0; });
        };
        EXPECT_GE(asleep(paper), 4);
        EXPECT_LE(median(swept), median(paper) + 5.0);
    }
}

}  // namespace
}  // namespace substep
