// Tests engine/physics/collision/convex_hull.cpp, collide_convex.cpp and convex_mesh_shape.cpp
// (and the convex case of mass_properties.cpp) against geometric facts and closed forms.

#include "physics/collision/collide_convex.h"
#include "physics/collision/convex_hull.h"
#include "physics/collision/convex_mesh_shape.h"
#include "physics/mass_properties.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace substep {
namespace {

std::vector<Vec3> boxCorners(const Vec3& size) {
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i) {
        corners.emplace_back(i & 1 ? 0.5 * size.x() : -0.5 * size.x(),
                             i & 2 ? 0.5 * size.y() : -0.5 * size.y(),
                             i & 4 ? 0.5 * size.z() : -0.5 * size.z());
    }
    return corners;
}

/// A convex-mesh shape whose mesh is just the points (no triangles needed for the hull).
Shape hullShape(const std::vector<Vec3>& points) {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->vertices = points;
    return convexMeshShape(mesh);
}

double hullVolume(const ConvexHull& hull) {
    return meshMassProperties(hullTriangleMesh(hull), 1.0).mass;
}

/// Largest signed distance of p outside the hull's face planes.
double outside(const ConvexHull& hull, const Vec3& p) {
    double worst = -1e300;
    for (const HullFace& f : hull.faces)
        worst = std::max(worst, f.normal.dot(p) - f.offset);
    return worst;
}

// ---------------------------------------------------------------------------------------------
// The hull

TEST(ConvexHull, CubeWithInteriorPointsHasSixSquareFacesAndTheCubesVolume) {
    std::vector<Vec3> points = boxCorners(Vec3(2, 2, 2));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> inside(-0.99, 0.99);
    for (int i = 0; i < 200; ++i)
        points.emplace_back(inside(rng), inside(rng), inside(rng));
    // Points on faces and edges are not vertices of the hull.
    points.emplace_back(1, 0, 0);
    points.emplace_back(1, 1, 0);
    std::shuffle(points.begin(), points.end(), rng);

    const ConvexHull hull = buildConvexHull(points);
    ASSERT_TRUE(hull.isSolid());
    EXPECT_EQ(hull.faces.size(), 6u);
    EXPECT_EQ(hull.vertices.size(), 8u);
    EXPECT_EQ(hull.edges.size(), 12u);
    for (const HullFace& f : hull.faces) {
        EXPECT_EQ(f.vertexCount, 4);
        EXPECT_NEAR(f.normal.cwiseAbs().maxCoeff(), 1.0, 1e-12);  // an axis
        EXPECT_NEAR(f.offset, 1.0, 1e-12);
    }
    EXPECT_NEAR(hullVolume(hull), 8.0, 1e-12);
}

TEST(ConvexHull, FacePolygonsWindCounterClockwiseAndEdgesJoinTheirFaces) {
    const ConvexHull hull = buildConvexHull(boxCorners(Vec3(1, 2, 3)));
    for (const HullFace& f : hull.faces) {
        Vec3 newell = Vec3::Zero();
        for (int i = 0; i < f.vertexCount; ++i) {
            newell += hull.faceVertex(f, i).cross(hull.faceVertex(f, (i + 1) % f.vertexCount));
        }
        EXPECT_GT(newell.dot(f.normal), 0.0);
    }
    for (const HullEdge& e : hull.edges) {
        for (int face : {e.face0, e.face1}) {
            const HullFace& f = hull.faces[face];
            EXPECT_NEAR(f.normal.dot(hull.vertices[e.vertex0]), f.offset, 1e-12);
            EXPECT_NEAR(f.normal.dot(hull.vertices[e.vertex1]), f.offset, 1e-12);
        }
    }
}

