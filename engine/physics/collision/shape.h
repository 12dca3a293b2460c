#pragma once
/// Shape descriptions: the geometry a body carries, used for its mass properties now and for
/// collision (broadphase bounds, narrowphase dispatch) as the collision module grows.

#include "physics/collision/aabb.h"
#include "physics/math.h"

#include <array>
#include <memory>
#include <vector>

namespace substep {

enum class ShapeType { None, Sphere, Box, Capsule, Plane, Mesh, Heightfield, Spline, Cylinder };

// Collision data of the shapes that need more than a few numbers; each is defined in its own
// header under collision/ and shared between bodies that use the same geometry.
struct ConvexHull;       ///< convex_hull.h: a mesh's hull (mesh with convex = true)
struct MeshCollider;     ///< mesh_collider.h: a static triangle mesh with its BVH
struct HeightfieldData;  ///< heightfield.h: a regular grid of heights
struct SplineTube;       ///< spline_tube.h: a tube around a Hermite spline

/// A closed (for mass properties) or open triangle mesh in its own frame.
struct TriangleMesh {
    std::vector<Vec3> vertices;
    std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from outside
};

/// One shape in the body's user frame (the frame its pose and joint anchors are given in).
struct Shape {
    ShapeType type = ShapeType::None;
    double radius = 0.0;                 ///< sphere, capsule, cylinder
    Vec3 size = Vec3::Zero();            ///< box: full extents
    double length = 0.0;                 ///< capsule: segment between cap centres; cylinder: between
                                         ///< its flat faces; both along local y
    Vec3 normal = Vec3::UnitY();         ///< plane: n·x = offset, world coordinates
    double offset = 0.0;                 ///< plane
    std::shared_ptr<const TriangleMesh> mesh;  ///< mesh (already scaled)
    bool convex = false;                 ///< mesh: collide as its convex hull
    std::shared_ptr<const ConvexHull> hull;            ///< mesh with convex = true
    std::shared_ptr<const MeshCollider> meshCollider;  ///< mesh with convex = false (static)
    std::shared_ptr<const HeightfieldData> heightfield;
    std::shared_ptr<const SplineTube> spline;
    /// Bounds in the shape's own frame for mesh, heightfield and spline shapes (the builders of
    /// their collision data fill it); the primitives' bounds follow from their parameters.
    Aabb localBounds;
};

inline Shape sphereShape(double radius) { return {.type = ShapeType::Sphere, .radius = radius}; }
inline Shape boxShape(const Vec3& size) { return {.type = ShapeType::Box, .size = size}; }
inline Shape capsuleShape(double radius, double length) {
    return {.type = ShapeType::Capsule, .radius = radius, .length = length};
}
/// A solid circular cylinder (a coin, a wheel, a can): flat faces at y = ±length/2.
inline Shape cylinderShape(double radius, double length) {
    return {.type = ShapeType::Cylinder, .radius = radius, .length = length};
}
inline Shape planeShape(const Vec3& normal, double offset) {
    return {.type = ShapeType::Plane, .normal = normal, .offset = offset};
}

}  // namespace substep
