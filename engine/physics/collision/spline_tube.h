#pragma once
/// A tube of constant radius around a cubic Hermite spline through control points, with
/// Catmull–Rom tangents: the wires and rails of the rolling ball sculpture and the two-wire
/// track of Fig. 13. Solid tubes are rails a marble rides on; hollow ones are pipes it runs inside.

#include "physics/collision/aabb.h"
#include "physics/collision/cubic_segment.h"
#include "physics/collision/shape.h"
#include "physics/collision/static_bvh.h"
#include "physics/math.h"

#include <memory>
#include <vector>

namespace substep {

/// The closest point of a spline to a query, as found on one of its segments.
struct SplinePoint {
    int segment = -1;  ///< -1: nothing within the search distance
    double t = 0.0;    ///< parameter on the segment, [0, 1]
    Vec3 point = Vec3::Zero();
    double distanceSquared = 0.0;
};

struct SplineTube {
    std::vector<Vec3> points;  ///< control points (consecutive duplicates removed)
    double radius = 0.0;
    bool closed = false;  ///< the curve returns from the last point to the first
    bool hollow = false;  ///< a pipe: contacts keep the body inside
    std::vector<CubicSegment> segments;
    std::vector<Aabb> segmentBounds;  ///< bounds of each curve piece (without the radius)
    StaticBvh tree;                   ///< over segmentBounds

    /// Calls visit(int segment) for every segment whose curve may come within `range` of q.
    template <class Visitor>
    void forSegmentsNear(const Vec3& q, double range, Visitor&& visit) const {
        const Aabb box{q.array() - range, q.array() + range};
        tree.query(box, visit);
    }

    /// The closest point on the curve within `range` of q (segment -1 if there is none).
    SplinePoint closestPoint(const Vec3& q, double range) const;

    /// Whether parameter t of `segment` is the start or the end of an open curve.
    bool isCurveStart(int segment, double t) const { return !closed && segment == 0 && t <= 0.0; }
    bool isCurveEnd(int segment, double t) const {
        return !closed && segment + 1 == static_cast<int>(segments.size()) && t >= 1.0;
    }
};

/// Builds the tube: Catmull–Rom tangents m_i = (p_{i+1} − p_{i−1})/2, one-sided at the ends of
/// an open curve, wrapped round for a closed one. Consecutive equal points are merged (a closed
/// curve's repeated first point too); a single remaining point gives a sphere. Throws
/// std::invalid_argument for no points or a radius that is not positive and finite.
std::shared_ptr<const SplineTube> makeSplineTube(std::vector<Vec3> points, double radius,
                                                 bool closed, bool hollow = false);

/// A spline shape with its local bounds (the curve's bounds grown by the radius).
Shape splineShape(std::shared_ptr<const SplineTube> tube);

}  // namespace substep