TEST(ConvexHull, RandomPointsAreAllInsideAndEveryVertexIsAnInputPoint) {
    std::mt19937 rng(42);
    std::normal_distribution<double> gauss;
    for (int trial = 0; trial < 20; ++trial) {
        std::vector<Vec3> points;
        const int n = 4 + trial * 25;
        for (int i = 0; i < n; ++i)
            points.emplace_back(gauss(rng), gauss(rng), 3 * gauss(rng));
        const ConvexHull hull = buildConvexHull(points);
        ASSERT_TRUE(hull.isSolid());
        for (const Vec3& p : points)
            EXPECT_LE(outside(hull, p), 1e-9);
        for (const Vec3& v : hull.vertices) {
            EXPECT_NE(std::find(points.begin(), points.end(), v), points.end());
        }
        // Euler's formula for a convex polyhedron.
        EXPECT_EQ(static_cast<int>(hull.vertices.size()) - static_cast<int>(hull.edges.size()) +
                      static_cast<int>(hull.faces.size()),
                  2);
    }
}

TEST(ConvexHull, PointsOnASphereAreAllVertices) {
    // Vertices of a regular icosahedron: 12 vertices, 20 triangles, 30 edges.
    const double g = 0.5 * (1 + std::sqrt(5.0));
    std::vector<Vec3> points;
    for (double s : {-1.0, 1.0}) {
        for (double t : {-1.0, 1.0}) {
            points.emplace_back(0, s, t * g);
            points.emplace_back(s, t * g, 0);
            points.emplace_back(t * g, 0, s);
        }
    }
    const ConvexHull hull = buildConvexHull(points);
    EXPECT_EQ(hull.vertices.size(), 12u);
    EXPECT_EQ(hull.faces.size(), 20u);
    EXPECT_EQ(hull.edges.size(), 30u);
    // Volume of the icosahedron with edge 2: 5/12 (3 + √5) 2³.
    EXPECT_NEAR(hullVolume(hull), 5.0 / 12.0 * (3 + std::sqrt(5.0)) * 8.0, 1e-12);
}

TEST(ConvexHull, DegenerateInputGivesAHullWithoutFacesAndNoNaN) {
    const std::vector<std::vector<Vec3>> cases = {
        {},
        {Vec3(1, 2, 3)},
        {Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(1, 2, 3)},
        {Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2), Vec3(3, 3, 3), Vec3(0.5, 0.5, 0.5)},
        {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0.3, 0, 0.7)},
        {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
    };
    for (const auto& points : cases) {
        const ConvexHull hull = buildConvexHull(points);
        EXPECT_FALSE(hull.isSolid());
        EXPECT_LE(hull.vertices.size(), std::max<std::size_t>(points.size(), 0));
        for (const Vec3& v : hull.vertices)
            EXPECT_TRUE(v.allFinite());
        EXPECT_TRUE(hull.interiorPoint.allFinite());
        auto mesh = std::make_shared<TriangleMesh>();
        mesh->vertices = points;
        EXPECT_THROW(convexMeshShape(mesh), std::invalid_argument);
    }
    EXPECT_THROW(buildConvexHull(std::vector<Vec3>{Vec3(0, std::nan(""), 0)}),
                 std::invalid_argument);
}

TEST(ConvexHull, DuplicateVerticesAreJoined) {
    std::vector<Vec3> points = boxCorners(Vec3(1, 1, 1));
    const std::vector<Vec3> copy = points;
    points.insert(points.end(), copy.begin(), copy.end());
    points.insert(points.end(), copy.begin(), copy.end());
    const ConvexHull hull = buildConvexHull(points);
    EXPECT_EQ(hull.vertices.size(), 8u);
    EXPECT_EQ(hull.faces.size(), 6u);
}

TEST(ConvexHull, HugeAndTinyScalesGiveTheSameTopology) {
    for (double scale : {1e-150, 1e-6, 1e6, 1e150}) {
        std::vector<Vec3> points = boxCorners(Vec3(scale, 2 * scale, 3 * scale));
        for (Vec3& p : points)
            p += Vec3(5 * scale, 0, 0);
        const ConvexHull hull = buildConvexHull(points);
        ASSERT_EQ(hull.faces.size(), 6u) << scale;
        for (const HullFace& f : hull.faces) {
            EXPECT_TRUE(f.normal.allFinite());
            EXPECT_TRUE(std::isfinite(f.offset));
        }
        for (const Vec3& p : points)
            EXPECT_LE(outside(hull, p), 1e-12 * scale);
    }
}

