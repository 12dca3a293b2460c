// Tests engine/physics/collision/gjk_epa.cpp and convex_support.cpp (through the general pair
// of convex_manifold.cpp) against brute force: for random poses of every pair of convex shapes,
// the signed distance and the normal from a dense sampling of the two surfaces.
//
// The brute force uses the support-function identity for the Minkowski difference D = A − B:
// the signed separation of two convex bodies is −min over unit u of h_D(u), with
// h_D(u) = h_A(u) + h_B(−u), attained at u = −normal. Each h is the largest u·x over the
// sampled surface: a polytope's corners (exact), 1024 points on each rim of a cylinder (within
// 4.7e-6 of its radius), a sphere's or capsule's centre points plus the radius (exact). The
// minimum over u is taken on 2000 spread directions and refined by a pattern search from the
// three best.

#include "physics/collision/convex_hull.h"
#include "physics/collision/convex_manifold.h"
#include "physics/collision/convex_mesh_shape.h"
#include "physics/collision/gjk_epa.h"
#include "physics/collision/narrowphase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace substep {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// A shape as the brute force sees it: surface samples in its frame and a rounding radius.
struct Sampled {
    std::string name;
    Shape shape;
    std::vector<Vec3> points;
    double radius = 0.0;
    double size = 0.0;  ///< largest half extent, for the tolerances
};

Sampled sphere() {
    return {"sphere", sphereShape(0.3), {Vec3::Zero()}, 0.3, 0.3};
}

Sampled capsule() {
    return {"capsule", capsuleShape(0.15, 0.5), {Vec3(0, -0.25, 0), Vec3(0, 0.25, 0)}, 0.15, 0.4};
}

Sampled box() {
    Sampled s{"box", boxShape(Vec3(0.8, 0.3, 0.5)), {}, 0.0, 0.4};
    for (int i = 0; i < 8; ++i) {
        s.points.emplace_back(i & 1 ? 0.4 : -0.4, i & 2 ? 0.15 : -0.15, i & 4 ? 0.25 : -0.25);
    }
    return s;
}

Sampled cylinder() {
    const double r = 0.35, h = 0.1;
    Sampled s{"cylinder", cylinderShape(r, 2 * h), {}, 0.0, r};
    for (int k = 0; k < 1024; ++k) {
        const double a = 2 * kPi * k / 1024;
        s.points.emplace_back(r * std::cos(a), h, r * std::sin(a));
        s.points.emplace_back(r * std::cos(a), -h, r * std::sin(a));
    }
    return s;
}

Sampled tallCylinder() {
    const double r = 0.12, h = 0.35;
    Sampled s{"tall_cylinder", cylinderShape(r, 2 * h), {}, 0.0, h};
    for (int k = 0; k < 1024; ++k) {
        const double a = 2 * kPi * k / 1024;
        s.points.emplace_back(r * std::cos(a), h, r * std::sin(a));
        s.points.emplace_back(r * std::cos(a), -h, r * std::sin(a));
    }
    return s;
}

Sampled hull() {
    // 30 points on an ellipsoid, not all of which end up on the hull's corners.
    std::mt19937 rng(7);
    std::normal_distribution<double> normal;
    Sampled s{"hull", {}, {}, 0.0, 0.4};
    for (int i = 0; i < 30; ++i) {
        const Vec3 u = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
        s.points.push_back(u.cwiseProduct(Vec3(0.4, 0.25, 0.3)));
    }
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->vertices = s.points;
    s.shape = convexMeshShape(mesh);
    return s;
}

std::vector<Sampled> allShapes() {
    return {sphere(), capsule(), box(), cylinder(), tallCylinder(), hull()};
}

/// h(u): the largest u·x over the posed samples, plus the radius.
double supportOf(const Sampled& s, const std::vector<Vec3>& world, const Vec3& u) {
    double best = -1e300;
    for (const Vec3& p : world)
        best = std::max(best, p.dot(u));
    return best + s.radius;
}

std::vector<Vec3> posed(const Sampled& s, const Pose& pose, int stride) {
    std::vector<Vec3> out;
    for (std::size_t i = 0; i < s.points.size(); i += stride)
        out.push_back(pose.apply(s.points[i]));
    return out;
}

std::vector<Vec3> spreadDirections(int n) {
    std::vector<Vec3> dirs;
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        const double y = 1.0 - 2.0 * (i + 0.5) / n;
        const double r = std::sqrt(1.0 - y * y);
        dirs.emplace_back(r * std::cos(golden * i), y, r * std::sin(golden * i));
    }
    return dirs;
}

struct BruteForce {
    double separation;
    Vec3 normal;  ///< from B towards A
};

