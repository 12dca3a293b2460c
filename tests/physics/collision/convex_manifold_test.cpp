// Tests engine/physics/collision/convex_manifold.cpp, collide_convex_triangles.cpp,
// collide_convex_spline.cpp and the narrowphase table (narrowphase.cpp) that routes to them:
// no empty cell among the shapes a dynamic body can have, manifolds that let shapes rest
// without jitter, a cylinder rolling at 2/3 g sin θ and a box sliding along spline rails at
// g sin θ (closed forms).

#include "physics/collision/convex_manifold.h"
#include "physics/collision/convex_mesh_shape.h"
#include "physics/collision/heightfield.h"
#include "physics/collision/mesh_collider.h"
#include "physics/collision/narrowphase.h"
#include "physics/collision/spline_tube.h"
#include "physics/world.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace substep {
namespace {

constexpr double kPi = 3.14159265358979323846;

Quat turn(double angle, const Vec3& axis) {
    return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

Shape boxHull(const Vec3& size) {
    auto mesh = std::make_shared<TriangleMesh>();
    for (int i = 0; i < 8; ++i) {
        mesh->vertices.emplace_back(i & 1 ? 0.5 * size.x() : -0.5 * size.x(),
                                    i & 2 ? 0.5 * size.y() : -0.5 * size.y(),
                                    i & 4 ? 0.5 * size.z() : -0.5 * size.z());
    }
    return convexMeshShape(mesh);
}

/// A flat square of two triangles at y = 0, facing up.
Shape groundMesh(double half) {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->vertices = {{-half, 0, -half}, {half, 0, -half}, {half, 0, half}, {-half, 0, half}};
    mesh->triangles = {{0, 2, 1}, {0, 3, 2}};
    return triangleMeshShape(mesh);
}

Shape flatHeightfield(double size, int samples) {
    return heightfieldShape(makeHeightfield(samples, samples,
                                            std::vector<double>(samples * samples, 0.0), size, size));
}

/// A straight solid rail along x, its top at y = top.
Shape rail(double top, double radius, double z = 0.0, double length = 4.0) {
    return splineShape(makeSplineTube({Vec3(-0.5 * length, top - radius, z), Vec3(0, top - radius, z),
                                       Vec3(0.5 * length, top - radius, z)},
                                      radius, false));
}

struct Placed {
    std::string name;
    Shape shape;
    Pose pose;
};

/// The shapes a dynamic body can have, each placed with its lowest point 1 cm below y = 0.
std::vector<Placed> dynamicShapes() {
    return {
        {"sphere", sphereShape(0.2), {Vec3(0, 0.19, 0), Quat::Identity()}},
        {"capsule", capsuleShape(0.1, 0.4), {Vec3(0, 0.09, 0), turn(kPi / 2, Vec3::UnitZ())}},
        {"box", boxShape(Vec3(0.3, 0.3, 0.3)), {Vec3(0, 0.14, 0), Quat::Identity()}},
        {"cylinder", cylinderShape(0.15, 0.2), {Vec3(0, 0.09, 0), Quat::Identity()}},
        {"convex mesh", boxHull(Vec3(0.3, 0.3, 0.3)), {Vec3(0, 0.14, 0), Quat::Identity()}},
    };
}

/// Every shape type as a target whose top is at y = 0 under the origin.
std::vector<Placed> targets() {
    std::vector<Placed> all = {
        {"plane", planeShape(Vec3::UnitY(), 0.0), {}},
        {"triangle mesh", groundMesh(2.0), {}},
        {"heightfield", flatHeightfield(4.0, 5), {}},
        {"spline", rail(0.0, 0.05), {}},
        {"sphere", sphereShape(1.0), {Vec3(0, -1, 0), Quat::Identity()}},
        {"capsule", capsuleShape(0.5, 2.0), {Vec3(0, -0.5, 0), turn(kPi / 2, Vec3::UnitZ())}},
        {"box", boxShape(Vec3(4, 1, 4)), {Vec3(0, -0.5, 0), Quat::Identity()}},
        {"cylinder", cylinderShape(1.0, 1.0), {Vec3(0, -0.5, 0), Quat::Identity()}},
        {"convex mesh", boxHull(Vec3(4, 1, 4)), {Vec3(0, -0.5, 0), Quat::Identity()}},
    };
    return all;
}

const ContactPoint* deepestPoint(const ContactManifold& m) {
    const ContactPoint* best = nullptr;
    for (int k = 0; k < m.count; ++k) {
        if (!best || m.points[k].depth > best->depth) best = &m.points[k];
    }
    return best;
}

// --- The table -------------------------------------------------------------------------------

TEST(NarrowphaseTable, NoEmptyCellForAnyShapeADynamicBodyCanHave) {
    // Every shape type in the enum (a new one must get its row) against every dynamic shape.
    const ShapeType dynamic[] = {ShapeType::Sphere, ShapeType::Capsule, ShapeType::Box,
                                 ShapeType::Cylinder, ShapeType::Mesh};
    for (int t = static_cast<int>(ShapeType::None) + 1; t <= static_cast<int>(ShapeType::Cylinder);
         ++t) {
        for (ShapeType d : dynamic) {
            EXPECT_TRUE(canCollide(d, static_cast<ShapeType>(t))) << int(d) << " " << t;
            EXPECT_TRUE(canCollide(static_cast<ShapeType>(t), d)) << int(d) << " " << t;
        }
    }
}

TEST(NarrowphaseTable, EveryDynamicShapeTouchesEveryShapeAtTheRightDepthAndNormal) {
    // A cell that is filled but silent would pass the test above: each pair must find the
    // 1 cm overlap, pushing the dynamic shape up, in both orders.
    for (const Placed& d : dynamicShapes()) {
        for (const Placed& t : targets()) {
            const std::string what = d.name + " on " + t.name;
            ContactManifold m;
            collide(d.shape, d.pose, t.shape, t.pose, 0.005, m);
            ASSERT_GT(m.count, 0) << what;
            const ContactPoint* deepest = deepestPoint(m);
            EXPECT_NEAR(deepest->depth, 0.01, 1e-6) << what;
            EXPECT_GT(deepest->normal.y(), std::cos(1e-3)) << what;
            ContactManifold reversed;
            collide(t.shape, t.pose, d.shape, d.pose, 0.005, reversed);
            ASSERT_GT(reversed.count, 0) << what << " (reversed)";
            EXPECT_NEAR(deepestPoint(reversed)->depth, 0.01, 1e-6) << what << " (reversed)";
            EXPECT_LT(deepestPoint(reversed)->normal.y(), -std::cos(1e-3)) << what << " (reversed)";
        }
    }
}

// --- Manifolds -------------------------------------------------------------------------------

TEST(GeneralManifold, FlatFacesTouchOnSeveralPointsSpanningTheOverlap) {
    // A cylinder flat on a hull face and on another cylinder; a hull on a hull; a capsule on
    // its side along a cylinder's face: each must have at least 3 points (2 for the capsule),
    // all at the 1 cm depth.
    struct Case {
        std::string name;
        Shape a;
        Pose pa;
        Shape b;
        Pose pb;
        int minimum;
    };
    const Case cases[] = {
        {"cylinder on hull", cylinderShape(0.15, 0.2), {Vec3(0.3, 0.09, 0.1), turn(0.3, Vec3::UnitY())},
         boxHull(Vec3(4, 1, 4)), {Vec3(0, -0.5, 0), Quat::Identity()}, 3},
        {"cylinder on cylinder", cylinderShape(0.15, 0.2), {Vec3(0.05, 0.09, 0), Quat::Identity()},
         cylinderShape(0.3, 0.4), {Vec3(0, -0.2, 0), turn(0.2, Vec3::UnitY())}, 3},
        {"capsule on cylinder", capsuleShape(0.05, 0.2), {Vec3(0, 0.04, 0), turn(kPi / 2, Vec3::UnitX())},
         cylinderShape(0.3, 0.4), {Vec3(0, -0.2, 0), Quat::Identity()}, 2},
        {"cylinder on its side on a hull", cylinderShape(0.1, 0.4), {Vec3(0, 0.09, 0), turn(kPi / 2, Vec3::UnitX())},
         boxHull(Vec3(4, 1, 4)), {Vec3(0, -0.5, 0), Quat::Identity()}, 2},
    };
    for (const Case& c : cases) {
        ContactManifold m;
        collideGeneralConvex(c.a, c.pa, c.b, c.pb, 0.005, m);
        EXPECT_GE(m.count, c.minimum) << c.name;
        for (int k = 0; k < m.count; ++k) {
            EXPECT_NEAR(m.points[k].depth, 0.01, 1e-9) << c.name;
            EXPECT_NEAR(m.points[k].normal.y(), 1.0, 1e-9) << c.name;
        }
    }
}

TEST(GeneralManifold, MatchesTheSpecialRoutinesWhereBothExist) {
    // Box on box, cylinder on box, box on hull: the deepest depth and the normal agree with the
    // separating-axis routines; both give a patch of at least 3 points lying flat.
    struct Case {
        std::string name;
        Shape a;
        Pose pa;
        Shape b;
        Pose pb;
    };
    const Case cases[] = {
        {"box on box", boxShape(Vec3(0.3, 0.2, 0.4)), {Vec3(0.1, 0.59, 0), turn(0.4, Vec3::UnitY())},
         boxShape(Vec3(1, 1, 1)), {}},
        {"cylinder on box", cylinderShape(0.15, 0.2), {Vec3(0.1, 0.59, 0), turn(0.4, Vec3::UnitY())},
         boxShape(Vec3(1, 1, 1)), {}},
        {"box on hull", boxShape(Vec3(0.3, 0.2, 0.4)), {Vec3(0.1, 0.59, 0), turn(0.4, Vec3::UnitY())},
         boxHull(Vec3(1, 1, 1)), {}},
    };
    for (const Case& c : cases) {
        ContactManifold special, general;
        collide(c.a, c.pa, c.b, c.pb, 0.005, special);
        collideGeneralConvex(c.a, c.pa, c.b, c.pb, 0.005, general);
        ASSERT_GE(special.count, 3) << c.name;
        ASSERT_GE(general.count, 3) << c.name;
        EXPECT_NEAR(deepestPoint(general)->depth, deepestPoint(special)->depth, 1e-9) << c.name;
        EXPECT_NEAR(deepestPoint(general)->depth, 0.01, 1e-9) << c.name;
        EXPECT_TRUE(deepestPoint(general)->normal.isApprox(deepestPoint(special)->normal, 1e-9))
            << c.name;
    }
}

// --- In the world ----------------------------------------------------------------------------

/// Drops `shape` from `height` above a static `ground` and checks it comes to rest: speed
/// below 1 mm/s and turning below 1 mrad/s after 2 s.
void expectRests(const std::string& name, const Shape& shape, const Quat& orientation,
                 double height, const Shape& ground, const Pose& groundPose) {
    World world({.gravity = Vec3(0, -10, 0), .substeps = 20});
    world.createBody({.shape = ground,
                      .type = BodyType::Static,
                      .position = groundPose.position,
                      .orientation = groundPose.rotation});
    const BodyId body = world.createBody(
        {.shape = shape, .density = 1000.0, .position = Vec3(0.05, height, -0.03), .orientation = orientation});
    for (int frame = 0; frame < 120; ++frame)
        world.step(1.0 / 60.0);
    const Body& b = world.body(body);
    EXPECT_LT(b.v.norm(), 1e-3) << name;
    EXPECT_LT(b.omega.norm(), 1e-2) << name;
    EXPECT_GT(b.userPosition().y(), 0.0) << name << ": fell through";
    EXPECT_LT(b.userPosition().y(), height) << name;
}

TEST(GeneralPairWorld, ShapesRestWithoutJitter) {
    const Shape slab = boxHull(Vec3(4, 1, 4));
    const Pose slabPose{Vec3(0, -0.5, 0), Quat::Identity()};
    const Shape field = flatHeightfield(4.0, 9);
    expectRests("cylinder flat on a hull", cylinderShape(0.15, 0.2), Quat::Identity(), 0.11, slab, slabPose);
    expectRests("hull on a hull", boxHull(Vec3(0.3, 0.2, 0.4)), turn(0.3, Vec3::UnitY()), 0.11, slab, slabPose);
    expectRests("box on a heightfield", boxShape(Vec3(0.3, 0.2, 0.4)), turn(0.3, Vec3::UnitY()), 0.11, field, {});
    expectRests("cylinder flat on a heightfield", cylinderShape(0.15, 0.2), Quat::Identity(), 0.11, field, {});
    expectRests("hull on a heightfield", boxHull(Vec3(0.3, 0.2, 0.4)), turn(0.3, Vec3::UnitY()), 0.11, field, {});
    expectRests("cylinder flat on a triangle mesh", cylinderShape(0.15, 0.2), Quat::Identity(), 0.11, groundMesh(2.0), {});
    expectRests("cylinder flat on a cylinder", cylinderShape(0.15, 0.2), Quat::Identity(), 0.11,
                cylinderShape(1.0, 1.0), {Vec3(0, -0.5, 0), Quat::Identity()});
}

TEST(GeneralPairWorld, CylinderRollsDownAHullInclineAtTwoThirdsGSinTheta) {
    // A solid cylinder rolling without slipping: a = g sin θ / (1 + I/(m r²)) = 2/3 g sin θ.
    // The incline is a convex mesh, so the contact is the general pair's.
    for (double degrees : {10.0, 20.0}) {
        const double theta = degrees * kPi / 180.0;
        const double g = 10.0, r = 0.1;
        const Quat tilt = turn(theta, Vec3::UnitZ());
        const Vec3 n = tilt * Vec3::UnitY();
        const Vec3 downhill = tilt * -Vec3::UnitX();
        World world({.gravity = Vec3(0, -g, 0), .substeps = 20});
        world.createBody({.shape = boxHull(Vec3(8, 1, 2)),
                          .type = BodyType::Static,
                          .position = -0.5 * n,
                          .orientation = tilt,
                          .staticFriction = 0.8,
                          .dynamicFriction = 0.8});
        const BodyId wheel = world.createBody({.shape = cylinderShape(r, 0.3),
                                               .density = 1000.0,
                                               .position = r * n,
                                               .orientation = turn(kPi / 2, Vec3::UnitX()),
                                               .staticFriction = 0.8,
                                               .dynamicFriction = 0.8});
        for (int frame = 0; frame < 60; ++frame)
            world.step(1.0 / 60.0);
        const Body& b = world.body(wheel);
        const double travelled = (b.x - r * n).dot(downhill);
        const double expected = 0.5 * (2.0 / 3.0) * g * std::sin(theta);  // in 1 s
        EXPECT_NEAR(travelled, expected, 0.01 * expected) << degrees << "°";
        EXPECT_NEAR(b.v.norm(), b.omega.norm() * r, 0.01 * b.v.norm()) << degrees << "°";
        EXPECT_NEAR(b.x.dot(n), r, 1e-3) << degrees << "°";
    }
}

TEST(GeneralPairWorld, BoxSlidesDownSplineRailsAtGSinThetaWithoutFallingThrough) {
    // Two frictionless rails sloping at θ, a box lying across them: it slides at g sin θ.
    const double theta = 15.0 * kPi / 180.0, g = 10.0, R = 0.02;
    const Vec3 down(std::cos(theta), -std::sin(theta), 0.0);
    World world({.gravity = Vec3(0, -g, 0), .substeps = 20});
    for (double z : {-0.15, 0.15}) {
        std::vector<Vec3> points;
        for (int i = 0; i <= 8; ++i)
            points.push_back(Vec3(0, 0, z) + (i - 1.0) * down);
        world.createBody({.shape = splineShape(makeSplineTube(points, R, false)),
                          .type = BodyType::Static,
                          .staticFriction = 0.0,
                          .dynamicFriction = 0.0});
    }
    const Vec3 up = Vec3(std::sin(theta), std::cos(theta), 0.0);
    const Vec3 start = (R + 0.05) * up;
    const BodyId box = world.createBody({.shape = boxShape(Vec3(0.2, 0.1, 0.5)),
                                         .density = 500.0,
                                         .position = start,
                                         .orientation = turn(-theta, Vec3::UnitZ()),
                                         .staticFriction = 0.0,
                                         .dynamicFriction = 0.0});
    for (int frame = 0; frame < 60; ++frame) {
        world.step(1.0 / 60.0);
        ASSERT_GT((world.body(box).x).dot(up), R) << "frame " << frame << ": through the rails";
    }
    const Body& b = world.body(box);
    const double travelled = (b.x - start).dot(down);
    const double expected = 0.5 * g * std::sin(theta);  // in 1 s
    EXPECT_NEAR(travelled, expected, 0.01 * expected);
    EXPECT_NEAR((b.x).dot(up), R + 0.05, 1e-3);  // still lying on the rails
    EXPECT_LT(b.omega.norm(), 1e-2);
}

}  // namespace
}  // namespace substep

