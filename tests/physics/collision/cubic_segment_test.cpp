// Tests engine/physics/collision/cubic_segment.cpp: closest points on a cubic agree with dense
// sampling of the curve, by the scan and by Newton from a guess (the fast path a marble on a
// wire takes), and the Bézier bounds hold every point of the curve.

#include "physics/collision/cubic_segment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

namespace substep {
namespace {

constexpr int kDenseSamples = 50000;

/// Smallest squared distance from q over a dense sampling of the curve.
double denseDistance2(const CubicSegment& curve, const Vec3& q, double* tBest = nullptr) {
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= kDenseSamples; ++i) {
        const double t = static_cast<double>(i) / kDenseSamples;
        const double d2 = (curve.point(t) - q).squaredNorm();
        if (d2 < best) {
            best = d2;
            if (tBest) *tBest = t;
        }
    }
    return best;
}

Vec3 randomVec(std::mt19937& rng, double scale) {
    std::uniform_real_distribution<double> u(-scale, scale);
    return {u(rng), u(rng), u(rng)};
}

TEST(CubicSegment, HermiteEndsAndTangents) {
    const Vec3 p0(1, 2, 3), m0(0.5, -1, 2), p1(-2, 0, 1), m1(3, 1, -1);
    const CubicSegment c = CubicSegment::hermite(p0, m0, p1, m1);
    EXPECT_TRUE(c.point(0).isApprox(p0));
    EXPECT_TRUE(c.point(1).isApprox(p1));
    EXPECT_TRUE(c.tangent(0).isApprox(m0));
    EXPECT_TRUE(c.tangent(1).isApprox(m1));
}

TEST(CubicSegment, BoundsHoldTheCurve) {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 50; ++trial) {
        const CubicSegment c = CubicSegment::hermite(randomVec(rng, 1), randomVec(rng, 3),
                                                     randomVec(rng, 1), randomVec(rng, 3));
        const Aabb box = c.bounds().inflated(1e-12);
        for (int i = 0; i <= 1000; ++i) {
            ASSERT_TRUE(box.contains({c.point(i / 1000.0), c.point(i / 1000.0)}));
        }
    }
}

TEST(CubicSegment, ClosestPointMatchesDenseSampling) {
    std::mt19937 rng(1);
    for (int trial = 0; trial < 200; ++trial) {
        // Tangents up to 3x the chord: curves that bend strongly, as Catmull-Rom pieces can.
        const CubicSegment c = CubicSegment::hermite(randomVec(rng, 1), randomVec(rng, 2),
                                                     randomVec(rng, 1), randomVec(rng, 2));
        const Vec3 q = randomVec(rng, 1.5);
        const SegmentClosest found = closestOnCubic(c, q);
        const double dense = denseDistance2(c, q);
        ASSERT_GE(found.t, 0.0);
        ASSERT_LE(found.t, 1.0);
        EXPECT_NEAR(found.distanceSquared, (c.point(found.t) - q).squaredNorm(), 1e-12);
        // Never worse than the dense scan (up to its own resolution), and as good as it.
        double tDense = 0;
        denseDistance2(c, q, &tDense);
        EXPECT_LE(std::sqrt(found.distanceSquared), std::sqrt(dense) + 1e-9)
            << "trial " << trial << " t " << found.t << " dense t " << tDense << " diff "
            << std::sqrt(found.distanceSquared) - std::sqrt(dense);
    }
}

TEST(CubicSegment, ClosestPointOnAStraightSegmentIsTheProjection) {
    // p(t) = (2t, 0, 0) written as a Hermite segment with chord tangents.
    const CubicSegment c =
        CubicSegment::hermite(Vec3::Zero(), Vec3(2, 0, 0), Vec3(2, 0, 0), Vec3(2, 0, 0));
    const SegmentClosest found = closestOnCubic(c, Vec3(0.7, 0.3, -0.4));
    EXPECT_NEAR(found.t, 0.35, 1e-12);
    EXPECT_NEAR(found.distanceSquared, 0.25, 1e-12);
    // Beyond the ends: the end points.
    EXPECT_EQ(closestOnCubic(c, Vec3(-1, 1, 0)).t, 0.0);
    EXPECT_EQ(closestOnCubic(c, Vec3(3, 1, 0)).t, 1.0);
}

