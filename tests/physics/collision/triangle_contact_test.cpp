// Tests engine/physics/collision/triangle_contact.cpp: closest points on triangles and between
// segments against dense sampling, and single-triangle contacts against closed forms.

#include "physics/collision/triangle_contact.h"

#include <gtest/gtest.h>

#include <random>

namespace substep {
namespace {

Vec3 randomVec(std::mt19937& rng, double scale) {
    std::uniform_real_distribution<double> u(-scale, scale);
    return {u(rng), u(rng), u(rng)};
}

/// Smallest distance from p to a dense barycentric grid over the triangle.
double denseTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    constexpr int n = 400;
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= n; ++i) {
        for (int j = 0; i + j <= n; ++j) {
            const Vec3 q = a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n);
            best = std::min(best, (q - p).norm());
        }
    }
    return best;
}

ContactTriangle flatTriangle() {
    ContactTriangle tri;
    tri.v[0] = Vec3(0, 0, 0);
    tri.v[1] = Vec3(0, 0, 1);
    tri.v[2] = Vec3(1, 0, 0);
    tri.normal = Vec3::UnitY();
    return tri;
}

TEST(TriangleContact, ClosestPointMatchesDenseSampling) {
    std::mt19937 rng(2);
    for (int trial = 0; trial < 100; ++trial) {
        const Vec3 a = randomVec(rng, 1), b = randomVec(rng, 1), c = randomVec(rng, 1);
        const Vec3 p = randomVec(rng, 2);
        const TrianglePoint found = closestOnTriangle(p, a, b, c);
        const double dense = denseTriangleDistance(p, a, b, c);
        EXPECT_LE((found.point - p).norm(), dense + 1e-12);
        EXPECT_GE((found.point - p).norm(), dense - 0.01);  // the grid's resolution
    }
}

TEST(TriangleContact, ClosestPointNamesItsFeature) {
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    EXPECT_EQ(closestOnTriangle({0.2, 0.2, 1}, a, b, c).feature, TriangleFeature::Face);
    const TrianglePoint v = closestOnTriangle({2, -1, 0}, a, b, c);
    EXPECT_EQ(v.feature, TriangleFeature::Vertex);
    EXPECT_EQ(v.index, 1);
    const TrianglePoint e = closestOnTriangle({1, 1, 0}, a, b, c);
    EXPECT_EQ(e.feature, TriangleFeature::Edge);
    EXPECT_EQ(e.index, 1);
    EXPECT_TRUE(e.point.isApprox(Vec3(0.5, 0.5, 0)));
}

TEST(TriangleContact, DegenerateTrianglesStayFinite) {
    // Collinear and coincident corners.
    const TrianglePoint line = closestOnTriangle({0.5, 1, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0});
    EXPECT_TRUE(line.point.isApprox(Vec3(0.5, 0, 0)));
    const TrianglePoint dot = closestOnTriangle({0, 1, 0}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1});
    EXPECT_TRUE(dot.point.isApprox(Vec3(1, 1, 1)));
}

TEST(TriangleContact, SegmentSegmentMatchesDenseSampling) {
    std::mt19937 rng(4);
    for (int trial = 0; trial < 100; ++trial) {
        const Vec3 p0 = randomVec(rng, 1), p1 = randomVec(rng, 1);
        const Vec3 q0 = randomVec(rng, 1), q1 = randomVec(rng, 1);
        double s, t;
        closestSegmentSegment(p0, p1, q0, q1, s, t);
        const double found = (p0 + s * (p1 - p0) - q0 - t * (q1 - q0)).norm();
        double dense = std::numeric_limits<double>::infinity();
        for (int i = 0; i <= 500; ++i) {
            for (int j = 0; j <= 500; ++j) {
                dense = std::min(
                    dense, (p0 + (p1 - p0) * (i / 500.0) - q0 - (q1 - q0) * (j / 500.0)).norm());
            }
        }
        EXPECT_LE(found, dense + 1e-12);
        EXPECT_GE(found, dense - 0.01);
    }
}

TEST(TriangleContact, SphereOverTheFaceAndBeyondABorderEdge) {
    ContactBuffer buffer(1e-6);
    addSphereTriangleContacts(flatTriangle(), {0.2, 0.4, 0.2}, 0.5, 0.0, false, buffer);
    ASSERT_EQ(buffer.count(), 1);
    EXPECT_NEAR(buffer[0].depth, 0.1, 1e-12);
    EXPECT_TRUE(buffer[0].normal.isApprox(Vec3::UnitY()));
    // Beside the border edge x = 0 (active): the normal points from the edge to the centre.
    ContactBuffer side(1e-6);
    addSphereTriangleContacts(flatTriangle(), {-0.3, 0.4, 0.5}, 0.6, 0.0, false, side);
    ASSERT_EQ(side.count(), 1);
    EXPECT_NEAR(side[0].depth, 0.1, 1e-12);
    EXPECT_TRUE(side[0].normal.isApprox(Vec3(-0.6, 0.8, 0)));
}

TEST(TriangleContact, OneSidedMeshVersusSolidHeightfield) {
    // Centre 0.7 below the plane with radius 0.5: a mesh triangle lets go, a heightfield lifts.
    ContactBuffer mesh(1e-6), field(1e-6);
    addSphereTriangleContacts(flatTriangle(), {0.2, -0.7, 0.2}, 0.5, 0.0, false, mesh);
    addSphereTriangleContacts(flatTriangle(), {0.2, -0.7, 0.2}, 0.5, 0.0, true, field);
    EXPECT_EQ(mesh.count(), 0);
    ASSERT_EQ(field.count(), 1);
    EXPECT_NEAR(field[0].depth, 1.2, 1e-12);
    EXPECT_TRUE(field[0].normal.isApprox(Vec3::UnitY()));
}

TEST(TriangleContact, BoxCornerOnTheFace) {
    // A unit cube turned to stand on a corner: the lowest corner is sqrt(3)/2 below the centre.
    OrientedBox box;
    box.half = Vec3::Constant(0.5);
    const Vec3 diagonal = Vec3(1, 1, 1).normalized();
    box.axes = Quat::FromTwoVectors(diagonal, Vec3::UnitY()).toRotationMatrix();
    box.centre = Vec3(0.25, std::sqrt(3.0) / 2 - 0.01, 0.25);
    ContactBuffer buffer(1e-6);
    addBoxTriangleContacts(flatTriangle(), box, 0.0, false, buffer);
    ASSERT_EQ(buffer.count(), 1);
    EXPECT_NEAR(buffer[0].depth, 0.01, 1e-9);
    EXPECT_TRUE(buffer[0].normal.isApprox(Vec3::UnitY()));
    EXPECT_TRUE(buffer[0].point0.isApprox(Vec3(0.25, -0.01, 0.25), 1e-9));
}

}  // namespace
}  // namespace substep
