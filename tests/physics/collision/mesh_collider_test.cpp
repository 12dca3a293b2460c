// Tests engine/physics/collision/mesh_collider.cpp (and the StaticBvh it builds): tree queries
// equal brute force over all triangles, creases are flagged by geometry, bad input is caught.

#include "physics/collision/mesh_collider.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <stdexcept>

namespace substep {
namespace {

/// A bumpy open grid of n x n quads (2 triangles each) over [0, n]².
std::shared_ptr<TriangleMesh> bumpyGrid(int n, double bump) {
    auto mesh = std::make_shared<TriangleMesh>();
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            mesh->vertices.emplace_back(i, bump * std::sin(1.3 * i) * std::cos(0.7 * j), j);
        }
    }
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            mesh->triangles.push_back({a, c, d});
            mesh->triangles.push_back({a, d, b});
        }
    }
    return mesh;
}

TEST(MeshCollider, TreeQueryEqualsBruteForce) {
    const auto mesh = bumpyGrid(20, 0.5);
    const auto collider = makeMeshCollider(mesh);
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-2.0, 22.0), size(0.0, 3.0);
    for (int trial = 0; trial < 300; ++trial) {
        const Vec3 lo(u(rng), 0.3 * u(rng) - 3.0, u(rng));
        const Aabb box{lo, lo + Vec3(size(rng), size(rng), size(rng))};
        std::vector<int> found;
        collider->forTrianglesIn(box, [&](int i) { found.push_back(i); });
        std::vector<int> brute;
        for (int i = 0; i < static_cast<int>(mesh->triangles.size()); ++i) {
            if (collider->triangleBounds[i].overlaps(box)) brute.push_back(i);
        }
        std::sort(found.begin(), found.end());
        EXPECT_EQ(found, brute) << "trial " << trial;
    }
}

TEST(MeshCollider, NormalsFollowTheWinding) {
    const auto collider = makeMeshCollider(bumpyGrid(2, 0.0));
    for (const Vec3& n : collider->normals)
        EXPECT_TRUE(n.isApprox(Vec3::UnitY()));
}

TEST(MeshCollider, FlatInteriorEdgesAreInactiveAndBordersActive) {
    const auto collider = makeMeshCollider(bumpyGrid(2, 0.0));
    // Triangle 0 is (0, 3, 4): its edge 0 (x = 0) lies on the border, edge 2 (4 -> 0, the
    // diagonal) is shared with the coplanar triangle 1.
    const ContactTriangle tri = collider->triangle(0);
    EXPECT_TRUE(tri.edgeActive(0));
    EXPECT_FALSE(tri.edgeActive(2));
    // The centre vertex 4 of the 2 x 2 grid has only flat edges round it.
    const ContactTriangle centre = collider->triangle(0);
    EXPECT_FALSE(centre.vertexActive(2));
    EXPECT_TRUE(centre.vertexActive(0));
}

TEST(MeshCollider, ConvexCreasesAreActiveConcaveOnesNot) {
    // Two triangles hinged along the z axis: a roof (convex) and a valley (concave).
    for (const double y : {-0.5, 0.5}) {
        auto mesh = std::make_shared<TriangleMesh>();
        mesh->vertices = {{0, 0, 0}, {0, 0, 1}, {1, y, 0}, {-1, y, 0}};
        mesh->triangles = {{0, 1, 2}, {0, 3, 1}};
        const auto collider = makeMeshCollider(mesh);
        ASSERT_GT(collider->normals[0].y(), 0.0);
        ASSERT_GT(collider->normals[1].y(), 0.0);
        const bool roof = y < 0.0;
        EXPECT_EQ(collider->triangle(0).edgeActive(0), roof);  // edge 0 -> 1, the hinge
        EXPECT_EQ(collider->triangle(1).edgeActive(2), roof);  // edge 1 -> 0
    }
}

TEST(MeshCollider, DegenerateTrianglesStayOutOfTheTree) {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 0, 1}};
    mesh->triangles = {{0, 1, 2}, {0, 3, 1}, {1, 1, 1}};
    const auto collider = makeMeshCollider(mesh);
    EXPECT_TRUE(collider->normals[0].isZero(0.0));
    EXPECT_TRUE(collider->normals[2].isZero(0.0));
    std::vector<int> found;
    collider->forTrianglesIn({Vec3::Constant(-10), Vec3::Constant(10)},
                             [&](int i) { found.push_back(i); });
    EXPECT_EQ(found, std::vector<int>{1});
}

TEST(MeshCollider, RejectsBadInput) {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->vertices = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
    mesh->triangles = {{0, 1, 3}};
    EXPECT_THROW(makeMeshCollider(mesh), std::invalid_argument);
    mesh->triangles = {{0, 1, 2}};
    mesh->vertices[1].x() = NAN;
    EXPECT_THROW(makeMeshCollider(mesh), std::invalid_argument);
    EXPECT_THROW(makeMeshCollider(nullptr), std::invalid_argument);
}

TEST(MeshCollider, ShapeCarriesBounds) {
    const Shape shape = triangleMeshShape(bumpyGrid(3, 0.0));
    EXPECT_EQ(shape.type, ShapeType::Mesh);
    ASSERT_TRUE(shape.meshCollider);
    EXPECT_TRUE(shape.localBounds.min.isApprox(Vec3(0, 0, 0)));
    EXPECT_TRUE(shape.localBounds.max.isApprox(Vec3(3, 0, 3)));
    // An empty mesh gives an empty shape that collides with nothing.
    const Shape empty = triangleMeshShape(std::make_shared<TriangleMesh>());
    EXPECT_TRUE(empty.localBounds.isEmpty());
}

}  // namespace
}  // namespace substep