namespace substep {
namespace {

TEST(GeneralPairSpline, ABoxInAPipeTouchesWhereItsCornerReachesTheWall) {
    // A 0.2 m cube in a straight pipe of radius 0.2 along x, 1 cm below the axis' level of
    // touching: its lower corners are sqrt(0.21² + 0.1²) from the axis, beyond the wall by that
    // less 0.2, pushed back towards the axis.
    const double R = 0.2;
    const Shape pipe = splineShape(makeSplineTube({Vec3(-2, 0, 0), Vec3(0, 0, 0), Vec3(2, 0, 0)}, R, false, true));
    const Shape cube = boxShape(Vec3(0.2, 0.2, 0.2));
    ContactManifold m;
    collide(cube, {Vec3(0.3, -0.11, 0), Quat::Identity()}, pipe, {}, 0.005, m);
    ASSERT_GT(m.count, 0);
    const ContactPoint* deepest = deepestPoint(m);
    const double reach = std::hypot(0.21, 0.1);
    EXPECT_NEAR(deepest->depth, reach - R, 1e-9);
    EXPECT_NEAR(std::abs(deepest->normal.z()), 0.1 / reach, 1e-9);
    EXPECT_NEAR(deepest->normal.y(), 0.21 / reach, 1e-9);
    // Centred in the pipe it touches nothing; out past the open end, nothing holds it.
    collide(cube, {Vec3(0.3, 0, 0), Quat::Identity()}, pipe, {}, 0.005, m);
    EXPECT_EQ(m.count, 0);
    collide(cube, {Vec3(2.15, -0.11, 0), Quat::Identity()}, pipe, {}, 0.005, m);
    EXPECT_EQ(m.count, 0);
}

TEST(GeneralPairMesh, AShapeBehindAOneSidedMeshIsLetGoAndAHeightfieldPushesUp) {
    // 30 cm under a ground mesh, wholly behind its triangles: no contact. Under a heightfield,
    // which is solid below, pushed up along the face normal by its whole depth.
    const Shape can = cylinderShape(0.15, 0.2);
    ContactManifold m;
    collide(can, {Vec3(0.2, -0.3, 0.1), Quat::Identity()}, groundMesh(2.0), {}, 0.005, m);
    EXPECT_EQ(m.count, 0);
    collide(can, {Vec3(0.2, -0.3, 0.1), Quat::Identity()}, flatHeightfield(4.0, 5), {}, 0.005, m);
    ASSERT_GT(m.count, 0);
    EXPECT_NEAR(deepestPoint(m)->depth, 0.4, 1e-9);
    EXPECT_NEAR(deepestPoint(m)->normal.y(), 1.0, 1e-12);
}

}  // namespace
}  // namespace substep

