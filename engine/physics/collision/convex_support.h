#pragma once
/// Support functions of the convex shapes, for the general convex pair (gjk_epa.h,
/// convex_manifold.h). A shape is a core (a point, a segment, a box, a cylinder, a hull, a
/// triangle) grown by a radius: a sphere is a point of radius r, a capsule a segment of radius r,
/// the others have radius 0. Distances are found between the cores and the radii added after,
/// so spheres and capsules stay exact (no polytope approximates their round surfaces).
///
/// Everything is expressed in one common frame chosen by the caller (the world, or a mesh's own
/// frame for triangles). Support queries switch on the core's kind: no virtual dispatch.

#include "physics/collision/contact_manifold.h"
#include "physics/collision/shape.h"
#include "physics/math.h"

#include <array>
#include <cstdint>

namespace substep {

struct ConvexHull;
struct ContactTriangle;

enum class CoreKind : uint8_t { Point, Segment, Box, Cylinder, Hull, Triangle };

/// The most vertices a support feature has: a cylinder's face is a 12-gon; hull faces with
/// more vertices are thinned to this many.
inline constexpr int kMaxFeatureVertices = 16;
/// The polygon standing for a cylinder's flat face (its vertices lie on the true rim).
inline constexpr int kCylinderFaceVertices = 12;

/// What a core shows in one direction: a vertex (1 point), an edge (2) or a face polygon (3 or
/// more, in order around it), with the face's outward normal and how well it faces the query
/// direction (1: exactly; a vertex or an edge has 0).
struct SupportFeature {
    std::array<Vec3, kMaxFeatureVertices> vertices;
    int count = 0;
    Vec3 normal = Vec3::UnitY();
    double alignment = 0.0;
    /// The feature's id on its shape (a face index, a vertex index), for contact feature ids.
    uint32_t id = 0;
};

/// A convex shape's core and radius in a common frame.
struct ConvexSupport {
    CoreKind kind = CoreKind::Point;
    Vec3 centre = Vec3::Zero();     ///< the core's centre (a point strictly inside it)
    Mat3 axes = Mat3::Identity();   ///< the core's local axes as columns
    Vec3 half = Vec3::Zero();       ///< box: half extents; segment, cylinder: y = half length,
                                    ///< cylinder: x = radius
    double radius = 0.0;            ///< rounding: sphere and capsule radius
    Vec3 origin = Vec3::Zero();     ///< hull: its frame's origin (the hull's vertices are local)
    const ConvexHull* hull = nullptr;
    std::array<Vec3, 3> triangle{}; ///< triangle vertices, counter-clockwise from the front
    Vec3 triangleNormal = Vec3::UnitY();
    mutable int warmStart = 0;      ///< hull: the last support vertex (the climb starts there)

    /// The core's point farthest along `direction` (need not be unit; zero gives some point).
    Vec3 support(const Vec3& direction) const;
    /// The core's feature farthest along the unit `direction`: a polytope's (box, hull,
    /// triangle) face turned most towards it; a cylinder's flat face when its axis lies within
    /// kCylinderFlatSine of the direction, its side line within kCylinderSideCosine, else the
    /// rim point; a capsule's segment when it lies across the direction, else an end.
    void feature(const Vec3& direction, SupportFeature& out) const;
    /// A length standing for the shape's size (for relative tolerances).
    double size() const;
};

/// The support of `shape` at `pose`, expressed in `frame`'s coordinates (the identity pose for
/// world coordinates). Returns false for shapes that are not convex (planes, triangle meshes,
/// heightfields, splines, hulls that enclose no volume).
bool makeConvexSupport(const Shape& shape, const Pose& pose, const Pose& frame,
                       ConvexSupport& out);

/// The support of one mesh or heightfield triangle (in the mesh's frame).
ConvexSupport triangleSupport(const ContactTriangle& triangle);

}  // namespace substep
