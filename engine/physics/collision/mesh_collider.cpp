#include "physics/collision/mesh_collider.h"

#include <algorithm>
#include <stdexcept>

namespace substep {

namespace {

/// Unit normal of (a, b, c), or zero when the triangle has no area to speak of.
Vec3 faceNormal(const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a;
    const Vec3 ac = c - a;
    const Vec3 cross = ab.cross(ac);
    const double length2 = cross.squaredNorm();
    // Relative test: the sine of the corner angle above 1e-12 (scale-free).
    if (!(length2 > 1e-24 * ab.squaredNorm() * ac.squaredNorm()) || length2 == 0.0) {
        return Vec3::Zero();
    }
    return cross / std::sqrt(length2);
}

struct EdgeUse {
    uint64_t key;  ///< the two vertex indices, smaller first
    int triangle;
    int edge;  ///< 0..2: from corner edge to corner edge + 1
};

}  // namespace

bool isActiveCrease(const Vec3& n, const Vec3& n2, const Vec3& start, const Vec3& opposite) {
    const Vec3 toOpposite = opposite - start;
    const double height = n.dot(toOpposite);
    const double tolerance = 1e-9 * toOpposite.norm();
    if (height > tolerance) return false;              // concave: faces hold it from inside
    if (height >= -tolerance) return n.dot(n2) < 0.0;  // coplanar: flat unless folded over
    return n.dot(n2) < 0.0 || n.cross(n2).norm() > kFlatCreaseSine;
}

std::vector<uint8_t> activeFeatureFlags(const TriangleMesh& mesh,
                                        const std::vector<Vec3>& normals) {
    const int triangleCount = static_cast<int>(mesh.triangles.size());
    std::vector<EdgeUse> uses;
    uses.reserve(3 * mesh.triangles.size());
    for (int t = 0; t < triangleCount; ++t) {
        if (normals[t].isZero(0.0)) continue;
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = static_cast<uint32_t>(mesh.triangles[t][e]);
            const uint32_t b = static_cast<uint32_t>(mesh.triangles[t][(e + 1) % 3]);
            uses.push_back({(uint64_t{std::min(a, b)} << 32) | std::max(a, b), t, e});
        }
    }
    std::sort(uses.begin(), uses.end(),
              [](const EdgeUse& x, const EdgeUse& y) { return x.key < y.key; });

    std::vector<uint8_t> flags(mesh.triangles.size(), 0);
    std::vector<bool> vertexActive(mesh.vertices.size(), false);
    // Whether triangle `t`'s edge `e` is a crease as seen against neighbour triangle `other`.
    const auto isCrease = [&](int t, int e, int other) {
        const Vec3& n = normals[t];
        const Vec3& n2 = normals[other];
        const Vec3& start = mesh.vertices[mesh.triangles[t][e]];
        const auto& o = mesh.triangles[other];
        // The neighbour's corner off the shared edge: below our plane means a convex crease.
        Vec3 opposite = mesh.vertices[o[0]];
        const int ea = mesh.triangles[t][e];
        const int eb = mesh.triangles[t][(e + 1) % 3];
        for (int k = 0; k < 3; ++k) {
            if (o[k] != ea && o[k] != eb) opposite = mesh.vertices[o[k]];
        }
        return isActiveCrease(n, n2, start, opposite);
    };
    for (std::size_t begin = 0; begin < uses.size();) {
        std::size_t end = begin + 1;
        while (end < uses.size() && uses[end].key == uses[begin].key)
            ++end;
        for (std::size_t i = begin; i < end; ++i) {
            const EdgeUse& use = uses[i];
            bool active = true;  // a border, or an edge shared by more than two triangles
            if (end - begin == 2) {
                const EdgeUse& other = uses[i == begin ? begin + 1 : begin];
                active = isCrease(use.triangle, use.edge, other.triangle);
            }
            if (active) {
                flags[use.triangle] |= static_cast<uint8_t>(kEdgeActive0 << use.edge);
                const auto& tri = mesh.triangles[use.triangle];
                vertexActive[tri[use.edge]] = true;
                vertexActive[tri[(use.edge + 1) % 3]] = true;
            }
        }
        begin = end;
    }
    for (int t = 0; t < triangleCount; ++t) {
        for (int k = 0; k < 3; ++k) {
            if (vertexActive[mesh.triangles[t][k]]) {
                flags[t] |= static_cast<uint8_t>(kVertexActive0 << k);
            }
        }
    }
    return flags;
}

std::shared_ptr<const MeshCollider> makeMeshCollider(std::shared_ptr<const TriangleMesh> mesh) {
    if (!mesh) throw std::invalid_argument("makeMeshCollider: no mesh");
    for (const Vec3& v : mesh->vertices) {
        if (!v.allFinite()) throw std::invalid_argument("makeMeshCollider: non-finite vertex");
    }
    const int vertexCount = static_cast<int>(mesh->vertices.size());
    for (const auto& t : mesh->triangles) {
        for (int index : t) {
            if (index < 0 || index >= vertexCount) {
                throw std::invalid_argument("makeMeshCollider: vertex index out of range");
            }
        }
    }
    auto collider = std::make_shared<MeshCollider>();
    const std::size_t count = mesh->triangles.size();
    collider->normals.resize(count);
    collider->triangleBounds.resize(count);
    std::vector<Aabb> treeBoxes;
    for (std::size_t i = 0; i < count; ++i) {
        const auto& t = mesh->triangles[i];
        const Vec3& a = mesh->vertices[t[0]];
        const Vec3& b = mesh->vertices[t[1]];
        const Vec3& c = mesh->vertices[t[2]];
        collider->normals[i] = faceNormal(a, b, c);
        Aabb box;
        box.grow(a);
        box.grow(b);
        box.grow(c);
        collider->triangleBounds[i] = box;
        if (!collider->normals[i].isZero(0.0)) {
            treeBoxes.push_back(box);
            collider->treeTriangles.push_back(static_cast<int32_t>(i));
        }
    }
    collider->activeFeatures = activeFeatureFlags(*mesh, collider->normals);
    collider->tree.build(treeBoxes);
    collider->mesh = std::move(mesh);
    return collider;
}

Shape triangleMeshShape(std::shared_ptr<const TriangleMesh> mesh) {
    Shape shape{.type = ShapeType::Mesh};
    shape.meshCollider = makeMeshCollider(mesh);
    shape.localBounds = shape.meshCollider->tree.bounds();
    shape.mesh = std::move(mesh);
    return shape;
}

}  // namespace substep
