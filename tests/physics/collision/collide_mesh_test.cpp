// Tests engine/physics/collision/collide_mesh.cpp: spheres, capsules and boxes against static
// triangle meshes and heightfields, with depths and normals from closed forms (planes, a
// valley, a slope), including the internal edges that must not bump.

#include "physics/collision/collide_curved.h"
#include "physics/collision/heightfield.h"
#include "physics/collision/mesh_collider.h"

#include <gtest/gtest.h>

#include <cmath>

namespace substep {
namespace {

constexpr double kTol = 1e-9;
const Pose kOrigin;  // identity

Pose at(const Vec3& p, const Quat& q = Quat::Identity()) {
    return {p, q};
}

/// The square [-1, 1]² at y = 0 as two triangles sharing the diagonal (-1, -1)-(1, 1).
Shape flatSquare() {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->vertices = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}};
    mesh->triangles = {{0, 1, 2}, {0, 2, 3}};
    return triangleMeshShape(mesh);
}

/// A flat heightfield at height y0 over [-2, 2]², cells of 0.25 m.
Shape flatField(double y0) {
    return heightfieldShape(makeHeightfield(17, 17, std::vector<double>(17 * 17, y0), 4.0, 4.0));
}

/// The plane y = a x + b z + c sampled on a 9 x 9 grid over [-2, 2]².
Shape slopedField(double a, double b, double c) {
    std::vector<double> h;
    for (int row = 0; row < 9; ++row) {
        for (int column = 0; column < 9; ++column) {
            h.push_back(a * (-2.0 + 0.5 * column) + b * (-2.0 + 0.5 * row) + c);
        }
    }
    return heightfieldShape(makeHeightfield(9, 9, h, 4.0, 4.0));
}

void expectConsistent(const ContactManifold& m) {
    for (int i = 0; i < m.count; ++i) {
        const ContactPoint& p = m.points[i];
        EXPECT_NEAR(p.normal.norm(), 1.0, 1e-12);
        EXPECT_NEAR((p.point1 - p.point0).dot(p.normal), p.depth, 1e-9);
        EXPECT_TRUE(p.point0.allFinite() && p.point1.allFinite());
    }
}

/// Every point has the normal n and the depth d.
void expectAll(const ContactManifold& m, const Vec3& n, double d) {
    for (int i = 0; i < m.count; ++i) {
        EXPECT_TRUE(m.points[i].normal.isApprox(n, 1e-9)) << m.points[i].normal.transpose();
        EXPECT_NEAR(m.points[i].depth, d, kTol);
    }
    expectConsistent(m);
}

// ---- Mesh ------------------------------------------------------------------------------------

TEST(CollideSphereMesh, OnAFlatSquareIncludingTheSharedDiagonal) {
    const Shape square = flatSquare();
    const double r = 0.2, delta = 0.01;
    ContactManifold m;
    // Over one triangle, exactly over the diagonal, over the centre vertex region, beside it.
    for (const Vec3& xz : {Vec3(0.5, 0, -0.4), Vec3(0.3, 0, 0.3), Vec3(-0.6, 0, -0.6),
                           Vec3(0.0, 0, 0.0), Vec3(0.1, 0, 0.105)}) {
        collideSphereMesh(sphereShape(r), at(xz + Vec3(0, r - delta, 0)), square, kOrigin, 0.0, m);
        ASSERT_EQ(m.count, 1) << xz.transpose();
        expectAll(m, Vec3::UnitY(), delta);
        EXPECT_TRUE(m.points[0].point1.isApprox(xz, 1e-12));
    }
}

TEST(CollideSphereMesh, SunkenBelowTheSurfaceIsPushedUp) {
    ContactManifold m;
    collideSphereMesh(sphereShape(0.3), at({0.2, -0.1, 0.2}), flatSquare(), kOrigin, 0.0, m);
    ASSERT_EQ(m.count, 1);
    expectAll(m, Vec3::UnitY(), 0.4);
    // Wholly behind the one-sided mesh: let go.
    collideSphereMesh(sphereShape(0.3), at({0.2, -0.35, 0.2}), flatSquare(), kOrigin, 0.0, m);
    EXPECT_EQ(m.count, 0);
}

TEST(CollideSphereMesh, OverTheBorderTheEdgeNormalTilts) {
    ContactManifold m;
    // 0.3 beyond the border x = 1 and 0.4 up: distance 0.5 to the edge.
    collideSphereMesh(sphereShape(0.6), at({1.3, 0.4, 0.0}), flatSquare(), kOrigin, 0.0, m);
    ASSERT_EQ(m.count, 1);
    expectAll(m, Vec3(0.6, 0.8, 0), 0.1);
}

TEST(CollideSphereMesh, FollowsThePoseOfTheMesh) {
    const Quat tilt(Eigen::AngleAxisd(0.5, Vec3(1, 0, 1).normalized()));
    const Vec3 origin(3, -1, 2);
    const Vec3 up = tilt * Vec3::UnitY();
    ContactManifold m;
    collideSphereMesh(sphereShape(0.25), at(origin + tilt * Vec3(0.2, 0, -0.3) + 0.2 * up),
                      flatSquare(), at(origin, tilt), 0.0, m);
    ASSERT_EQ(m.count, 1);
    expectAll(m, up, 0.05);
}

