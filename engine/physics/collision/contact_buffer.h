#pragma once
/// Candidate contacts of one pair, gathered in the frame of the complex shape (spline, mesh,
/// heightfield) before the best of them go into the manifold. Fixed capacity, no allocation:
/// near-duplicates (the same contact found from two triangles sharing an edge, or from two
/// segments meeting at a control point) are merged, and when full the shallowest gives way.

#include "physics/collision/contact_manifold.h"

#include <algorithm>
#include <cstddef>
#include <new>
#include <type_traits>

namespace substep {

class ContactBuffer {
  public:
    /// Points whose surface points lie within `mergeDistance` with normals within about 2.5°
    /// count as one contact (the deeper is kept).
    explicit ContactBuffer(double mergeDistance) : mergeDistance2_(mergeDistance * mergeDistance) {}
    ContactBuffer(const ContactBuffer&) = delete;  // points_ points into this object
    ContactBuffer& operator=(const ContactBuffer&) = delete;

    void add(const ContactPoint& p) {
        for (int i = 0; i < count_; ++i) {
            ContactPoint& q = points_[i];
            if ((q.point1 - p.point1).squaredNorm() <= mergeDistance2_ &&
                q.normal.dot(p.normal) > kSameNormalCosine) {
                if (p.depth > q.depth) q = p;
                return;
            }
        }
        if (count_ < kCapacity) {
            new (&points_[count_++]) ContactPoint(p);
            return;
        }
        ContactPoint* shallowest = std::min_element(
            points_, points_ + count_,
            [](const ContactPoint& a, const ContactPoint& b) { return a.depth < b.depth; });
        if (p.depth > shallowest->depth) *shallowest = p;
    }

    int count() const { return count_; }
    const ContactPoint& operator[](int i) const { return points_[i]; }

    /// Moves the deepest kMaxContactPoints into `out` (world frame), appending to what it holds.
    void emit(const Pose& frame, ContactManifold& out) {
        std::sort(points_, points_ + count_,
                  [](const ContactPoint& a, const ContactPoint& b) { return a.depth > b.depth; });
        for (int i = 0; i < count_ && !out.full(); ++i) {
            ContactPoint p = points_[i];
            p.point0 = frame.apply(p.point0);
            p.point1 = frame.apply(p.point1);
            p.normal = frame.rotation * p.normal;
            out.add(p);
        }
    }

  private:
    static constexpr int kCapacity = 32;
    static constexpr double kSameNormalCosine = 0.999;
    static_assert(std::is_trivially_destructible_v<ContactPoint>);
    // Raw storage: default-constructing 32 points per pair test would cost more than the test.
    alignas(ContactPoint) std::byte storage_[kCapacity * sizeof(ContactPoint)];
    ContactPoint* points_ = reinterpret_cast<ContactPoint*>(storage_);
    int count_ = 0;
    double mergeDistance2_;
};

}  // namespace substep
