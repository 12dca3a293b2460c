// Tests engine/render/mesh_builders.cpp: every mesh is well formed, its normals point outwards,
// and its triangles wind counter-clockwise seen from outside (so back-face culling is safe).

#include "render/mesh_builders.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace substep::render {
namespace {

Vec3f position(const MeshVertex& v) { return {v.position[0], v.position[1], v.position[2]}; }
Vec3f normal(const MeshVertex& v) { return {v.normal[0], v.normal[1], v.normal[2]}; }

/// Indices in range, unit normals, and each triangle's winding agreeing with its vertex normals.
void expectWellFormed(const MeshData& mesh) {
    ASSERT_FALSE(mesh.indices.empty());
    ASSERT_EQ(mesh.indices.size() % 3, 0u);
    for (const uint32_t index : mesh.indices) ASSERT_LT(index, mesh.vertices.size());
    for (const MeshVertex& v : mesh.vertices) EXPECT_NEAR(normal(v).norm(), 1.0f, 1e-4f);
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        const MeshVertex& a = mesh.vertices[mesh.indices[t]];
        const MeshVertex& b = mesh.vertices[mesh.indices[t + 1]];
        const MeshVertex& c = mesh.vertices[mesh.indices[t + 2]];
        const Vec3f faceNormal = (position(b) - position(a)).cross(position(c) - position(a));
        if (faceNormal.norm() < 1e-6f) continue;  // the poles' degenerate triangles
        EXPECT_GT(faceNormal.dot(normal(a) + normal(b) + normal(c)), 0.0f) << "triangle " << t / 3;
    }
}

/// Every vertex normal points away from the given centre line's nearest point.
void expectNormalsOutward(const MeshData& mesh, float halfLength) {
    for (const MeshVertex& v : mesh.vertices) {
        const Vec3f p = position(v);
        const Vec3f axisPoint(0.0f, std::clamp(p.y(), -halfLength, halfLength), 0.0f);
        EXPECT_GT(normal(v).dot(p - axisPoint), 0.0f);
    }
}

TEST(MeshBuilders, UnitSphereHasRadiusOneAndOutwardNormals) {
    const MeshData mesh = unitSphereMesh(8, 16);
    expectWellFormed(mesh);
    for (const MeshVertex& v : mesh.vertices) EXPECT_NEAR(position(v).norm(), 1.0f, 1e-5f);
    expectNormalsOutward(mesh, 0.0f);
}

TEST(MeshBuilders, UnitBoxSpansMinusHalfToHalf) {
    const MeshData mesh = unitBoxMesh();
    expectWellFormed(mesh);
    EXPECT_EQ(mesh.indices.size(), 36u);
    for (const MeshVertex& v : mesh.vertices) EXPECT_FLOAT_EQ(position(v).cwiseAbs().maxCoeff(), 0.5f);
    expectNormalsOutward(mesh, 0.0f);
}

TEST(MeshBuilders, CapsuleReachesItsCapsAlongY) {
    const MeshData mesh = capsuleMesh(0.2f, 1.0f, 6, 12);
    expectWellFormed(mesh);
    float top = -1.0f;
    float bottom = 1.0f;
    for (const MeshVertex& v : mesh.vertices) {
        top = std::max(top, v.position[1]);
        bottom = std::min(bottom, v.position[1]);
    }
    EXPECT_NEAR(top, 0.7f, 1e-5f);
    EXPECT_NEAR(bottom, -0.7f, 1e-5f);
    expectNormalsOutward(mesh, 0.5f);
}

TEST(MeshBuilders, FlatShadedMeshGivesEachTriangleItsNormal) {
    const std::vector<Vec3f> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const std::vector<uint32_t> triangle = {0, 1, 2};
    const MeshData mesh = flatShadedMesh(points, triangle);
    expectWellFormed(mesh);
    ASSERT_EQ(mesh.vertices.size(), 3u);
    EXPECT_TRUE(normal(mesh.vertices[0]).isApprox(Vec3f::UnitZ()));
}

TEST(MeshBuilders, HeightfieldFollowsItsHeightsAndFacesUp) {
    const std::vector<float> heights = {0, 0, 0, 0, 1, 0, 0, 0, 0};
    const MeshData mesh = heightfieldMesh(3, 3, Vec2f(-0.5f, -0.5f), Vec2f(0.5f, 0.5f), heights);
    expectWellFormed(mesh);
    EXPECT_EQ(mesh.vertices.size(), 9u);
    EXPECT_EQ(mesh.indices.size(), 4u * 6u);
    EXPECT_FLOAT_EQ(mesh.vertices[4].position[1], 1.0f);
    EXPECT_FLOAT_EQ(mesh.vertices[0].position[0], -0.5f);
    EXPECT_FLOAT_EQ(mesh.vertices[8].position[0], 0.5f);
    EXPECT_FLOAT_EQ(mesh.vertices[8].position[2], 0.5f);
    for (const MeshVertex& v : mesh.vertices) EXPECT_GT(v.normal[1], 0.0f);
    EXPECT_TRUE(heightfieldMesh(1, 3, Vec2f(0, 0), Vec2f(1, 1), heights).indices.empty());
}

TEST(MeshBuilders, TubeSurroundsItsCurveAtItsRadius) {
    std::vector<Vec3f> centres;
    for (int i = 0; i <= 20; ++i) centres.emplace_back(std::cos(i * 0.1f), std::sin(i * 0.1f), 0.1f * i);
    const MeshData open = tubeMesh(centres, 0.05f, false, 8);
    expectWellFormed(open);
    for (const MeshVertex& v : open.vertices) {
        float nearest = 1e9f;
        for (const Vec3f& c : centres) nearest = std::min(nearest, (position(v) - c).norm());
        EXPECT_LE(nearest, 0.05f + 1e-4f);
    }
    // A closed tube: a ring, its last point joined back to the first.
    std::vector<Vec3f> ring;
    for (int i = 0; i < 24; ++i) ring.emplace_back(std::cos(i * 0.2618f), 0.0f, std::sin(i * 0.2618f));
    const MeshData closed = tubeMesh(ring, 0.05f, true, 8);
    expectWellFormed(closed);
    EXPECT_TRUE(tubeMesh(std::vector<Vec3f>{Vec3f::Zero()}, 0.05f, false).indices.empty());
}

}  // namespace
}  // namespace substep::render
