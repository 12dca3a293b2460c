/// Convex shapes against static triangle meshes and heightfields (collide_general.h): the
/// general convex pair per triangle, in the frame of the mesh, duplicates found from
/// neighbouring triangles merged by a ContactBuffer.

#include "physics/collision/collide_general.h"
#include "physics/collision/contact_buffer.h"
#include "physics/collision/convex_manifold.h"
#include "physics/collision/heightfield.h"
#include "physics/collision/mesh_collider.h"
#include "physics/collision/triangle_contact.h"

#include <algorithm>

namespace substep {

namespace {

/// Two contacts closer than this fraction of the shape's size are one.
constexpr double kMergeFraction = 0.01;

/// How far past the closest pair the triangle's feature is probed, as a fraction of the
/// shape's size: far enough to leave a vertex or edge it sits exactly on.
constexpr double kFeatureProbe = 1e-3;

/// The shape's bounds in the mesh frame from six support queries, grown by its radius.
Aabb supportBounds(const ConvexSupport& s) {
    Aabb box;
    for (int k = 0; k < 3; ++k) {
        const Vec3 axis = Vec3::Unit(k);
        box.grow(s.support(axis));
        box.grow(s.support(-axis));
    }
    return box.inflated(s.radius);
}

/// Whether the triangle's feature nearest `probe` is an inactive edge or vertex (between
/// near-coplanar or concave neighbours), where only the face normal may push.
bool onInactiveFeature(const ContactTriangle& tri, const Vec3& probe) {
    const TrianglePoint p = closestOnTriangle(probe, tri.v[0], tri.v[1], tri.v[2]);
    switch (p.feature) {
        case TriangleFeature::Face:
            return false;
        case TriangleFeature::Vertex:
            return !tri.vertexActive(p.index);
        case TriangleFeature::Edge:
            return !tri.edgeActive(p.index);
    }
    return false;
}

void addTriangleContacts(const ConvexSupport& s, const ContactTriangle& tri, double margin,
                         bool solidBelow, ContactBuffer& buffer) {
    const Vec3& n = tri.normal;
    const Vec3 lowest = s.support(-n);
    const double coreHeight = n.dot(lowest - tri.v[0]);  // of the core's lowest point
    if (coreHeight - s.radius > margin) return;
    // A one-sided triangle lets go of a shape that has passed wholly behind it.
    if (!solidBelow && n.dot(s.support(n) - tri.v[0]) + s.radius < 0.0) return;

    const ConvexSupport triangle = triangleSupport(tri);
    ConvexDistance deepest;
    bool faceNormal = false;
    if (solidBelow && n.dot(s.centre - tri.v[0]) < 0.0 &&
        closestOnTriangle(s.centre, tri.v[0], tri.v[1], tri.v[2]).feature ==
            TriangleFeature::Face) {
        // Sunk with its centre under this triangle: up along the face normal, however deep.
        faceNormal = true;
    } else {
        deepest = convexDistance(s, triangle, margin + s.radius);
        if (deepest.beyondCutoff) return;
    }
    const double along = deepest.normal.dot(n);
    if (!faceNormal) faceNormal = along <= 0.0;  // pushing the shape through the triangle: never
    if (!faceNormal && along < 1.0 - 1e-9) {
        const double step = std::max(deepest.separation, kFeatureProbe * s.size());
        faceNormal = onInactiveFeature(tri, deepest.pointB + step * deepest.normal);
    }
    if (faceNormal) {
        deepest.normal = n;
        deepest.pointA = lowest;
        deepest.separation = coreHeight;
        deepest.pointB = lowest - coreHeight * n;
    }
    ContactManifold points;
    buildConvexManifold(s, triangle, deepest, margin, tri.id * 2654435761u, points);
    for (int k = 0; k < points.count; ++k)
        buffer.add(points.points[k]);
}

template <class ForTriangles>
void convexAgainstTriangles(const Shape& a, const Pose& pa, const Pose& pb, double margin,
                            bool solidBelow, ForTriangles&& forTrianglesIn,
                            ContactManifold& out) {
    ConvexSupport s;
    if (!makeConvexSupport(a, pa, pb, s)) return;
    ContactBuffer buffer(kMergeFraction * (s.size() + s.radius));
    forTrianglesIn(supportBounds(s).inflated(margin), [&](const ContactTriangle& tri) {
        addTriangleContacts(s, tri, margin, solidBelow, buffer);
    });
    buffer.emit(pb, out);
}

}  // namespace

void collideConvexTriangleMesh(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                               double margin, ContactManifold& out) {
    out.clear();
    if (!b.meshCollider) return;
    const MeshCollider& mesh = *b.meshCollider;
    convexAgainstTriangles(
        a, pa, pb, margin, false,
        [&](const Aabb& box, auto&& visit) {
            mesh.forTrianglesIn(box, [&](int i) { visit(mesh.triangle(i)); });
        },
        out);
}

void collideConvexHeightfield(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                              double margin, ContactManifold& out) {
    out.clear();
    if (!b.heightfield) return;
    const HeightfieldData& field = *b.heightfield;
    convexAgainstTriangles(
        a, pa, pb, margin, true,
        [&](const Aabb& box, auto&& visit) { field.forTrianglesIn(box, visit); }, out);
}

}  // namespace substep