BruteForce bruteForce(const Sampled& a, const Pose& pa, const Sampled& b, const Pose& pb) {
    const auto fineA = posed(a, pa, 1), fineB = posed(b, pb, 1);
    const auto coarseA = posed(a, pa, 32), coarseB = posed(b, pb, 32);
    const auto hD = [&](const Vec3& u, bool fine) {
        return fine ? supportOf(a, fineA, u) + supportOf(b, fineB, -u)
                    : supportOf(a, coarseA, u) + supportOf(b, coarseB, -u);
    };
    static const std::vector<Vec3> kDirections = spreadDirections(1000);
    std::vector<std::pair<double, Vec3>> ranked;
    for (const Vec3& u : kDirections)
        ranked.emplace_back(hD(u, false), u);
    std::partial_sort(ranked.begin(), ranked.begin() + 3, ranked.end(),
                      [](const auto& x, const auto& y) { return x.first < y.first; });
    // Far from contact on the coarse look already: not worth refining (the caller skips it).
    if (-ranked[0].first > 0.3 * (a.size + b.size)) {
        return {-ranked[0].first, -ranked[0].second};
    }
    double bestValue = 1e300;
    Vec3 bestDirection = Vec3::UnitY();
    for (int c = 0; c < 3; ++c) {
        Vec3 u = ranked[c].second;
        double value = hD(u, true);
        for (double step = 0.05; step > 1e-6; step *= 0.5) {
            for (bool improved = true; improved;) {
                improved = false;
                const Vec3 e = anyPerpendicular(u), f = u.cross(e);
                // 24 directions around u, so that a ridge of the piecewise-linear h_D is
                // followed too.
                for (int k = 0; k < 24; ++k) {
                    const double angle = 2.0 * kPi * k / 24;
                    const Vec3 d = std::cos(angle) * e + std::sin(angle) * f;
                    const Vec3 candidate = (u + step * d).normalized();
                    const double v = hD(candidate, true);
                    if (v < value) value = v, u = candidate, improved = true;
                }
            }
        }
        if (value < bestValue) bestValue = value, bestDirection = u;
    }
    return {-bestValue, -bestDirection};
}

