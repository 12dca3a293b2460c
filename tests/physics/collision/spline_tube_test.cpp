// Tests engine/physics/collision/spline_tube.cpp: the Catmull–Rom curve through the control
// points, its degenerate inputs, and closest points over the whole curve against dense sampling.

#include "physics/collision/spline_tube.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace substep {
namespace {

/// A wavy closed loop: enough bends that a query sees several segments.
std::vector<Vec3> wavyLoop(int n) {
    std::vector<Vec3> points;
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * M_PI * i / n;
        points.emplace_back((1.0 + 0.3 * std::sin(3 * a)) * std::cos(a), 0.2 * std::sin(5 * a),
                            (1.0 + 0.3 * std::sin(3 * a)) * std::sin(a));
    }
    return points;
}

double denseDistance(const SplineTube& tube, const Vec3& q) {
    double best = std::numeric_limits<double>::infinity();
    for (const CubicSegment& s : tube.segments) {
        for (int i = 0; i <= 4000; ++i)
            best = std::min(best, (s.point(i / 4000.0) - q).norm());
    }
    return best;
}

TEST(SplineTube, PassesThroughItsPointsWithCatmullRomTangents) {
    const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {3, 1, 1}};
    const auto tube = makeSplineTube(p, 0.1, false);
    ASSERT_EQ(tube->segments.size(), 3u);
    for (int i = 0; i < 3; ++i) {
        EXPECT_TRUE(tube->segments[i].point(0).isApprox(p[i]));
        EXPECT_TRUE(tube->segments[i].point(1).isApprox(p[i + 1]));
    }
    // Interior tangents (p[i+1] - p[i-1]) / 2, one-sided at the open ends; C1 at the joints.
    EXPECT_TRUE(tube->segments[0].tangent(0).isApprox(p[1] - p[0]));
    EXPECT_TRUE(tube->segments[1].tangent(0).isApprox(0.5 * (p[2] - p[0])));
    EXPECT_TRUE(tube->segments[0].tangent(1).isApprox(tube->segments[1].tangent(0)));
    EXPECT_TRUE(tube->segments[2].tangent(1).isApprox(p[3] - p[2]));
}

TEST(SplineTube, ClosedCurveWrapsAround) {
    const std::vector<Vec3> p = {{1, 0, 0}, {0, 0, 1}, {-1, 0, 0}, {0, 0, -1}};
    const auto tube = makeSplineTube(p, 0.1, true);
    ASSERT_EQ(tube->segments.size(), 4u);
    EXPECT_TRUE(tube->segments[3].point(1).isApprox(p[0]));
    EXPECT_TRUE(tube->segments[0].tangent(0).isApprox(0.5 * (p[1] - p[3])));
    EXPECT_TRUE(tube->segments[3].tangent(1).isApprox(tube->segments[0].tangent(0)));
}

TEST(SplineTube, RepeatedPointsAreMerged) {
    const auto tube =
        makeSplineTube({{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {2, 0, 0}}, 0.1, false);
    EXPECT_EQ(tube->points.size(), 3u);
    EXPECT_EQ(tube->segments.size(), 2u);
    // A closed curve given with its first point repeated at the end.
    const auto loop = makeSplineTube({{1, 0, 0}, {0, 0, 1}, {-1, 0, 0}, {1, 0, 0}}, 0.1, true);
    EXPECT_EQ(loop->segments.size(), 3u);
}

TEST(SplineTube, CoincidentPointsGiveASphere) {
    const auto tube = makeSplineTube({{1, 2, 3}, {1, 2, 3}, {1, 2, 3}}, 0.5, true);
    ASSERT_EQ(tube->segments.size(), 1u);
    const SplinePoint p = tube->closestPoint(Vec3(1, 4, 3), 10.0);
    ASSERT_EQ(p.segment, 0);
    EXPECT_TRUE(p.point.isApprox(Vec3(1, 2, 3)));
    EXPECT_DOUBLE_EQ(p.distanceSquared, 4.0);
}

TEST(SplineTube, RejectsMeaninglessInput) {
    EXPECT_THROW(makeSplineTube({}, 0.1, false), std::invalid_argument);
    EXPECT_THROW(makeSplineTube({{0, 0, 0}, {1, 0, 0}}, 0.0, false), std::invalid_argument);
    EXPECT_THROW(makeSplineTube({{0, 0, 0}, {1, 0, 0}}, NAN, false), std::invalid_argument);
    EXPECT_THROW(makeSplineTube({{0, 0, 0}, {INFINITY, 0, 0}}, 0.1, false), std::invalid_argument);
}

TEST(SplineTube, ClosestPointMatchesDenseSamplingOfTheWholeCurve) {
    const auto tube = makeSplineTube(wavyLoop(24), 0.05, true);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    for (int trial = 0; trial < 200; ++trial) {
        const Vec3 q(u(rng), 0.3 * u(rng), u(rng));
        const SplinePoint found = tube->closestPoint(q, 10.0);
        ASSERT_GE(found.segment, 0);
        const double dense = denseDistance(*tube, q);
        EXPECT_LE(std::sqrt(found.distanceSquared), dense + 1e-9) << "trial " << trial;
        EXPECT_GE(std::sqrt(found.distanceSquared), dense - 1e-3);  // dense over-estimates
        EXPECT_TRUE(found.point.isApprox(tube->segments[found.segment].point(found.t)));
    }
}

TEST(SplineTube, NothingBeyondTheSearchRange) {
    const auto tube = makeSplineTube({{0, 0, 0}, {1, 0, 0}}, 0.1, false);
    EXPECT_EQ(tube->closestPoint(Vec3(0.5, 2.0, 0), 1.0).segment, -1);
    const SplinePoint near = tube->closestPoint(Vec3(0.5, 0.9, 0), 1.0);
    EXPECT_EQ(near.segment, 0);
    EXPECT_NEAR(near.t, 0.5, 1e-12);
}

TEST(SplineTube, ShapeBoundsHoldTheTube) {
    const auto tube = makeSplineTube(wavyLoop(10), 0.07, true);
    const Shape shape = splineShape(tube);
    EXPECT_EQ(shape.type, ShapeType::Spline);
    ASSERT_EQ(shape.spline, tube);
    for (const CubicSegment& s : tube->segments) {
        for (int i = 0; i <= 200; ++i) {
            const Vec3 p = s.point(i / 200.0);
            const Aabb ball{p.array() - 0.07, p.array() + 0.07};
            ASSERT_TRUE(shape.localBounds.inflated(1e-12).contains(ball));
        }
    }
}

}  // namespace
}  // namespace substep
