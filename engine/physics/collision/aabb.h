#pragma once
/// Axis-aligned bounding boxes, the currency of the broadphase.

#include "physics/math.h"

#include <limits>

namespace substep {

struct Aabb {
    Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());

    bool isEmpty() const { return (min.array() > max.array()).any(); }
    bool overlaps(const Aabb& o) const {
        return (min.array() <= o.max.array()).all() && (o.min.array() <= max.array()).all();
    }
    bool contains(const Aabb& o) const {
        return (min.array() <= o.min.array()).all() && (o.max.array() <= max.array()).all();
    }
    void grow(const Vec3& p) {
        min = min.cwiseMin(p);
        max = max.cwiseMax(p);
    }
    void grow(const Aabb& o) {
        min = min.cwiseMin(o.min);
        max = max.cwiseMax(o.max);
    }
    Aabb merged(const Aabb& o) const {
        Aabb r = *this;
        r.grow(o);
        return r;
    }
    Aabb inflated(double margin) const { return {min.array() - margin, max.array() + margin}; }
    Vec3 center() const { return 0.5 * (min + max); }
    Vec3 extents() const { return max - min; }
    /// Half the surface area (the tree's cost measure).
    double halfArea() const {
        const Vec3 e = extents();
        return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
    }
};

}  // namespace substep