namespace substep {
namespace {

/// Slides `shape` frictionless across `ground` at 1.65 m/s for 1.5 s: no edge may catch it
/// (speed kept within 0.5 %, no lift, no spin).
void expectSlidesFreely(const std::string& name, const Shape& shape, const Shape& ground) {
    World world({.gravity = Vec3(0, -10, 0), .substeps = 20});
    world.createBody({.shape = ground, .type = BodyType::Static, .staticFriction = 0.0, .dynamicFriction = 0.0});
    const Vec3 velocity(1.5, 0.0, 0.7);
    const BodyId body = world.createBody({.shape = shape,
                                          .density = 1000.0,
                                          .position = Vec3(-1.5, 0.1, -0.8),
                                          .velocity = velocity,
                                          .staticFriction = 0.0,
                                          .dynamicFriction = 0.0});
    for (int frame = 0; frame < 90; ++frame)
        world.step(1.0 / 60.0);
    const Body& b = world.body(body);
    EXPECT_NEAR(b.v.norm(), velocity.norm(), 0.005 * velocity.norm()) << name;
    EXPECT_LT(std::abs(b.v.y()), 1e-3) << name;
    EXPECT_LT(b.omega.norm(), 1e-2) << name;
    EXPECT_NEAR(b.userPosition().y(), 0.1, 1e-3) << name;
}

TEST(GeneralPairWorld, ShapesSlideAcrossInternalEdgesWithoutCatching) {
    // Diagonally across the 25 cm cells of a flat heightfield (many internal edges and
    // diagonals) and the diagonal of a two-triangle mesh.
    const Shape field = flatHeightfield(8.0, 33);
    expectSlidesFreely("hull on a heightfield", boxHull(Vec3(0.3, 0.2, 0.3)), field);
    expectSlidesFreely("hull on a mesh", boxHull(Vec3(0.3, 0.2, 0.3)), groundMesh(4.0));
    expectSlidesFreely("cylinder on a mesh", cylinderShape(0.15, 0.2), groundMesh(4.0));
}

TEST(GeneralPairWorld, FlatCylinderSlidesAcrossHeightfieldCellsWithoutCatching) {
    // Failed before contact normals within 1e-6 of a triangle's face normal were snapped to it:
    // the points from neighbouring triangles carried normals 2e-5 rad apart, and the patch's
    // velocity solve turned that into a kick of 6.3 rad/s about the vertical (frame 31).
    expectSlidesFreely("cylinder on a heightfield", cylinderShape(0.15, 0.2), flatHeightfield(8.0, 33));
}

}  // namespace
}  // namespace substep
