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
#include <array>

namespace substep {

namespace {

/// Two contacts closer than this fraction of the shape's size are one.
constexpr double kMergeFraction = 0.01;

/// A contact normal this close to the triangle's face normal is taken as the face normal.
constexpr double kFaceNormalCosine = 1.0 - 1e-6;

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
    // Pushing the shape through the triangle: never. Within kFaceNormalCosine of the face
    // normal: the face normal itself, so that the points of neighbouring coplanar triangles
    // share one normal (the patch solve of a flat cylinder on a heightfield otherwise met rows
    // 2e-5 rad apart and kicked it sideways at 6 rad/s).
    if (!faceNormal) faceNormal = along <= 0.0;
    if (!faceNormal && along >= kFaceNormalCosine) {
        // The same pair of points, measured along the face normal.
        deepest.normal = n;
        deepest.separation = (deepest.pointA - deepest.pointB).dot(n);
    } else if (!faceNormal) {
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
    // The 4 spanning the patch, as the general pair keeps for one face: the deepest 8 of a
    // flat cylinder's rim points over several triangles cluster on one side, and the patch
    // rocked about them (2 mm/s at rest).
    std::array<ContactPoint, 64> points;
    const int count = std::min(buffer.count(), static_cast<int>(points.size()));
    for (int k = 0; k < count; ++k) {
        points[k] = buffer[k];
        points[k].point0 = pb.apply(points[k].point0);
        points[k].point1 = pb.apply(points[k].point1);
        points[k].normal = pb.rotation * points[k].normal;
    }
    appendSpanningPoints(points.data(), count, out);
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
