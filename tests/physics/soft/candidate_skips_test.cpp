// Tests engine/physics/soft/candidate_skips.h: the candidates' skip test keeps exactly the
// candidates whose particle may be within the margin, eight at a time as one at a time, over random
// candidate lists of every length around the vector width: particles that repeat, in any order
// and far apart in the array, gaps below, at and above the margin (−∞ for a moving body, NaN),
// displacements just inside and outside the slack, ±0 and far-from-origin coordinates.
#include "physics/soft/candidate_skips.h"

#include "physics/soft/element_batch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace substep {
namespace {

/// The candidates the test must keep, written out from its definition.
std::vector<uint32_t> expectedKept(const CandidateSkips& skips, const std::vector<Vec3>& x, double margin) {
    std::vector<uint32_t> kept;
    for (size_t i = 0; i < skips.size(); ++i) {
        const Vec3 origin(skips.originX[i], skips.originY[i], skips.originZ[i]);
        const double slack = skips.gap[i] - margin;
        const bool skipped = slack > 0.0 && (x[skips.particle[i]] - origin).squaredNorm() < slack * slack;
        if (!skipped) kept.push_back(static_cast<uint32_t>(i));
    }
    return kept;
}

std::vector<uint32_t> keptBy(const CandidateSkips& skips, const std::vector<Vec3>& x, double margin, SkipLanes lanes) {
    std::vector<uint32_t> kept(skips.size() + 1, 0xdeadbeef);
    const size_t count = keepUnskipped(skips, x.data(), margin, kept.data(), lanes);
    EXPECT_LE(count, skips.size());
    EXPECT_EQ(kept[skips.size()], 0xdeadbeef) << "wrote past its room";
    kept.resize(count);
    return kept;
}

struct SkipCase {
    CandidateSkips skips;
    std::vector<Vec3> x;
    double margin = 0.0;
};

/// `runs`: of ten candidates, how many take the particle after the last one's (10: only runs).
SkipCase randomCase(std::mt19937_64& rng, size_t count, int runs) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::uniform_int_distribution<int> kind(0, 9);
    SkipCase c;
    c.margin = kind(rng) == 0 ? 0.0 : 0.01 * unit(rng);
    const size_t particles = 1 + count / 2 + static_cast<size_t>(kind(rng)) * 1000;
    const double far = kind(rng) < 2 ? 1e6 : 10.0;  // far from the origin: coordinates of many ulps
    c.x.resize(particles);
    for (Vec3& p : c.x) p = Vec3(far * (2 * unit(rng) - 1), far * (2 * unit(rng) - 1), far * (2 * unit(rng) - 1));
    std::uniform_int_distribution<size_t> anyParticle(0, particles - 1);
    size_t next = anyParticle(rng);
    for (size_t i = 0; i < count; ++i) {
        // Runs of consecutive particles, as a tyre's candidates come, and jumps.
        const size_t particle = kind(rng) < runs ? next++ % particles : anyParticle(rng);
        const Vec3& p = c.x[particle];
        double gap = 0.0;
        Vec3 origin = p;
        switch (kind(rng)) {
            case 0: gap = -std::numeric_limits<double>::infinity(); break;  // a moving body
            case 1: gap = std::numeric_limits<double>::quiet_NaN(); break;
            case 2: gap = c.margin; break;                        // no slack: kept
            case 3: gap = c.margin * unit(rng); break;            // inside the margin: kept
            case 4: origin = p, gap = c.margin + 1e-300; break;   // not moved, a denormal's slack
            default: {
                // Moved by about the slack: just inside or just outside it.
                const double slack = 0.05 * unit(rng) + 1e-12;
                gap = c.margin + slack;
                const Vec3 direction = Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5).normalized();
                const double moved = slack * (kind(rng) < 5 ? 1.0 - 1e-15 * kind(rng) : 1.0 + 1e-15 * kind(rng));
                origin = p - moved * direction;
                if (kind(rng) == 0) origin = Vec3(-0.0, p.y(), 0.0);  // signed zeros
            }
        }
        c.skips.add(origin, gap, static_cast<uint32_t>(particle));
    }
    return c;
}

TEST(CandidateSkips, EightAtATimeKeepTheSameCandidatesAsOneAtATime) {
    std::mt19937_64 rng(20261126);
    size_t skippedSome = 0, keptSome = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const size_t count = trial < 40 ? static_cast<size_t>(trial) : 40 + static_cast<size_t>(rng() % 3000);
        const SkipCase c = randomCase(rng, count, trial % 3 == 0 ? 10 : 7);
        const std::vector<uint32_t> expected = expectedKept(c.skips, c.x, c.margin);
        ASSERT_EQ(keptBy(c.skips, c.x, c.margin, SkipLanes::One), expected) << "trial " << trial;
        ASSERT_EQ(keptBy(c.skips, c.x, c.margin, SkipLanes::Widest), expected) << "trial " << trial;
        skippedSome += expected.size() < count;
        keptSome += !expected.empty();
    }
    // The cases exercise both outcomes.
    EXPECT_GT(skippedSome, 300u);
    EXPECT_GT(keptSome, 300u);
    if (!wideElementLanes()) GTEST_SKIP() << "no AVX-512 here: only one at a time was tested";
}

TEST(CandidateSkips, FilterInPlaceKeepsTheRecordsTogether) {
    CandidateSkips skips;
    for (uint32_t i = 0; i < 5; ++i) skips.add(Vec3(i, 10.0 + i, 20.0 + i), 0.5 * i, 100 + i);
    skips.move(3, 1), skips.move(4, 2), skips.resize(3);
    ASSERT_EQ(skips.size(), 3u);
    EXPECT_EQ(skips.particle[1], 103u);
    EXPECT_EQ(skips.originY[1], 13.0);
    EXPECT_EQ(skips.gap[2], 2.0);
    EXPECT_EQ(skips.originZ[2], 24.0);
    skips.clear();
    EXPECT_EQ(skips.size(), 0u);
    uint32_t kept[1] = {7};
    EXPECT_EQ(keepUnskipped(skips, nullptr, 0.0, kept), 0u);
    EXPECT_EQ(kept[0], 7u);
}

}  // namespace
}  // namespace substep
