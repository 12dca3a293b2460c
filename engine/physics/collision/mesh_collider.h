#pragma once
/// A static triangle mesh prepared for collision: face normals, which edges and vertices are
/// creases (active) and which lie between near-coplanar or concave neighbours (inactive), and a
/// bounding-volume hierarchy over the triangles, all built once.

#include "physics/collision/shape.h"
#include "physics/collision/static_bvh.h"
#include "physics/collision/triangle_contact.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace substep {

struct MeshCollider {
    std::shared_ptr<const TriangleMesh> mesh;
    std::vector<Vec3> normals;            ///< per triangle, unit (zero for degenerate ones)
    std::vector<uint8_t> activeFeatures;  ///< per triangle, the ContactTriangle flag bits
    std::vector<Aabb> triangleBounds;     ///< per triangle
    StaticBvh tree;                       ///< over the triangles with a normal
    std::vector<int32_t> treeTriangles;   ///< tree item -> triangle index

    /// Calls visit(int triangle) for every triangle whose bounds overlap `box`.
    template <class Visitor>
    void forTrianglesIn(const Aabb& box, Visitor&& visit) const {
        tree.query(box, [&](int item) { visit(static_cast<int>(treeTriangles[item])); });
    }

    /// Triangle i as the contact routines take it.
    ContactTriangle triangle(int i) const {
        const auto& t = mesh->triangles[i];
        ContactTriangle tri;
        tri.v[0] = mesh->vertices[t[0]];
        tri.v[1] = mesh->vertices[t[1]];
        tri.v[2] = mesh->vertices[t[2]];
        tri.normal = normals[i];
        tri.activeFeatures = activeFeatures[i];
        tri.id = static_cast<uint32_t>(i);
        return tri;
    }
};

/// Creases sharper than this (the sine of the angle between neighbouring normals) are active.
inline constexpr double kFlatCreaseSine = 0.02;

/// Whether the edge from `start` shared by a triangle of normal `n` and a neighbour of normal
/// `n2`, whose corner off the edge is `opposite`, is an active crease (activeFeatureFlags' rule).
bool isActiveCrease(const Vec3& n, const Vec3& n2, const Vec3& start, const Vec3& opposite);

/// The ContactTriangle flags of every triangle: an edge is active when it borders one triangle
/// only (or more than two), or when its two triangles meet at a convex crease sharper than
/// kFlatCreaseSine; a vertex is active when any edge at it is. Degenerate triangles (zero
/// normal) are ignored as neighbours.
std::vector<uint8_t> activeFeatureFlags(const TriangleMesh& mesh, const std::vector<Vec3>& normals);

/// Builds the collider. Throws std::invalid_argument for indices out of range or non-finite
/// vertices; zero-area triangles are kept out of the tree (they have no face to push with).
std::shared_ptr<const MeshCollider> makeMeshCollider(std::shared_ptr<const TriangleMesh> mesh);

/// A (non-convex, static) mesh shape with its collider and local bounds.
Shape triangleMeshShape(std::shared_ptr<const TriangleMesh> mesh);

}  // namespace substep