TEST(CollideSphereMesh, InAValleyTouchesBothFaces) {
    // Faces y = |x| (45°), sphere on the axis at height h: distance h / sqrt(2) to each face.
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->vertices = {{0, 0, -1}, {0, 0, 1}, {1, 1, 1}, {1, 1, -1}, {-1, 1, 1}, {-1, 1, -1}};
    mesh->triangles = {{0, 1, 2}, {0, 2, 3}, {0, 4, 1}, {0, 5, 4}};
    const Shape valley = triangleMeshShape(mesh);
    const double r = 0.3, h = 0.4;
    ContactManifold m;
    collideSphereMesh(sphereShape(r), at({0, h, 0.1}), valley, kOrigin, 0.0, m);
    ASSERT_EQ(m.count, 2);
    const double d = r - h / std::sqrt(2.0);
    const Vec3 n0 = Vec3(-1, 1, 0).normalized(), n1 = Vec3(1, 1, 0).normalized();
    for (int i = 0; i < 2; ++i) {
        EXPECT_NEAR(m.points[i].depth, d, kTol);
        EXPECT_TRUE(m.points[i].normal.isApprox(n0, 1e-9) || m.points[i].normal.isApprox(n1, 1e-9));
    }
    EXPECT_FALSE(m.points[0].normal.isApprox(m.points[1].normal));
}

TEST(CollideCapsuleMesh, LyingFlatAcrossTheDiagonal) {
    const double r = 0.1, delta = 0.004;
    const Quat lying(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));  // axis along x
    ContactManifold m;
    collideCapsuleMesh(capsuleShape(r, 1.0), at({0.0, r - delta, 0.1}, lying), flatSquare(),
                       kOrigin, 0.0, m);
    ASSERT_GE(m.count, 2);
    expectAll(m, Vec3::UnitY(), delta);
    double lo = 1e9, hi = -1e9;
    for (int i = 0; i < m.count; ++i) {
        lo = std::min(lo, m.points[i].point1.x());
        hi = std::max(hi, m.points[i].point1.x());
    }
    EXPECT_NEAR(lo, -0.5, 1e-9);
    EXPECT_NEAR(hi, 0.5, 1e-9);
}

TEST(CollideCapsuleMesh, HangingOverTheBorderRestsOnTheEdge) {
    // Axis along z at x = 1.05 (beyond the border x = 1), height 0.08: it rests on the edge.
    const Quat alongZ(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));
    const double r = 0.1;
    ContactManifold m;
    collideCapsuleMesh(capsuleShape(r, 0.6), at({1.06, 0.08, 0.0}, alongZ), flatSquare(), kOrigin,
                       0.0, m);
    ASSERT_GE(m.count, 1);
    const double d = std::hypot(0.06, 0.08);
    expectAll(m, Vec3(0.06, 0.08, 0) / d, r - d);
}

TEST(CollideBoxMesh, RestingFlatGivesFourCorners) {
    const Shape square = flatSquare();
    const Vec3 size(0.6, 0.4, 0.8);
    const double delta = 0.005;
    // Axis-aligned (the footprint crosses the diagonal) and turned 45° about y.
    for (const double yaw : {0.0, M_PI / 4}) {
        const Quat q(Eigen::AngleAxisd(yaw, Vec3::UnitY()));
        const Vec3 centre(0.1, 0.2 - delta, -0.05);
        ContactManifold m;
        collideBoxMesh(boxShape(size), at(centre, q), square, kOrigin, 0.0, m);
        ASSERT_EQ(m.count, 4) << "yaw " << yaw;
        expectAll(m, Vec3::UnitY(), delta);
        for (int i = 0; i < 4; ++i) {
            const Vec3 local = q.conjugate() * (m.points[i].point0 - centre);
            EXPECT_NEAR(std::abs(local.x()), 0.3, 1e-9);
            EXPECT_NEAR(local.y(), -0.2, 1e-9);
            EXPECT_NEAR(std::abs(local.z()), 0.4, 1e-9);
        }
    }
}

TEST(CollideBoxMesh, OverhangingTheBorderStopsAtTheEdge) {
    // Footprint x in [0.8, 1.4]: two corners over the mesh, two points on its border x = 1.
    ContactManifold m;
    collideBoxMesh(boxShape({0.6, 0.2, 0.4}), at({1.1, 0.09, 0.3}), flatSquare(), kOrigin, 0.0, m);
    ASSERT_EQ(m.count, 4);
    expectAll(m, Vec3::UnitY(), 0.01);
    int onBorder = 0;
    for (int i = 0; i < 4; ++i)
        onBorder += std::abs(m.points[i].point1.x() - 1.0) < 1e-9;
    EXPECT_EQ(onBorder, 2);
}