TEST(ConvexHull, FloatRoundedFacesStillMergeIntoOnePolygon) {
    // A cube subdivided on its faces and stored in single precision: 6 faces, not 54.
    std::vector<Vec3> points;
    for (int i = 0; i <= 3; ++i) {
        for (int j = 0; j <= 3; ++j) {
            for (int k = 0; k <= 3; ++k) {
                if (i % 3 && j % 3 && k % 3) continue;
                const Vec3 p = Vec3(i, j, k) * (0.1 / 3.0) + Vec3(0.3, 0.7, 0.11);
                points.emplace_back(float(p.x()), float(p.y()), float(p.z()));
            }
        }
    }
    const ConvexHull hull = buildConvexHull(points);
    EXPECT_EQ(hull.faces.size(), 6u);
    for (const Vec3& p : points)
        EXPECT_LE(outside(hull, p), 1e-9);
}

TEST(ConvexHull, ManyCoplanarAndCollinearPointsStillGiveTheBox) {
    // A 6 x 6 x 6 lattice (every face a grid of coplanar, collinear points) and random points on
    // a box's surface: 6 faces, 8 vertices, 12 edges, and everything inside.
    std::vector<Vec3> lattice;
    for (int i = 0; i < 6; ++i) {
        for (int j = 0; j < 6; ++j) {
            for (int k = 0; k < 6; ++k)
                lattice.emplace_back(i * 0.2, j * 0.2, k * 0.2);
        }
    }
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::vector<Vec3> surface = boxCorners(Vec3(2, 4, 6));
    for (int i = 0; i < 600; ++i) {
        Vec3 p(unit(rng), 2 * unit(rng), 3 * unit(rng));
        const int axis = i % 3;
        p[axis] = (i / 3) % 2 ? Vec3(1, 2, 3)[axis] : -Vec3(1, 2, 3)[axis];
        surface.push_back(p);
    }
    std::shuffle(surface.begin(), surface.end(), rng);
    for (const auto* points : {&lattice, &surface}) {
        const ConvexHull hull = buildConvexHull(*points);
        EXPECT_EQ(hull.faces.size(), 6u);
        EXPECT_EQ(hull.vertices.size(), 8u);
        EXPECT_EQ(hull.edges.size(), 12u);
        for (const Vec3& p : *points)
            EXPECT_LE(outside(hull, p), 1e-9);
    }
}

TEST(ConvexHull, CylinderHasTwoCapsAndItsSides) {
    std::vector<Vec3> points;
    const int sides = 40;
    for (int i = 0; i < sides; ++i) {
        const double a = 2 * M_PI * i / sides;
        for (double y : {0.0, 0.25, 0.5, 1.0})
            points.emplace_back(std::cos(a), y, std::sin(a));
    }
    const ConvexHull hull = buildConvexHull(points);
    EXPECT_EQ(hull.faces.size(), static_cast<std::size_t>(sides + 2));
    EXPECT_EQ(hull.vertices.size(), static_cast<std::size_t>(2 * sides));
    // Volume of the prism over the regular 40-gon: area (n/2) sin(2π/n), height 1.
    EXPECT_NEAR(hullVolume(hull), 0.5 * sides * std::sin(2 * M_PI / sides), 1e-12);
    for (const HullFace& f : hull.faces) {
        if (std::abs(f.normal.y()) > 0.5)
            EXPECT_EQ(f.vertexCount, sides);
        else
            EXPECT_EQ(f.vertexCount, 4);
    }
}

