#pragma once
/// One cubic piece of a Hermite spline and the closest-point searches on it. The paper names
/// "finding the closest point on a Hermite spline segment" the most expensive part of the rolling
/// ball sculpture, so these run without allocation: a coarse scan for the right basin, then
/// Newton's method kept inside a shrinking bracket (bisection when a step would leave it); or,
/// where a bound proves the distance has one minimum on the piece, Newton from a guess alone.

#include "physics/collision/aabb.h"
#include "physics/math.h"

namespace substep {

/// p(t) = c0 + t (c1 + t (c2 + t c3)) for t in [0, 1], the power form of a Hermite segment.
struct CubicSegment {
    Vec3 c0 = Vec3::Zero();
    Vec3 c1 = Vec3::Zero();
    Vec3 c2 = Vec3::Zero();
    Vec3 c3 = Vec3::Zero();

    /// The Hermite segment from p0 (tangent m0) to p1 (tangent m1).
    static CubicSegment hermite(const Vec3& p0, const Vec3& m0, const Vec3& p1, const Vec3& m1);

    Vec3 point(double t) const { return c0 + t * (c1 + t * (c2 + t * c3)); }
    Vec3 tangent(double t) const { return c1 + t * (2.0 * c2 + t * (3.0 * c3)); }
    Vec3 secondDerivative(double t) const { return 2.0 * c2 + (6.0 * t) * c3; }
    /// Bounds of the curve piece (the box of its Bézier control polygon, which holds the curve).
    Aabb bounds() const;
};

/// Where a search ended on a segment: the curve parameter t and the squared distance reached.
struct SegmentClosest {
    double t = 0.0;
    double distanceSquared = 0.0;
    double s = 0.0;  ///< for segment queries: parameter on the line segment [a, b] (0 at a)
};

/// The point of the cubic closest to q (global over t in [0, 1] up to the scan's resolution,
/// which separates minima further apart than 1/8 of the parameter range).
SegmentClosest closestOnCubic(const CubicSegment& curve, const Vec3& q);

/// The same closest point, searched by Newton steps from the parameter `guess` (the one found
/// for the same body a substep earlier, or the projection onto the chord) instead of a scan.
/// Used only where a bound proves the squared distance convex over the whole segment, so that
/// its one minimum is the global one (|p'|² > |p − q| |p''| everywhere: the query is well
/// inside the radius of curvature and the piece is short, as a marble on a wire is); elsewhere
/// it is closestOnCubic.
SegmentClosest closestOnCubicFrom(const CubicSegment& curve, const Vec3& q, double guess);

/// Whether a bound proves |p(t) − q|² convex on [0, 1] (so it has one minimum there): the test
/// closestOnCubicFrom makes before trusting Newton from its guess.
bool distanceIsConvex(const CubicSegment& curve, const Vec3& q);

/// The projection of q onto the chord from p(0) to p(1), as a parameter in [0, 1]: a guess for
/// closestOnCubicFrom that is close on the short, gently bent pieces of a spline.
double chordParameter(const CubicSegment& curve, const Vec3& q);

/// The closest pair between the cubic and the line segment [a, b] (a capsule's axis).
SegmentClosest closestOnCubicToSegment(const CubicSegment& curve, const Vec3& a, const Vec3& b);

}  // namespace substep