TEST(CubicSegment, DegenerateSegmentIsAPoint) {
    const CubicSegment c{.c0 = Vec3(1, 1, 1)};
    const SegmentClosest found = closestOnCubic(c, Vec3(1, 3, 1));
    EXPECT_TRUE(std::isfinite(found.t));
    EXPECT_DOUBLE_EQ(found.distanceSquared, 4.0);
    const SegmentClosest toSegment = closestOnCubicToSegment(c, Vec3(0, 2, 1), Vec3(2, 2, 1));
    EXPECT_DOUBLE_EQ(toSegment.distanceSquared, 1.0);
    EXPECT_DOUBLE_EQ(toSegment.s, 0.5);
}

TEST(CubicSegment, ClosestPairToALineSegmentMatchesDenseSampling) {
    std::mt19937 rng(3);
    for (int trial = 0; trial < 100; ++trial) {
        const CubicSegment c = CubicSegment::hermite(randomVec(rng, 1), randomVec(rng, 2),
                                                     randomVec(rng, 1), randomVec(rng, 2));
        const Vec3 a = randomVec(rng, 1.5);
        const Vec3 b = randomVec(rng, 1.5);
        const SegmentClosest found = closestOnCubicToSegment(c, a, b);
        // Dense over the curve, exact projection onto the segment for each sample.
        double dense = std::numeric_limits<double>::infinity();
        const Vec3 u = b - a;
        for (int i = 0; i <= 20000; ++i) {
            const Vec3 p = c.point(i / 20000.0);
            const double s = std::clamp((p - a).dot(u) / u.squaredNorm(), 0.0, 1.0);
            dense = std::min(dense, (p - (a + s * u)).squaredNorm());
        }
        const Vec3 onSegment = a + found.s * u;
        EXPECT_NEAR(found.distanceSquared, (c.point(found.t) - onSegment).squaredNorm(), 1e-9);
        EXPECT_LE(std::sqrt(found.distanceSquared), std::sqrt(dense) + 1e-6) << "trial " << trial;
    }
}

TEST(CubicSegment, HugeCoordinatesStayFinite) {
    const CubicSegment c = CubicSegment::hermite(Vec3(1e6, 0, 0), Vec3(1, 1e3, 0),
                                                 Vec3(1e6 + 1, 0, 0), Vec3(1, -1e3, 0));
    const SegmentClosest found = closestOnCubic(c, Vec3(1e6 + 0.5, 1e5, 0));
    EXPECT_TRUE(std::isfinite(found.t));
    EXPECT_TRUE(std::isfinite(found.distanceSquared));
}

/// A piece of a Catmull–Rom spline through points on a helix of radius `radius` (m), `perTurn`
/// points a turn, as the sculpture's wires are built: short, gently bent pieces.
CubicSegment helixPiece(std::mt19937& rng, double radius, int perTurn) {
    std::uniform_real_distribution<double> u(0.0, 2.0 * M_PI);
    const double a0 = u(rng);
    const double step = 2.0 * M_PI / perTurn;
    const auto at = [&](int k) {
        const double a = a0 + k * step;
        return Vec3(radius * std::cos(a), 0.04 * a / (2.0 * M_PI), radius * std::sin(a));
    };
    return CubicSegment::hermite(at(0), 0.5 * (at(1) - at(-1)), at(1), 0.5 * (at(2) - at(0)));
}

TEST(CubicSegment, NewtonFromAGuessMatchesDenseSamplingNearAWire) {
    // Marble centres 5 mm to 3 cm from wire pieces of 5 mm to 0.5 m bend radius, from guesses
    // anywhere on the piece: the distance found is the dense scan's within 1e-9 m.
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int certified = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const double radius = 0.005 * std::pow(100.0, unit(rng));
        const CubicSegment c = helixPiece(rng, radius, 24);
        const Vec3 q = c.point(unit(rng)) + (0.005 + 0.025 * unit(rng)) * randomVec(rng, 1.0).normalized();
        for (const double guess : {0.0, 1.0, unit(rng), chordParameter(c, q)}) {
            const SegmentClosest found = closestOnCubicFrom(c, q, guess);
            ASSERT_GE(found.t, 0.0);
            ASSERT_LE(found.t, 1.0);
            EXPECT_NEAR(found.distanceSquared, (c.point(found.t) - q).squaredNorm(), 1e-15);
            EXPECT_NEAR(std::sqrt(found.distanceSquared), std::sqrt(denseDistance2(c, q)), 1e-9)
                << "trial " << trial << " radius " << radius << " guess " << guess;
        }
        // The same answer as the global search (up to Newton's tolerance).
        EXPECT_NEAR(closestOnCubicFrom(c, q, chordParameter(c, q)).t, closestOnCubic(c, q).t, 1e-6);
        certified += distanceIsConvex(c, q);
    }
    // The fast path was taken on most of them (the rest were answered by the scan).
    std::printf("convexity proven for %d of 400 queries\n", certified);
    EXPECT_GT(certified, 200);
}

