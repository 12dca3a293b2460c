// Tests engine/physics/collision/collide_spline.cpp and collide_mesh.cpp on random and degenerate
// input: every reported point is finite, obeys the manifold convention (unit normal, depth =
// (point1 − point0)·n, within the margin), and lies on the surfaces it names.

#include "physics/collision/collide_curved.h"
#include "physics/collision/heightfield.h"
#include "physics/collision/mesh_collider.h"
#include "physics/collision/spline_tube.h"

#include <gtest/gtest.h>

#include <random>

namespace substep {
namespace {

using Collide = void (*)(const Shape&, const Pose&, const Shape&, const Pose&, double,
                         ContactManifold&);

Quat randomRotation(std::mt19937& rng) {
    std::normal_distribution<double> g;
    return Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
}

/// Runs `collide` for random poses of `primitive` near `target` and checks every manifold.
int fuzz(Collide collide, const Shape& primitive, const Shape& target, double spread, double margin,
         uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-spread, spread);
    const Pose targetPose{Vec3(0.3, -0.2, 0.1), randomRotation(rng)};
    int points = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const Pose pose{targetPose.position + Vec3(u(rng), u(rng), u(rng)), randomRotation(rng)};
        ContactManifold m;
        m.count = 3;  // stale content must be cleared
        collide(primitive, pose, target, targetPose, margin, m);
        EXPECT_LE(m.count, kMaxContactPoints);
        for (int i = 0; i < m.count; ++i) {
            const ContactPoint& p = m.points[i];
            ++points;
            EXPECT_TRUE(p.point0.allFinite() && p.point1.allFinite() && p.normal.allFinite());
            EXPECT_NEAR(p.normal.norm(), 1.0, 1e-9);
            EXPECT_NEAR((p.point1 - p.point0).dot(p.normal), p.depth, 1e-9);
            EXPECT_GE(p.depth, -margin - 1e-9);
            if (primitive.type == ShapeType::Sphere) {
                EXPECT_NEAR((p.point0 - pose.position).norm(), primitive.radius, 1e-9);
            }
        }
    }
    return points;
}

Shape bumpyField() {
    std::vector<double> h;
    for (int j = 0; j < 12; ++j) {
        for (int i = 0; i < 12; ++i)
            h.push_back(0.3 * std::sin(1.1 * i) * std::cos(0.8 * j));
    }
    return heightfieldShape(makeHeightfield(12, 12, h, 3.0, 3.0));
}

Shape bumpyMesh() {
    const Shape field = bumpyField();
    auto mesh = std::make_shared<TriangleMesh>();
    for (int j = 0; j < 12; ++j) {
        for (int i = 0; i < 12; ++i)
            mesh->vertices.push_back(field.heightfield->vertex(i, j));
    }
    for (int j = 0; j < 11; ++j) {
        for (int i = 0; i < 11; ++i) {
            const int a = j * 12 + i;
            mesh->triangles.push_back({a, a + 12, a + 13});
            mesh->triangles.push_back({a, a + 13, a + 1});
        }
    }
    return triangleMeshShape(mesh);
}

Shape wavySpline(bool hollow) {
    std::vector<Vec3> points;
    for (int i = 0; i < 30; ++i) {
        const double a = 0.4 * i;
        points.emplace_back(0.5 * std::cos(a), 0.05 * i, 0.5 * std::sin(2 * a));
    }
    points.push_back(points.back());  // a repeated point
    return splineShape(makeSplineTube(points, 0.05, false, hollow));
}

