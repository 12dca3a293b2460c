// Tests engine/physics/soft/attachment_run.h: runs of attachments stepped in vector lanes
// (attachment_lanes.cpp) give the bits of the same runs stepped one after the other in turn
// (attachment_run.cpp), particles, multipliers and the bodies' poses, over random runs: one to
// eight of them, of unequal lengths (empty ones too), hard and soft attachments, static, moving
// and turning bodies, particles that repeat within a run, pinned particles, and particles right
// on their body's point (the link that changes nothing).
#include "physics/soft/attachment_run.h"

#include "physics/soft/element_batch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

namespace substep {
namespace {

/// Random runs with their attachments and particles.
struct RunsCase {
    std::vector<AttachmentRun> runs;
    std::vector<Attachment> attachments;
    std::vector<Vec3> x;
    std::vector<double> invMass;
    double invH2 = 0.0;
    /// Links that must change nothing (a particle on a still body's point).
    int resting = 0;
};

RunsCase randomRuns(std::mt19937_64& rng, int runCount) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_int_distribution<int> length(0, 40), kind(0, 5);
    const auto logUniform = [&](double low, double high) {
        return low * std::pow(high / low, 0.5 * (unit(rng) + 1.0));
    };
    const auto vector = [&](double scale) { return Vec3(Vec3(unit(rng), unit(rng), unit(rng)) * scale); };
    RunsCase c;
    c.invH2 = 1.0 / std::pow(logUniform(1e-4, 1e-2), 2);
    for (int k = 0; k < runCount; ++k) {
        AttachmentRun run;
        run.bodyIndex = static_cast<uint32_t>(k);
        const int body = kind(rng);  // 0: still, 1: moves without turning, else turns
        Quat q(unit(rng), unit(rng), unit(rng), unit(rng));
        q.normalize();
        run.rotation = q.toRotationMatrix();
        run.inverseMass = body == 0 ? 0.0 : logUniform(1e-2, 1e2);
        const Vec3 principal(logUniform(1e-1, 1e3), logUniform(1e-1, 1e3), logUniform(1e-1, 1e3));
        run.inverseInertia =
            body >= 2 ? Mat3(run.rotation * principal.asDiagonal() * run.rotation.transpose()) : Mat3::Zero();
        run.position = vector(std::pow(10.0, 2.0 * unit(rng)));
        run.turned = body >= 2 ? vector(1e-4) : Vec3::Zero();
        // The run's particles, a few of them held twice.
        const int links = length(rng);
        const uint32_t firstParticle = static_cast<uint32_t>(c.x.size());
        const int particles = links / 2 + 1;
        for (int p = 0; p < particles; ++p) {
            c.x.push_back(run.position + vector(0.5));
            c.invMass.push_back(kind(rng) == 0 ? 0.0 : logUniform(1e-1, 1e3));
        }
        run.next = c.attachments.size();
        std::uniform_int_distribution<uint32_t> pick(0, static_cast<uint32_t>(particles - 1));
        for (int n = 0; n < links; ++n) {
            Attachment a;
            a.particle = firstParticle + (n < particles ? static_cast<uint32_t>(n) : pick(rng));
            a.body = run.bodyIndex;
            a.local = vector(0.4);
            a.compliance = kind(rng) < 3 ? 0.0 : logUniform(1e-10, 1e-3);
            a.lambda = unit(rng) * 1e-3;
            const Vec3 point = run.position + run.rotation * a.local;
            if (n < particles) {
                // Right on a still body's point (r = R local, x_body + r − x = 0), or off it by
                // a random gap.
                const bool onThePoint = body == 0 && kind(rng) == 0;
                c.x[a.particle] = onThePoint ? point : point + vector(logUniform(1e-9, 1e-1));
                c.resting += onThePoint;
            }
            c.attachments.push_back(a);
        }
        run.end = c.attachments.size();
        c.runs.push_back(run);
    }
    return c;
}

bool sameBits(const Vec3& a, const Vec3& b) { return std::memcmp(a.data(), b.data(), sizeof(Vec3)) == 0; }
bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Everything the runs changed, bit for bit; false at the first difference (reported).
bool sameOutcome(const RunsCase& a, const RunsCase& b) {
    for (size_t k = 0; k < a.runs.size(); ++k) {
        EXPECT_EQ(a.runs[k].next, b.runs[k].next) << "run " << k;
        EXPECT_TRUE(sameBits(a.runs[k].position, b.runs[k].position)) << "run " << k << "'s position";
        EXPECT_TRUE(sameBits(a.runs[k].turned, b.runs[k].turned)) << "run " << k << "'s turn";
        if (a.runs[k].next != b.runs[k].next || !sameBits(a.runs[k].position, b.runs[k].position) ||
            !sameBits(a.runs[k].turned, b.runs[k].turned))
            return false;
    }
    for (size_t i = 0; i < a.x.size(); ++i)
        if (!sameBits(a.x[i], b.x[i])) {
            ADD_FAILURE() << "particle " << i;
            return false;
        }
    for (size_t n = 0; n < a.attachments.size(); ++n)
        if (!sameBits(a.attachments[n].lambda, b.attachments[n].lambda)) {
            ADD_FAILURE() << "attachment " << n << "'s lambda";
            return false;
        }
    return true;
}

/// The runs of `trials` random cases stepped one by one and by `inLanes`, bit for bit.
template <typename InLanes>
void expectTheBitsOfOneAfterTheOther(InLanes inLanes, int trials, int fewestRuns, int mostRuns, uint64_t seed) {
    std::mt19937_64 rng(seed);
    int resting = 0, moved = 0;
    long soft = 0;
    for (int trial = 0; trial < trials; ++trial) {
        const int runCount = fewestRuns + trial % (mostRuns - fewestRuns + 1);
        RunsCase oneByOne = randomRuns(rng, runCount);
        RunsCase lanes = oneByOne;
        const RunsCase before = oneByOne;
        solveAttachmentRuns(oneByOne.runs, oneByOne.attachments.data(), oneByOne.x.data(), oneByOne.invMass.data(),
                            oneByOne.invH2, AttachmentLanes::OneByOne);
        inLanes(lanes);
        ASSERT_TRUE(sameOutcome(oneByOne, lanes)) << "trial " << trial << ", " << runCount << " runs";
        resting += oneByOne.resting;
        for (size_t k = 0; k < oneByOne.runs.size(); ++k)
            moved += !sameBits(oneByOne.runs[k].position, before.runs[k].position);
        soft += std::count_if(oneByOne.attachments.begin(), oneByOne.attachments.end(),
                              [](const Attachment& a) { return a.compliance > 0.0; });
    }
    // Some links changed nothing (the lanes kept their bits), most bodies moved, and soft
    // attachments summed their λ.
    EXPECT_GT(resting, trials / 40);
    EXPECT_GT(moved, trials);
    EXPECT_GT(soft, 2 * trials);
}

TEST(AttachmentRuns, Avx2LanesGiveTheBitsOfOneAfterTheOther) {
    // The lanes' kernel itself, for one to four runs (solveAttachmentRuns steps a lone run one
    // by one).
    if (!attachmentVectorLanes()) GTEST_SKIP() << "no AVX2";
    expectTheBitsOfOneAfterTheOther(
        [](RunsCase& c) { solveAttachmentRunsInLanes(c.runs, c.attachments.data(), c.x.data(), c.invMass.data(), c.invH2); },
        4000, 1, 4, 20261125);
}

TEST(AttachmentRuns, WideLanesGiveTheBitsOfOneAfterTheOther) {
    if (!wideElementLanes()) GTEST_SKIP() << "no x86-64-v4";
    expectTheBitsOfOneAfterTheOther(
        [](RunsCase& c) {
            solveAttachmentRunsInWideLanes(c.runs, c.attachments.data(), c.x.data(), c.invMass.data(), c.invH2);
        },
        4000, 1, 4, 314159);
}

TEST(AttachmentRuns, MoreRunsThanLanesGiveTheBitsOfOneAfterTheOther) {
    // solveAttachmentRuns with five to eight runs: four in lanes, then the rest, as widest and
    // as AVX2 (each one by one on a CPU without them).
    for (const AttachmentLanes lanes : {AttachmentLanes::Avx2, AttachmentLanes::Widest})
        expectTheBitsOfOneAfterTheOther(
            [&](RunsCase& c) {
                solveAttachmentRuns(c.runs, c.attachments.data(), c.x.data(), c.invMass.data(), c.invH2, lanes);
            },
            1000, 5, 8, 7);
}

TEST(AttachmentRuns, ALinkClosesTheGapAsEq4Says) {
    // One hard attachment of a particle (w) to a still body's point: Δλ = c / w moves the
    // particle by w Δλ, onto the point, whichever lanes step it.
    for (const AttachmentLanes lanes : {AttachmentLanes::OneByOne, AttachmentLanes::Avx2, AttachmentLanes::Widest}) {
        AttachmentRun runs[2];
        std::vector<Attachment> attachments(2);
        std::vector<Vec3> x = {Vec3(1.0, 2.0, 3.5), Vec3(-4.0, 0.0, 0.25)};
        const std::vector<double> invMass = {2.0, 0.5};
        for (int k = 0; k < 2; ++k) {
            runs[k].position = Vec3(k, 2.0, 3.0);
            runs[k].next = k, runs[k].end = k + 1;
            attachments[k].particle = k;
            attachments[k].body = k;
        }
        solveAttachmentRuns(runs, attachments.data(), x.data(), invMass.data(), 1e4, lanes);
        for (int k = 0; k < 2; ++k) EXPECT_LT((x[k] - runs[k].position).norm(), 1e-14) << k;
    }
}

}  // namespace
}  // namespace substep