TEST(CubicSegment, ConvexityBoundHoldsWhereItIsClaimed) {
    // Wherever the bound claims one minimum, the dense scan finds f'' > 0 all along.
    std::mt19937 rng(13);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int claimed = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const CubicSegment c = helixPiece(rng, 0.005 * std::pow(100.0, unit(rng)), 24);
        const Vec3 q = c.point(unit(rng)) + 0.05 * unit(rng) * randomVec(rng, 1.0).normalized();
        if (!distanceIsConvex(c, q)) continue;
        ++claimed;
        for (int i = 0; i <= 200; ++i) {
            const double t = i / 200.0;
            const double h = c.tangent(t).squaredNorm() + (c.point(t) - q).dot(c.secondDerivative(t));
            ASSERT_GT(h, 0.0) << "trial " << trial << " t " << t;
        }
    }
    EXPECT_GT(claimed, 100);
    // A query on the far side of a tight bend's centre is refused.
    const CubicSegment tight = CubicSegment::hermite(Vec3(1, 0, 0), Vec3(0, 1.6, 0), Vec3(-1, 0, 0), Vec3(0, -1.6, 0));
    EXPECT_FALSE(distanceIsConvex(tight, Vec3(0, -0.5, 0)));
}

TEST(CubicSegment, NewtonFromAGuessFallsBackOnStronglyBentPieces) {
    // Random pieces with tangents up to twice the chord and far queries: the convexity bound
    // fails on most and the scan answers; every answer is the dense scan's within 1e-9.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int trial = 0; trial < 200; ++trial) {
        const CubicSegment c = CubicSegment::hermite(randomVec(rng, 1), randomVec(rng, 2),
                                                     randomVec(rng, 1), randomVec(rng, 2));
        const Vec3 q = randomVec(rng, 1.5);
        const SegmentClosest found = closestOnCubicFrom(c, q, unit(rng));
        EXPECT_LE(std::sqrt(found.distanceSquared), std::sqrt(denseDistance2(c, q)) + 1e-9)
            << "trial " << trial;
    }
}

TEST(CubicSegment, NewtonFromAGuessFindsTheEndsAndSurvivesBadGuesses) {
    const CubicSegment c =
        CubicSegment::hermite(Vec3::Zero(), Vec3(2, 0, 0), Vec3(2, 0, 0), Vec3(2, 0, 0));
    EXPECT_EQ(closestOnCubicFrom(c, Vec3(-1, 0.1, 0), 0.7).t, 0.0);
    EXPECT_EQ(closestOnCubicFrom(c, Vec3(3, 0.1, 0), 0.2).t, 1.0);
    EXPECT_NEAR(closestOnCubicFrom(c, Vec3(0.7, 0.3, -0.4), 0.9).t, 0.35, 1e-12);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_NEAR(closestOnCubicFrom(c, Vec3(0.7, 0.3, -0.4), nan).t, 0.35, 1e-12);
    EXPECT_NEAR(closestOnCubicFrom(c, Vec3(0.7, 0.3, -0.4), 1e300).t, 0.35, 1e-12);
    // A point-like piece: no bound (zero speed), the scan answers.
    const CubicSegment point{.c0 = Vec3(1, 1, 1)};
    EXPECT_DOUBLE_EQ(closestOnCubicFrom(point, Vec3(1, 3, 1), 0.5).distanceSquared, 4.0);
    EXPECT_EQ(chordParameter(point, Vec3(5, 5, 5)), 0.0);
}

}  // namespace
}  // namespace substep
