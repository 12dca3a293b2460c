#pragma once
/// What the narrowphase reports for one pair of shapes: the contact points, each with the
/// points on both surfaces, the normal and the depth, in world coordinates.
///
/// Convention (the same as the joints'): shape 0 is the first shape of the pair, and the normal
/// points from shape 1 towards shape 0, the direction shape 0 must move to separate. The depth
/// is (point1 − point0)·normal: positive while the shapes overlap, negative for a gap. Points
/// with a gap up to the requested margin are reported too (speculative contacts), so a caller
/// can test the depth again on the current poses of later substeps.

#include "physics/math.h"

#include <array>
#include <cstdint>

namespace substep {

/// A shape's pose: its user frame in world coordinates.
struct Pose {
    Vec3 position = Vec3::Zero();
    Quat rotation = Quat::Identity();

    Vec3 apply(const Vec3& local) const { return position + rotation * local; }
    Vec3 applyInverse(const Vec3& world) const { return rotation.conjugate() * (world - position); }
};

struct ContactPoint {
    Vec3 point0 = Vec3::Zero();  ///< on the surface of shape 0 (world)
    Vec3 point1 = Vec3::Zero();  ///< on the surface of shape 1 (world)
    Vec3 normal = Vec3::UnitY(); ///< unit, from shape 1 towards shape 0
    double depth = 0.0;          ///< (point1 − point0)·normal; > 0 overlapping
    /// Identifies the pair of features that made the point (a box corner, a clipped edge, a
    /// triangle), stable while the contact keeps its features; 0 when the pair has no such id.
    uint32_t feature = 0;
};

/// Enough points for a box to rest flat on a face (4) and for a capsule or box lying across
/// several triangles of a mesh.
inline constexpr int kMaxContactPoints = 8;

struct ContactManifold {
    std::array<ContactPoint, kMaxContactPoints> points;
    int count = 0;

    void clear() { count = 0; }
    bool full() const { return count == kMaxContactPoints; }
    /// Appends a point unless the manifold is full; returns whether it was added.
    bool add(const ContactPoint& p) {
        if (count == kMaxContactPoints) return false;
        points[count++] = p;
        return true;
    }
};

}  // namespace substep
