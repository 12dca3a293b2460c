#pragma once
/// Contacts of spheres, capsules and boxes with single triangles, shared by triangle meshes and
/// heightfields. Everything is in the frame of the mesh; results go into a ContactBuffer.
///
/// Triangles are one-sided: the front normal n = (v1 − v0) × (v2 − v0) / |...| is the direction
/// they push. Each knows which of its edges and vertices are "active" (on the boundary or on a
/// convex crease): contacts found on inactive features (between near-coplanar or concave
/// neighbours) use the face normal instead of the direction to the feature, so bodies sliding
/// over a flat mesh do not catch on the edges between its triangles.

#include "physics/collision/contact_buffer.h"
#include "physics/math.h"

#include <cstdint>

namespace substep {

/// Flag bits of a triangle's features: edge i runs from v[i] to v[(i + 1) % 3].
inline constexpr uint8_t kEdgeActive0 = 1u << 0;
inline constexpr uint8_t kVertexActive0 = 1u << 3;
inline constexpr uint8_t kAllFeaturesActive = 0x3f;

struct ContactTriangle {
    Vec3 v[3];
    Vec3 normal = Vec3::UnitY();                  ///< unit front normal
    uint8_t activeFeatures = kAllFeaturesActive;  ///< kEdgeActive0 << i, kVertexActive0 << i
    uint32_t id = 0;                              ///< triangle index, for contact feature ids

    bool edgeActive(int i) const { return activeFeatures & (kEdgeActive0 << i); }
    bool vertexActive(int i) const { return activeFeatures & (kVertexActive0 << i); }
};

/// Inactive features whose closest point sits farther than this (in sphere radii) sideways from
/// the sphere's foot on the plane are left to the neighbour triangle, which holds that foot;
/// nearer ones cover the sliver a slightly convex crease leaves between the two faces
/// (addSphereTriangleContacts).
inline constexpr double kInactiveSideways = 0.05;

/// The triangle's feature a closest point lies on.
enum class TriangleFeature : uint8_t { Face, Vertex, Edge };

struct TrianglePoint {
    Vec3 point = Vec3::Zero();
    TriangleFeature feature = TriangleFeature::Face;
    int index = 0;  ///< vertex or edge index
};

/// Closest point of the triangle to p (Ericson's Voronoi-region walk). Zero-area triangles
/// give the closest point of their edges.
TrianglePoint closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// Closest points of segments [p0, p1] and [q0, q1]: parameters s on the first, t on the second.
void closestSegmentSegment(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1,
                           double& s, double& t);

/// A contact's feature id: the triangle's index times 64 plus a local code (the face's is 0, a
/// vertex's 1-3, an edge's 4-6, the capsule and box features' above).
inline uint32_t triangleFeatureId(uint32_t triangleId, uint32_t local) { return triangleId * 64u + local; }

/// A sphere's contact along a triangle's unit front normal n, its centre c at `height` above the
/// plane: the foot c − height n, depth r − height; none beyond the margin. The face normal of
/// addSphereTriangleContacts, which a heightfield also writes directly for a foot clearly
/// inside a triangle.
inline void addSphereFaceNormalContact(const Vec3& n, double height, const Vec3& c, double r, double margin,
                                       uint32_t feature, ContactBuffer& buffer) {
    ContactPoint contact;
    contact.normal = n;
    contact.depth = r - height;
    if (contact.depth < -margin) return;
    contact.point1 = c - height * n;
    contact.point0 = c - r * n;
    contact.feature = feature;
    buffer.add(contact);
}

/// Sphere (centre c, radius r). `solidBelow`: a heightfield pushes up whatever lies under its
/// surface; a mesh triangle lets go of a shape once that has passed entirely behind its plane.
void addSphereTriangleContacts(const ContactTriangle& tri, const Vec3& c, double r, double margin,
                               bool solidBelow, ContactBuffer& buffer);

/// Capsule of radius r around the segment [e0, e1]: its caps and, on active edges, the axis.
void addCapsuleTriangleContacts(const ContactTriangle& tri, const Vec3& e0, const Vec3& e1,
                                double r, double margin, bool solidBelow, ContactBuffer& buffer);

/// A box: centre, unit axes (columns of `axes`), half extents.
struct OrientedBox {
    Vec3 centre = Vec3::Zero();
    Mat3 axes = Mat3::Identity();
    Vec3 half = Vec3::Zero();
};

/// Box against triangle by separating axes (face normal, box faces, edge pairs), then clipping:
/// up to 4 points from a face, 1 from an edge pair.
void addBoxTriangleContacts(const ContactTriangle& tri, const OrientedBox& box, double margin,
                            bool solidBelow, ContactBuffer& buffer);

}  // namespace substep
