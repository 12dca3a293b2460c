#include "physics/collision/spline_tube.h"

#include <stdexcept>

namespace substep {

std::shared_ptr<const SplineTube> makeSplineTube(std::vector<Vec3> points, double radius,
                                                 bool closed, bool hollow) {
    if (points.empty()) throw std::invalid_argument("makeSplineTube: no control points");
    if (!(radius > 0.0) || !std::isfinite(radius)) {
        throw std::invalid_argument("makeSplineTube: radius must be positive and finite");
    }
    for (const Vec3& p : points) {
        if (!p.allFinite()) throw std::invalid_argument("makeSplineTube: non-finite point");
    }
    // Repeated points would make zero-length segments with turning tangents: merge them.
    std::vector<Vec3> unique;
    unique.reserve(points.size());
    for (const Vec3& p : points) {
        if (unique.empty() || unique.back() != p) unique.push_back(p);
    }
    if (closed && unique.size() > 1 && unique.front() == unique.back()) unique.pop_back();

    auto tube = std::make_shared<SplineTube>();
    tube->radius = radius;
    tube->hollow = hollow;
    tube->closed = closed && unique.size() >= 3;
    tube->points = std::move(unique);
    const std::vector<Vec3>& p = tube->points;
    const int n = static_cast<int>(p.size());

    if (n == 1) {
        tube->segments.push_back({.c0 = p[0]});
    } else {
        std::vector<Vec3> tangents(n);
        for (int i = 0; i < n; ++i) {
            if (tube->closed) {
                tangents[i] = 0.5 * (p[(i + 1) % n] - p[(i + n - 1) % n]);
            } else if (i == 0) {
                tangents[i] = p[1] - p[0];
            } else if (i == n - 1) {
                tangents[i] = p[n - 1] - p[n - 2];
            } else {
                tangents[i] = 0.5 * (p[i + 1] - p[i - 1]);
            }
        }
        const int count = tube->closed ? n : n - 1;
        for (int i = 0; i < count; ++i) {
            const int j = (i + 1) % n;
            tube->segments.push_back(CubicSegment::hermite(p[i], tangents[i], p[j], tangents[j]));
        }
    }
    for (const CubicSegment& segment : tube->segments) {
        tube->segmentBounds.push_back(segment.bounds());
    }
    tube->tree.build(tube->segmentBounds);
    return tube;
}

SplinePoint SplineTube::closestPoint(const Vec3& q, double range) const {
    SplinePoint best;
    double bestDistance2 = range * range;
    forSegmentsNear(q, range, [&](int i) {
        // The box's distance bounds the curve's from below: skip pieces that cannot win.
        const Vec3 outside =
            (segmentBounds[i].min - q).cwiseMax(q - segmentBounds[i].max).cwiseMax(0.0);
        if (outside.squaredNorm() > bestDistance2) return;
        const SegmentClosest c = closestOnCubic(segments[i], q);
        if (c.distanceSquared <= bestDistance2) {
            bestDistance2 = c.distanceSquared;
            best = {.segment = i,
                    .t = c.t,
                    .point = segments[i].point(c.t),
                    .distanceSquared = c.distanceSquared};
        }
    });
    return best;
}

Shape splineShape(std::shared_ptr<const SplineTube> tube) {
    Shape shape{.type = ShapeType::Spline};
    Aabb bounds = tube->tree.bounds();
    shape.localBounds = bounds.inflated(tube->radius);
    shape.spline = std::move(tube);
    return shape;
}

}  // namespace substep