TEST(ConvexHull, SupportAndClosestPoint) {
    const ConvexHull hull = buildConvexHull(boxCorners(Vec3(2, 2, 2)));
    EXPECT_EQ(hull.support(Vec3(1, 2, 3)), Vec3(1, 1, 1));
    // Outside a face, an edge, a corner; inside.
    HullClosestPoint c = hull.closestPoint(Vec3(0.2, 3, 0.1));
    EXPECT_NEAR(c.signedDistance, 2.0, 1e-12);
    EXPECT_TRUE(c.point.isApprox(Vec3(0.2, 1, 0.1), 1e-12));
    c = hull.closestPoint(Vec3(2, 2, 0.5));
    EXPECT_NEAR(c.signedDistance, std::sqrt(2.0), 1e-12);
    EXPECT_TRUE(c.point.isApprox(Vec3(1, 1, 0.5), 1e-12));
    c = hull.closestPoint(Vec3(2, 3, 4));
    EXPECT_NEAR(c.signedDistance, std::sqrt(1.0 + 4.0 + 9.0), 1e-12);
    c = hull.closestPoint(Vec3(0.1, 0.2, 0.7));
    EXPECT_NEAR(c.signedDistance, -0.3, 1e-12);
    EXPECT_TRUE(c.point.isApprox(Vec3(0.1, 0.2, 1.0), 1e-12));
}

// ---------------------------------------------------------------------------------------------
// Shape and mass properties

TEST(ConvexMeshShape, FillsBoundsAndHull) {
    const Shape shape = hullShape(boxCorners(Vec3(1, 2, 3)));
    EXPECT_EQ(shape.type, ShapeType::Mesh);
    EXPECT_TRUE(shape.convex);
    ASSERT_TRUE(shape.hull);
    EXPECT_TRUE(shape.localBounds.min.isApprox(Vec3(-0.5, -1, -1.5)));
    EXPECT_TRUE(shape.localBounds.max.isApprox(Vec3(0.5, 1, 1.5)));
    EXPECT_THROW(convexMeshShape(nullptr), std::invalid_argument);
}

TEST(ConvexMeshShape, WeighsAsItsHullNotAsTheDentedMesh) {
    // A unit cube whose top face is four triangles meeting at a centre pushed 0.3 down: the
    // closed mesh encloses less than the cube, the hull is the cube.
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->vertices = boxCorners(Vec3(1, 1, 1));
    mesh->vertices.emplace_back(0, 0.2, 0);  // vertex 8: the dent
    // Corners: bit0 x, bit1 y, bit2 z. Bottom (y-), sides, then the dented top fan.
    mesh->triangles = {{0, 1, 5}, {0, 5, 4},                         // y-
                       {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5},   // x-, x+
                       {0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6},   // z-, z+
                       {2, 6, 8}, {6, 7, 8}, {7, 3, 8}, {3, 2, 8}};  // y+ dented
    const double density = 500.0;
    const MassProperties dented = meshMassProperties(*mesh, density);
    EXPECT_NEAR(dented.mass, density * (1.0 - 0.3 / 3.0), 1e-9);  // minus the pyramid

    const Shape shape = convexMeshShape(mesh);
    const MassProperties hull = shapeMassProperties(shape, density);
    const MassProperties box = boxMassProperties(Vec3(1, 1, 1), density);
    EXPECT_NEAR(hull.mass, box.mass, 1e-9);
    EXPECT_LT(hull.centerOfMass.norm(), 1e-12);
    EXPECT_LT((hull.inertia - box.inertia).norm(), 1e-9);

    // A convex-flagged shape without a prebuilt hull weighs the same.
    Shape bare{.type = ShapeType::Mesh, .mesh = mesh, .convex = true};
    EXPECT_NEAR(shapeMassProperties(bare, density).mass, box.mass, 1e-9);
}

// ---------------------------------------------------------------------------------------------
// Collisions

Pose pose(const Vec3& position, const Quat& rotation = Quat::Identity()) {
    return {position, rotation};
}

void expectConsistent(const ContactManifold& m) {
    for (int i = 0; i < m.count; ++i) {
        const ContactPoint& c = m.points[i];
        EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
        EXPECT_NEAR((c.point1 - c.point0).dot(c.normal), c.depth, 1e-12);
        EXPECT_TRUE(c.point0.allFinite() && c.point1.allFinite());
    }
}

