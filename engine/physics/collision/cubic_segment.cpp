#include "physics/collision/cubic_segment.h"

#include <algorithm>
#include <cmath>

namespace substep {

namespace {

/// Coarse scan resolution: Catmull–Rom pieces turn by well under a half circle, so 8 intervals
/// put the global minimum's basin next to the best sample.
constexpr int kScanIntervals = 8;
constexpr int kMaxNewtonSteps = 16;
constexpr double kParameterTolerance = 1e-12;

/// Minimises f(t) on [0, 1] given f(t) (`distance2`) and f'/2, f''/2 (`slopes`).
template <class Distance2, class Slopes>
SegmentClosest minimise(Distance2&& distance2, Slopes&& slopes) {
    // Scan for the basin of the global minimum.
    int best = 0;
    double bestF = distance2(0.0);
    for (int k = 1; k <= kScanIntervals; ++k) {
        const double f = distance2(static_cast<double>(k) / kScanIntervals);
        if (f < bestF) {
            bestF = f;
            best = k;
        }
    }
    const double step = 1.0 / kScanIntervals;
    double lo = std::max(0.0, (best - 1) * step);
    double hi = std::min(1.0, (best + 1) * step);
    double t = best * step;

    // Newton on f' = 0 inside [lo, hi]; the sign of f' tells which side the minimum is on.
    for (int i = 0; i < kMaxNewtonSteps; ++i) {
        double g, h;
        slopes(t, g, h);
        if (g > 0.0) {
            hi = t;
        } else if (g < 0.0) {
            lo = t;
        } else {
            break;
        }
        if (h > 0.0 && std::abs(g) < kParameterTolerance * h) break;  // Newton step below tolerance
        double next = h > 0.0 ? t - g / h : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // also catches NaN
        t = next;
        if (hi - lo < kParameterTolerance) break;
    }
    const double f = distance2(t);
    if (f <= bestF) return {.t = t, .distanceSquared = f};
    return {.t = best * step, .distanceSquared = bestF};
}

}  // namespace

CubicSegment CubicSegment::hermite(const Vec3& p0, const Vec3& m0, const Vec3& p1, const Vec3& m1) {
    return {
        .c0 = p0, .c1 = m0, .c2 = 3.0 * (p1 - p0) - 2.0 * m0 - m1, .c3 = 2.0 * (p0 - p1) + m0 + m1};
}

Aabb CubicSegment::bounds() const {
    // Bézier control points of the same cubic: b0 = p(0), b1 = b0 + c1/3, b2 = b1 + (c1 + c2)/3,
    // b3 = p(1); the curve lies in their convex hull.
    Aabb box;
    const Vec3 b1 = c0 + c1 / 3.0;
    const Vec3 b2 = b1 + (c1 + c2) / 3.0;
    box.grow(c0);
    box.grow(b1);
    box.grow(b2);
    box.grow(point(1.0));
    return box;
}

SegmentClosest closestOnCubic(const CubicSegment& curve, const Vec3& q) {
    const auto distance2 = [&](double t) { return (curve.point(t) - q).squaredNorm(); };
    // f = |r|², r = p(t) - q: f'/2 = r·p', f''/2 = p'·p' + r·p''.
    const auto slopes = [&](double t, double& g, double& h) {
        const Vec3 r = curve.point(t) - q;
        const Vec3 d1 = curve.tangent(t);
        g = r.dot(d1);
        h = d1.squaredNorm() + r.dot(curve.secondDerivative(t));
    };
    return minimise(distance2, slopes);
}

// f''/2 = |p'|² + r·p'' with r = p − q is positive where |p'|² > |r| |p''|. Around the middle
// m = p(1/2): p'' is linear in t, so |p''| ≤ A = max(|p''(0)|, |p''(1)|); |p'(t) − p'(½)| ≤ A/2,
// so |p'| ≥ s − A/2 with s = |p'(½)|; and |p(t) − m| ≤ (s + A/2)/2, so |r| ≤ |m − q| + (s + A/2)/2.
bool distanceIsConvex(const CubicSegment& curve, const Vec3& q) {
    const double accel =
        std::sqrt(std::max(curve.secondDerivative(0.0).squaredNorm(), curve.secondDerivative(1.0).squaredNorm()));
    const double speed = curve.tangent(0.5).norm();
    const double slowest = speed - 0.5 * accel;
    if (!(slowest > 0.0)) return false;
    const double farthest = (curve.point(0.5) - q).norm() + 0.5 * (speed + 0.5 * accel);
    return slowest * slowest > farthest * accel;
}

double chordParameter(const CubicSegment& curve, const Vec3& q) {
    const Vec3 chord = curve.point(1.0) - curve.c0;
    const double length2 = chord.squaredNorm();
    if (!(length2 > 0.0)) return 0.0;
    return std::clamp((q - curve.c0).dot(chord) / length2, 0.0, 1.0);
}

SegmentClosest closestOnCubicFrom(const CubicSegment& curve, const Vec3& q, double guess) {
    if (!distanceIsConvex(curve, q) || !std::isfinite(guess)) return closestOnCubic(curve, q);
    // One minimum on [0, 1]: Newton on f' = 0 inside a bracket that the sign of f' shrinks,
    // stepping onto an end of the segment when the step leaves it there (a minimum at the end).
    double lo = 0.0, hi = 1.0;
    double t = std::clamp(guess, 0.0, 1.0);
    for (int i = 0; i < kMaxNewtonSteps; ++i) {
        const Vec3 r = curve.point(t) - q;
        const Vec3 d1 = curve.tangent(t);
        const double g = r.dot(d1);
        const double h = d1.squaredNorm() + r.dot(curve.secondDerivative(t));  // > 0: convex
        if (g > 0.0) {
            if (t == 0.0) break;  // rising from the start: the minimum is there
            hi = t;
        } else if (g < 0.0) {
            if (t == 1.0) break;
            lo = t;
        } else {
            break;
        }
        if (std::abs(g) < kParameterTolerance * h) break;
        double next = t - g / h;
        if (next <= 0.0 && lo == 0.0) next = 0.0;
        else if (next >= 1.0 && hi == 1.0) next = 1.0;
        else if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        t = next;
        if (hi - lo < kParameterTolerance) break;
    }
    return {.t = t, .distanceSquared = (curve.point(t) - q).squaredNorm()};
}

SegmentClosest closestOnCubicToSegment(const CubicSegment& curve, const Vec3& a, const Vec3& b) {
    const Vec3 u = b - a;
    const double uu = u.squaredNorm();
    const double invUu = uu > kDirectionEpsilon * kDirectionEpsilon ? 1.0 / uu : 0.0;
    const auto parameterOn = [&](const Vec3& p) {
        return std::clamp((p - a).dot(u) * invUu, 0.0, 1.0);
    };
    const auto distance2 = [&](double t) {
        const Vec3 p = curve.point(t);
        return (p - (a + parameterOn(p) * u)).squaredNorm();
    };
    // f = |r|² with r = p(t) - x(s(t)); by the envelope theorem f'/2 = r·p' whether s is free or
    // clamped, and f''/2 = p'·(I - uuᵀ/|u|²)p' + r·p'' while s is free (p'·p' + r·p'' clamped).
    const auto slopes = [&](double t, double& g, double& h) {
        const Vec3 p = curve.point(t);
        const double sRaw = (p - a).dot(u) * invUu;
        const double s = std::clamp(sRaw, 0.0, 1.0);
        const Vec3 r = p - (a + s * u);
        const Vec3 d1 = curve.tangent(t);
        g = r.dot(d1);
        h = d1.squaredNorm() + r.dot(curve.secondDerivative(t));
        if (sRaw > 0.0 && sRaw < 1.0) h -= d1.dot(u) * d1.dot(u) * invUu;
    };
    SegmentClosest result = minimise(distance2, slopes);
    result.s = parameterOn(curve.point(result.t));
    return result;
}

}  // namespace substep