TEST(CurvedRobustness, RandomPosesGiveConsistentContacts) {
    const Shape sphere = sphereShape(0.2), capsule = capsuleShape(0.1, 0.5),
                box = boxShape({0.5, 0.2, 0.3});
    const Shape mesh = bumpyMesh(), field = bumpyField();
    const Shape rail = wavySpline(false), pipe = wavySpline(true);
    EXPECT_GT(fuzz(collideSphereMesh, sphere, mesh, 1.5, 0.02, 1), 100);
    EXPECT_GT(fuzz(collideCapsuleMesh, capsule, mesh, 1.5, 0.02, 2), 100);
    EXPECT_GT(fuzz(collideBoxMesh, box, mesh, 1.5, 0.02, 3), 100);
    EXPECT_GT(fuzz(collideSphereHeightfield, sphere, field, 1.5, 0.02, 4), 100);
    EXPECT_GT(fuzz(collideCapsuleHeightfield, capsule, field, 1.5, 0.02, 5), 100);
    EXPECT_GT(fuzz(collideBoxHeightfield, box, field, 1.5, 0.02, 6), 100);
    EXPECT_GT(fuzz(collideSphereSpline, sphere, rail, 0.8, 0.02, 7), 100);
    EXPECT_GT(fuzz(collideCapsuleSpline, capsule, rail, 0.8, 0.02, 8), 100);
    EXPECT_GT(fuzz(collideSphereSpline, sphereShape(0.03), pipe, 0.8, 0.02, 9), 10);
    EXPECT_GT(fuzz(collideCapsuleSpline, capsuleShape(0.02, 0.04), pipe, 0.8, 0.02, 10), 10);
}

TEST(CurvedRobustness, HugeValuesStayFinite) {
    // Heights and coordinates at the scene format's bounds.
    std::vector<double> h = {1e6, -1e6, 0, 1e6};
    const Shape field = heightfieldShape(makeHeightfield(2, 2, h, 1e6, 1e6));
    const Shape rail =
        splineShape(makeSplineTube({{-1e6, 0, 0}, {0, 1e6, 0}, {1e6, 0, 1e6}}, 1e4, false));
    for (const Vec3& p : {Vec3(0, 0, 0), Vec3(1e6, 1e6, -1e6), Vec3(-3e5, 2e5, 1e5)}) {
        for (const Shape& s :
             {sphereShape(1e4), capsuleShape(1e4, 1e4), boxShape({1e4, 1e4, 1e4})}) {
            ContactManifold m;
            const Pose pose{p, Quat::Identity()};
            if (s.type == ShapeType::Sphere) collideSphereHeightfield(s, pose, field, {}, 1.0, m);
            if (s.type == ShapeType::Capsule) collideCapsuleHeightfield(s, pose, field, {}, 1.0, m);
            if (s.type == ShapeType::Box) collideBoxHeightfield(s, pose, field, {}, 1.0, m);
            for (int i = 0; i < m.count; ++i) {
                EXPECT_TRUE(m.points[i].point0.allFinite() && m.points[i].normal.allFinite());
                EXPECT_TRUE(std::isfinite(m.points[i].depth));
            }
            if (s.type == ShapeType::Sphere) collideSphereSpline(s, pose, rail, {}, 1.0, m);
            if (s.type == ShapeType::Capsule) collideCapsuleSpline(s, pose, rail, {}, 1.0, m);
            for (int i = 0; i < m.count; ++i) {
                EXPECT_TRUE(m.points[i].point0.allFinite() && m.points[i].normal.allFinite());
                EXPECT_TRUE(std::isfinite(m.points[i].depth));
            }
        }
    }
}

TEST(CurvedRobustness, NonFinitePosesGiveNoContacts) {
    const Pose bad{Vec3(NAN, 0, 0), Quat::Identity()};
    ContactManifold m;
    collideSphereMesh(sphereShape(0.1), bad, bumpyMesh(), {}, 0.0, m);
    EXPECT_EQ(m.count, 0);
    collideBoxHeightfield(boxShape({1, 1, 1}), bad, bumpyField(), {}, 0.0, m);
    EXPECT_EQ(m.count, 0);
    collideSphereSpline(sphereShape(0.1), bad, wavySpline(false), {}, 0.0, m);
    EXPECT_EQ(m.count, 0);
}

}  // namespace
}  // namespace substep