TEST(CollideConvex, BoxHullOnAPlaneTouchesAtTheFourLowestCornersLikeABox) {
    const Vec3 size(1.0, 0.5, 2.0);
    const Shape hull = hullShape(boxCorners(size));
    const Shape ground = planeShape(Vec3(0, 1, 0), 0.1);
    const Quat tilt(Eigen::AngleAxisd(0.02, Vec3(1, 0, 2).normalized()));
    const Pose placed = pose(Vec3(0.3, 0.1 + 0.25 - 0.01, -0.2), tilt);

    ContactManifold m;
    collideConvexPlane(hull, placed, ground, Pose{}, 0.05, m);
    expectConsistent(m);
    ASSERT_EQ(m.count, 4);
    // The box's own answer: each bottom corner's height above the plane.
    for (const Vec3& corner : boxCorners(size)) {
        if (corner.y() > 0) continue;
        const Vec3 world = placed.apply(corner);
        const auto match =
            std::find_if(m.points.begin(), m.points.begin() + m.count,
                         [&](const ContactPoint& c) { return c.point0.isApprox(world, 1e-12); });
        ASSERT_NE(match, m.points.begin() + m.count);
        EXPECT_NEAR(match->depth, 0.1 - world.y(), 1e-12);
        EXPECT_TRUE(match->normal.isApprox(Vec3::UnitY()));
        EXPECT_NEAR(match->point1.y(), 0.1, 1e-12);
    }
}

TEST(CollideConvex, PlaneKeepsFourPointsOfAManySidedBaseAndHonoursTheMargin) {
    // A 16-sided prism standing on its base.
    std::vector<Vec3> points;
    for (int i = 0; i < 16; ++i) {
        const double a = 2 * M_PI * i / 16;
        points.emplace_back(std::cos(a), 0, std::sin(a));
        points.emplace_back(std::cos(a), 1, std::sin(a));
    }
    const Shape prism = hullShape(points);
    ContactManifold m;
    collideConvexPlane(prism, pose(Vec3(0, -0.01, 0)), planeShape(Vec3::UnitY(), 0), Pose{}, 0, m);
    expectConsistent(m);
    EXPECT_EQ(m.count, 4);
    // The four span most of the base: their quadrilateral has area near the inscribed square's.
    // (A quadrilateral's area is half its diagonals' cross product; the pairing that gives the
    // largest one is the pair of diagonals.)
    const auto p = [&](int i) { return m.points[i].point0; };
    double area = 0.0;
    for (const auto& [a, b, c, d] :
         {std::array{0, 2, 1, 3}, std::array{0, 1, 2, 3}, std::array{0, 3, 1, 2}}) {
        area = std::max(area, 0.5 * std::abs((p(a) - p(b)).cross(p(c) - p(d)).y()));
    }
    EXPECT_GT(area, 1.8);  // the inscribed square's is 2, the 16-gon's 3.06

    m.clear();
    collideConvexPlane(prism, pose(Vec3(0, 0.02, 0)), planeShape(Vec3::UnitY(), 0), Pose{}, 0.01,
                       m);
    EXPECT_EQ(m.count, 0);
    collideConvexPlane(prism, pose(Vec3(0, 0.02, 0)), planeShape(Vec3::UnitY(), 0), Pose{}, 0.03,
                       m);
    EXPECT_EQ(m.count, 4);
    for (int i = 0; i < m.count; ++i)
        EXPECT_NEAR(m.points[i].depth, -0.02, 1e-12);
}