TEST(CollideMesh, DegenerateMeshesStayQuiet) {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    mesh->triangles = {{0, 1, 2}, {1, 1, 1}};
    const Shape flat = triangleMeshShape(mesh);
    ContactManifold m;
    collideSphereMesh(sphereShape(1.0), at({1, 0, 0}), flat, kOrigin, 0.0, m);
    EXPECT_EQ(m.count, 0);
    collideBoxMesh(boxShape({1, 1, 1}), at({1, 0, 0}), flat, kOrigin, 0.0, m);
    EXPECT_EQ(m.count, 0);
    Shape none{.type = ShapeType::Mesh};
    collideCapsuleMesh(capsuleShape(1, 1), at({1, 0, 0}), none, kOrigin, 0.0, m);
    EXPECT_EQ(m.count, 0);
}

// ---- Heightfield -----------------------------------------------------------------------------

TEST(CollideHeightfield, FlatFieldBehavesLikeAPlane) {
    const Shape field = flatField(0.5);
    const double r = 0.1, delta = 0.003;
    ContactManifold m;
    // Over a cell, over a grid vertex, on a cell diagonal, on a cell edge.
    for (const Vec3& xz :
         {Vec3(0.33, 0, -0.71), Vec3(0.25, 0, 0.5), Vec3(0.1, 0, 0.1), Vec3(0.5, 0, 0.37)}) {
        collideSphereHeightfield(sphereShape(r), at(xz + Vec3(0, 0.5 + r - delta, 0)), field,
                                 kOrigin, 0.0, m);
        ASSERT_EQ(m.count, 1) << xz.transpose();
        expectAll(m, Vec3::UnitY(), delta);
    }
    // Deep below the surface: still pushed straight up.
    collideSphereHeightfield(sphereShape(r), at({0.3, -0.5, 0.3}), field, kOrigin, 0.0, m);
    ASSERT_EQ(m.count, 1);
    expectAll(m, Vec3::UnitY(), 1.0 + r);
    // Outside the field's extent: nothing.
    collideSphereHeightfield(sphereShape(r), at({2.5, 0.5, 0.0}), field, kOrigin, 0.0, m);
    EXPECT_EQ(m.count, 0);
}

TEST(CollideHeightfield, SlopeGivesTheSlopeNormal) {
    const double a = 0.3, b = -0.2, c = 0.1, r = 0.15, gap = 0.12;
    const Shape field = slopedField(a, b, c);
    const Vec3 n = Vec3(-a, 1, -b).normalized();
    ContactManifold m;
    for (const Vec3& xz : {Vec3(0.1, 0, 0.2), Vec3(-1.0, 0, 0.5), Vec3(1.25, 0, -0.75)}) {
        // Centre `gap` above the plane along its normal: depth r − gap.
        const Vec3 foot(xz.x(), a * xz.x() + b * xz.z() + c, xz.z());
        collideSphereHeightfield(sphereShape(r), at(foot + gap * n), field, kOrigin, 0.0, m);
        ASSERT_EQ(m.count, 1) << xz.transpose();
        expectAll(m, n, r - gap);
    }
}

TEST(CollideHeightfield, BoxOnAFlatFieldGivesFourCorners) {
    const Shape field = flatField(0.0);
    const Quat yaw(Eigen::AngleAxisd(0.3, Vec3::UnitY()));
    const Vec3 centre(0.07, 0.25 - 0.002, 0.11);
    ContactManifold m;
    collideBoxHeightfield(boxShape({0.9, 0.5, 0.7}), at(centre, yaw), field, kOrigin, 0.0, m);
    ASSERT_EQ(m.count, 4);
    expectAll(m, Vec3::UnitY(), 0.002);
}

TEST(CollideHeightfield, CapsuleOnASlope) {
    const double a = 0.2, b = 0.0, c = 0.0, r = 0.1, gap = 0.08;
    const Shape field = slopedField(a, b, c);
    const Vec3 n = Vec3(-a, 1, -b).normalized();
    // Axis along the slope's contour (z), centre gap above the plane.
    const Quat alongZ(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));
    ContactManifold m;
    collideCapsuleHeightfield(capsuleShape(r, 0.8), at(Vec3(0.3, 0.06, 0.1) + gap * n, alongZ),
                              field, kOrigin, 0.0, m);
    ASSERT_GE(m.count, 2);
    expectAll(m, n, r - gap);
}

TEST(CollideHeightfield, FollowsThePoseOfTheField) {
    const Quat turn(Eigen::AngleAxisd(0.7, Vec3::UnitZ()));
    const Vec3 origin(1, 2, 3);
    const Vec3 up = turn * Vec3::UnitY();
    ContactManifold m;
    collideSphereHeightfield(sphereShape(0.2), at(origin + turn * Vec3(0.4, 0, 0.2) + 0.15 * up),
                             flatField(0.0), at(origin, turn), 0.0, m);
    ASSERT_EQ(m.count, 1);
    expectAll(m, up, 0.05);
}

}  // namespace
}  // namespace substep