Quat randomRotation(std::mt19937& rng) {
    std::normal_distribution<double> normal;
    return Quat(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
}

double angleBetween(const Vec3& a, const Vec3& b) {
    return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// The deepest point of a manifold.
const ContactPoint* deepestPoint(const ContactManifold& m) {
    const ContactPoint* best = nullptr;
    for (int k = 0; k < m.count; ++k) {
        if (!best || m.points[k].depth > best->depth) best = &m.points[k];
    }
    return best;
}

/// Runs `collideFn` on random poses of every pair and compares with the brute force.
template <class Collide>
void compareWithBruteForce(Collide&& collideFn, int posesPerPair, uint32_t seed) {
    const std::vector<Sampled> shapes = allShapes();
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (std::size_t i = 0; i < shapes.size(); ++i) {
        for (std::size_t j = i; j < shapes.size(); ++j) {
            const Sampled& a = shapes[i];
            const Sampled& b = shapes[j];
            const double size = std::max(a.size, b.size);
            const double tolerance = 1e-4 * size;
            int compared = 0;
            int searchFellShort = 0;  // the brute-force search stuck on a ridge of h_D
            for (int attempt = 0; compared < posesPerPair && attempt < 60 * posesPerPair;
                 ++attempt) {
                const Pose pb{Vec3(unit(rng), unit(rng), unit(rng)) * 0.1, randomRotation(rng)};
                const Vec3 offset = Vec3(unit(rng), unit(rng), unit(rng)).normalized() *
                                    (a.size + b.size) * (0.3 + 0.6 * std::abs(unit(rng)));
                const Pose pa{pb.position + offset, randomRotation(rng)};
                const BruteForce expected = bruteForce(a, pa, b, pb);
                // Near contact: from 30 % of the size apart to 50 % deep.
                if (expected.separation > 0.3 * size || expected.separation < -0.5 * size) continue;
                ++compared;
                ContactManifold m;
                collideFn(a.shape, pa, b.shape, pb, 0.5 * size, m);
                const ContactPoint* deepest = deepestPoint(m);
                const std::string what = a.name + " against " + b.name + ", pose " +
                                         std::to_string(compared) + ", brute separation " +
                                         std::to_string(expected.separation);
                ASSERT_NE(deepest, nullptr) << what;
                // The depth is min over u of h_D(u): the pair's normal must attain the depth it
                // claims on the sampled surfaces, and no sampled direction may do better.
                const auto fineA = posed(a, pa, 1), fineB = posed(b, pb, 1);
                const double attained = supportOf(a, fineA, -deepest->normal) +
                                        supportOf(b, fineB, deepest->normal);
                EXPECT_NEAR(attained, deepest->depth, tolerance) << what;
                EXPECT_LE(deepest->depth, -expected.separation + tolerance) << what;
                // Where the search found the same optimum, the same direction.
                if (std::abs(deepest->depth + expected.separation) <= tolerance) {
                    // Within 1°, unless the pair's direction is the better minimum of the two
                    // (a flat minimum the search stopped short of).
                    if (attained > -expected.separation) {
                        EXPECT_LT(angleBetween(deepest->normal, expected.normal), kPi / 180.0)
                            << what << ", attained " << attained;
                    }
                } else {
                    ++searchFellShort;
                }
                // Every point's depth agrees with its two surface points.
                for (int k = 0; k < m.count; ++k) {
                    const ContactPoint& p = m.points[k];
                    EXPECT_NEAR((p.point1 - p.point0).dot(p.normal), p.depth, 1e-12) << what;
                    EXPECT_LE(p.depth, deepest->depth + 1e-12) << what;
                }
            }
            EXPECT_EQ(compared, posesPerPair) << a.name << " against " << b.name;
            // The search is only a check if it finds the optimum itself often enough.
            EXPECT_LE(searchFellShort, posesPerPair / 2) << a.name << " against " << b.name;
        }
    }
}

TEST(GeneralConvexPair, DistanceDepthAndNormalMatchBruteForceForEveryPair) {
    compareWithBruteForce(collideGeneralConvex, 8, 11);
}

TEST(GeneralConvexPair, OrderOfTheShapesFlipsTheResult) {
    const std::vector<Sampled> shapes = allShapes();
    std::mt19937 rng(3);
    for (const Sampled& a : shapes) {
        for (const Sampled& b : shapes) {
            const Pose pa{Vec3(0.1, 0.35, -0.05), randomRotation(rng)};
            const Pose pb{Vec3::Zero(), randomRotation(rng)};
            ContactManifold ab, ba;
            collideGeneralConvex(a.shape, pa, b.shape, pb, 0.2, ab);
            collideGeneralConvex(b.shape, pb, a.shape, pa, 0.2, ba);
            ASSERT_GT(ab.count, 0) << a.name << " " << b.name;
            ASSERT_GT(ba.count, 0) << a.name << " " << b.name;
            EXPECT_NEAR(deepestPoint(ab)->depth, deepestPoint(ba)->depth, 1e-6)
                << a.name << " " << b.name;
            EXPECT_LT(angleBetween(deepestPoint(ab)->normal, -deepestPoint(ba)->normal), 1e-4)
                << a.name << " " << b.name;
        }
    }
}

TEST(GeneralConvexPair, FarApartGivesNothingAndTheCutoffReportsIt) {
    ConvexSupport a, b;
    ASSERT_TRUE(makeConvexSupport(boxShape(Vec3(1, 1, 1)), {Vec3(3, 0, 0), Quat::Identity()}, {}, a));
    ASSERT_TRUE(makeConvexSupport(cylinderShape(0.5, 1), {}, {}, b));
    // Exactly 2 apart (box face at x = 2.5, cylinder side at x = 0.5).
    const ConvexDistance d = convexDistance(a, b, 10.0);
    EXPECT_FALSE(d.beyondCutoff);
    EXPECT_NEAR(d.separation, 2.0, 1e-9);
    EXPECT_TRUE(d.normal.isApprox(Vec3::UnitX(), 1e-9));
    EXPECT_TRUE(convexDistance(a, b, 1.0).beyondCutoff);
    ContactManifold m;
    collideGeneralConvex(boxShape(Vec3(1, 1, 1)), {Vec3(3, 0, 0), Quat::Identity()},
                         cylinderShape(0.5, 1), {}, 1.9, m);
    EXPECT_EQ(m.count, 0);
}

TEST(GeneralConvexPair, CoincidentShapesStayFinite) {
    // Degenerate input: the same box twice at the same pose, and a zero-length capsule.
    for (const Shape& shape : {boxShape(Vec3(1, 1, 1)), capsuleShape(0.2, 0.0), cylinderShape(0.3, 0.2)}) {
        ContactManifold m;
        collideGeneralConvex(shape, {}, shape, {}, 0.01, m);
        ASSERT_GT(m.count, 0);
        for (int k = 0; k < m.count; ++k) {
            EXPECT_TRUE(m.points[k].point0.allFinite());
            EXPECT_TRUE(m.points[k].normal.allFinite());
            EXPECT_NEAR(m.points[k].normal.norm(), 1.0, 1e-9);
            EXPECT_GT(m.points[k].depth, 0.0);
        }
    }
}

}  // namespace
}  // namespace substep