TEST(CollideConvex, CubeRestingOnCubeGivesFourPointsAtTheOverlap) {
    const Shape cube = hullShape(boxCorners(Vec3(1, 1, 1)));
    const double overlap = 0.003;
    // Top cube turned about y and shifted so that its bottom face lies inside the lower top face.
    const Pose top =
        pose(Vec3(0.05, 1 - overlap, -0.02), Quat(Eigen::AngleAxisd(0.3, Vec3::UnitY())));
    const Pose bottom = pose(Vec3::Zero());
    for (bool asBox : {false, true}) {
        ContactManifold m;
        if (asBox)
            collideConvexBox(cube, top, boxShape(Vec3(1, 1, 1)), bottom, 0.01, m);
        else
            collideConvexConvex(cube, top, cube, bottom, 0.01, m);
        expectConsistent(m);
        ASSERT_EQ(m.count, 4) << asBox;
        for (int i = 0; i < m.count; ++i) {
            EXPECT_TRUE(m.points[i].normal.isApprox(Vec3::UnitY(), 1e-12));
            EXPECT_NEAR(m.points[i].depth, overlap, 1e-12);
            EXPECT_NEAR(m.points[i].point1.y(), 0.5, 1e-12);  // on the lower cube's top
        }
    }
    // Swapped roles: the lower cube is shape a, the normal points down towards it.
    ContactManifold m;
    collideConvexConvex(cube, bottom, cube, top, 0.0, m);
    expectConsistent(m);
    ASSERT_EQ(m.count, 4);
    for (int i = 0; i < m.count; ++i) {
        EXPECT_TRUE(m.points[i].normal.isApprox(-Vec3::UnitY(), 1e-12));
        EXPECT_NEAR(m.points[i].depth, overlap, 1e-12);
    }
}

TEST(CollideConvex, SeparatedHullsReportOnlyWithinTheMargin) {
    const Shape cube = hullShape(boxCorners(Vec3(1, 1, 1)));
    ContactManifold m;
    collideConvexConvex(cube, pose(Vec3(0, 1.02, 0)), cube, Pose{}, 0.01, m);
    EXPECT_EQ(m.count, 0);
    collideConvexConvex(cube, pose(Vec3(0, 1.02, 0)), cube, Pose{}, 0.05, m);
    ASSERT_EQ(m.count, 4);
    for (int i = 0; i < m.count; ++i)
        EXPECT_NEAR(m.points[i].depth, -0.02, 1e-12);
}

TEST(CollideConvex, CrossedEdgesGiveOneEdgeContact) {
    // Lower cube turned 45° about x (a ridge along x on top at √2/2), upper one 45° about z (a
    // ridge along z underneath): the ridges cross at the y axis.
    const Shape cube = hullShape(boxCorners(Vec3(1, 1, 1)));
    const double ridge = std::sqrt(0.5);
    const double height = 2 * ridge - 0.01;
    const Pose lower = pose(Vec3::Zero(), Quat(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX())));
    const Pose upper = pose(Vec3(0, height, 0), Quat(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitZ())));
    ContactManifold m;
    collideConvexConvex(cube, upper, cube, lower, 0.0, m);
    expectConsistent(m);
    ASSERT_EQ(m.count, 1);
    EXPECT_TRUE(m.points[0].normal.isApprox(Vec3::UnitY(), 1e-9));
    EXPECT_NEAR(m.points[0].depth, 0.01, 1e-12);
    EXPECT_TRUE(m.points[0].point0.isApprox(Vec3(0, height - ridge, 0), 1e-9));
    EXPECT_TRUE(m.points[0].point1.isApprox(Vec3(0, ridge, 0), 1e-9));
}

TEST(CollideConvex, SphereDepthsFromClosedForms) {
    const Shape cube = hullShape(boxCorners(Vec3(2, 2, 2)));
    const Quat turn(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
    const Pose placed = pose(Vec3(1, -2, 3), turn);
    const double r = 0.5;
    struct Case {
        Vec3 localCenter;
        double depth;
        Vec3 localNormal;  // from the sphere towards the hull
    };
    const std::vector<Case> cases = {
        {Vec3(0.2, 1.4, -0.3), r - 0.4, -Vec3::UnitY()},                          // above a face
        {Vec3(1.2, 1.2, 0.0), r - std::sqrt(0.08), -Vec3(1, 1, 0).normalized()},  // an edge
        {Vec3(1.1, 1.2, 1.3), r - std::sqrt(0.14), -Vec3(0.1, 0.2, 0.3).normalized()},  // corner
        {Vec3(0.1, 0.2, 0.8), r + 0.2, -Vec3::UnitZ()},  // centre inside
    };
    for (const Case& k : cases) {
        ContactManifold m;
        collideConvexSphere(cube, placed, sphereShape(r), pose(placed.apply(k.localCenter)), 0, m);
        expectConsistent(m);
        ASSERT_EQ(m.count, 1);
        EXPECT_NEAR(m.points[0].depth, k.depth, 1e-12);
        EXPECT_TRUE(m.points[0].normal.isApprox(turn * k.localNormal, 1e-12));
        EXPECT_NEAR((m.points[0].point1 - placed.apply(k.localCenter)).norm(), r, 1e-12);
    }
    ContactManifold m;
    collideConvexSphere(cube, placed, sphereShape(r), pose(placed.apply(Vec3(0, 1.6, 0))), 0.05, m);
    EXPECT_EQ(m.count, 0);
}

TEST(CollideConvex, CapsuleLyingOnAFaceGivesTwoPointsAndAcrossAnEdgeOne) {
    const Shape cube = hullShape(boxCorners(Vec3(2, 2, 2)));
    const double r = 0.2, gap = -0.01;  // 1 cm overlap
    // Lying along x (capsule axis is local y), its segment spanning x in [-0.5, 0.5].
    const Pose lying =
        pose(Vec3(0, 1 + r + gap, 0), Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ())));
    ContactManifold m;
    collideConvexCapsule(cube, Pose{}, capsuleShape(r, 1.0), lying, 0, m);
    expectConsistent(m);
    ASSERT_EQ(m.count, 2);
    for (int i = 0; i < 2; ++i) {
        EXPECT_NEAR(m.points[i].depth, -gap, 1e-12);
        EXPECT_TRUE(m.points[i].normal.isApprox(-Vec3::UnitY(), 1e-12));
        EXPECT_NEAR(std::abs(m.points[i].point0.x()), 0.5, 1e-9);
    }
    // Overhanging the edge at x = 1: the clipped segment ends on the edge.
    m.clear();
    collideConvexCapsule(cube, Pose{}, capsuleShape(r, 1.0),
                         pose(lying.position + Vec3(0.8, 0, 0), lying.rotation), 0, m);
    ASSERT_EQ(m.count, 2);
    EXPECT_NEAR(std::max(m.points[0].point0.x(), m.points[1].point0.x()), 1.0, 1e-9);

    // Standing upright over a corner region: one point, depth from the closest distance.
    m.clear();
    const Vec3 tip(1.1, 1.1, 0.3);  // lower cap centre
    collideConvexCapsule(cube, Pose{}, capsuleShape(r, 1.0), pose(tip + Vec3(0, 0.5, 0)), 0, m);
    expectConsistent(m);
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].depth, r - std::sqrt(0.02), 1e-9);
    EXPECT_TRUE(m.points[0].point0.isApprox(Vec3(1, 1, 0.3), 1e-9));
}

TEST(CollideConvex, PrimitiveFirstOrderSwapsPointsAndNormal) {
    const Shape cube = hullShape(boxCorners(Vec3(1, 1, 1)));
    const Pose hullPose = pose(Vec3(0.1, 0.2, 0.3), Quat(Eigen::AngleAxisd(0.4, Vec3::UnitZ())));
    const Pose sphereAt = pose(hullPose.apply(Vec3(0.1, 0.6, 0.0)));
    const Pose boxAt = pose(hullPose.apply(Vec3(0.0, 0.99, 0.0)), hullPose.rotation);
    const Pose capsuleAt =
        pose(hullPose.apply(Vec3(0.0, 0.65, 0.0)),
             hullPose.rotation * Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX())));
    const auto check = [](const ContactManifold& hullFirst, const ContactManifold& primitiveFirst) {
        ASSERT_EQ(hullFirst.count, primitiveFirst.count);
        ASSERT_GT(hullFirst.count, 0);
        for (int i = 0; i < hullFirst.count; ++i) {
            const ContactPoint& h = hullFirst.points[i];
            const ContactPoint& p = primitiveFirst.points[i];
            EXPECT_EQ(p.point0, h.point1);
            EXPECT_EQ(p.point1, h.point0);
            EXPECT_EQ(p.normal, -h.normal);
            EXPECT_EQ(p.depth, h.depth);
        }
    };
    ContactManifold h, p;
    collideConvexSphere(cube, hullPose, sphereShape(0.2), sphereAt, 0, h);
    collideSphereConvex(sphereShape(0.2), sphereAt, cube, hullPose, 0, p);
    check(h, p);
    h.clear(), p.clear();
    collideConvexCapsule(cube, hullPose, capsuleShape(0.2, 0.4), capsuleAt, 0, h);
    collideCapsuleConvex(capsuleShape(0.2, 0.4), capsuleAt, cube, hullPose, 0, p);
    check(h, p);
    h.clear(), p.clear();
    collideConvexBox(cube, hullPose, boxShape(Vec3(1, 1, 1)), boxAt, 0, h);
    collideBoxConvex(boxShape(Vec3(1, 1, 1)), boxAt, cube, hullPose, 0, p);
    check(h, p);
    EXPECT_EQ(h.count, 4);
}

TEST(CollideConvex, DegenerateHullCollidesWithNothing) {
    Shape flat{.type = ShapeType::Mesh, .convex = true};
    flat.hull = std::make_shared<ConvexHull>(
        buildConvexHull(std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1)}));
    ContactManifold m;
    collideConvexPlane(flat, Pose{}, planeShape(Vec3::UnitY(), 1), Pose{}, 0, m);
    collideConvexSphere(flat, Pose{}, sphereShape(1), Pose{}, 0, m);
    collideConvexCapsule(flat, Pose{}, capsuleShape(1, 1), Pose{}, 0, m);
    collideConvexBox(flat, Pose{}, boxShape(Vec3(1, 1, 1)), Pose{}, 0, m);
    collideConvexConvex(flat, Pose{}, flat, Pose{}, 0, m);
    EXPECT_EQ(m.count, 0);
}

TEST(CollideConvex, RandomHullsSeparateWhenMovedByTheDeepestDepthAlongTheNormal) {
    // The normal of a shallow overlap is the shortest way out: moving hull a by the deepest
    // depth along it leaves the pair just touching, whatever the shapes and poses. (Random
    // poses overlap deeply; each pair is first backed off to a shallow overlap, as a simulation
    // with substeps keeps them.)
    std::mt19937 rng(3);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const auto randomHull = [&] {
        std::vector<Vec3> points;
        for (int i = 0; i < 12; ++i)
            points.emplace_back(gauss(rng), 0.5 * gauss(rng), gauss(rng));
        return hullShape(points);
    };
    const auto randomRotation = [&] {
        return Quat(Eigen::Vector4d(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized());
    };
    const auto deepest = [](const ContactManifold& m) {
        const ContactPoint* best = &m.points[0];
        for (int i = 1; i < m.count; ++i) {
            if (m.points[i].depth > best->depth) best = &m.points[i];
        }
        return *best;
    };
    int shallow = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const Shape a = randomHull(), b = randomHull();
        Pose pa = pose(Vec3(unit(rng), unit(rng), unit(rng)), randomRotation());
        const Pose pb = pose(Vec3(unit(rng), unit(rng), unit(rng)), randomRotation());
        ContactManifold m;
        collideConvexConvex(a, pa, b, pb, 0.0, m);
        expectConsistent(m);
        if (m.count == 0) continue;
        const ContactPoint first = deepest(m);
        pa.position += (first.depth - 0.01) * first.normal;

        m.clear();
        collideConvexConvex(a, pa, b, pb, 0.0, m);
        expectConsistent(m);
        if (m.count == 0) continue;
        ++shallow;
        const ContactPoint contact = deepest(m);
        EXPECT_GE(contact.depth, 0.0);
        ContactManifold apart;
        collideConvexConvex(
            a, pose(pa.position + (contact.depth + 1e-9) * contact.normal, pa.rotation), b, pb, 0.0,
            apart);
        EXPECT_EQ(apart.count, 0) << trial;
    }
    EXPECT_GT(shallow, 100);
}

}  // namespace
}  // namespace substep
