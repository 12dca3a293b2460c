/// Convex shapes against spline tubes (collide_general.h). A solid tube of radius R is, near
/// any curve point x, the ball of radius R around x; the shape meets the tube where it meets
/// one of those balls. The balls tried are the curve's samples inside the shape's reach and
/// the curve point nearest the shape (alternating closest points: the shape's core point
/// nearest x, then the curve point nearest that, cubic_segment.h). The contacts are reduced to
/// the 4 spanning the stretch of rail under the shape.

#include "physics/collision/collide_general.h"
#include "physics/collision/convex_manifold.h"
#include "physics/collision/spline_tube.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace substep {

namespace {

/// Samples along the curve are spaced at most this fraction of the shape's size apart.
constexpr double kSampleFraction = 0.2;
/// At most this many samples per segment (a long straight segment under a small shape is
/// culled sample by sample before any pair test).
constexpr int kMaxSamplesPerSegment = 512;
/// Rounds of the alternating closest-point search.
constexpr int kClosestRounds = 4;
/// Directions across the curve tried for a shape in a pipe (plus the one towards its centre).
constexpr int kPipeDirections = 8;
/// Candidates kept before the reduction to the spanning four.
constexpr int kMaxCandidates = 64;

struct Candidates {
    std::array<ContactPoint, kMaxCandidates> points;
    int count = 0;

    void add(const ContactPoint& p) {
        if (count < kMaxCandidates) {
            points[count++] = p;
            return;
        }
        // Full: the shallowest gives way.
        int shallowest = 0;
        for (int i = 1; i < count; ++i) {
            if (points[i].depth < points[shallowest].depth) shallowest = i;
        }
        if (p.depth > points[shallowest].depth) points[shallowest] = p;
    }
};

Aabb supportBounds(const ConvexSupport& s) {
    Aabb box;
    for (int k = 0; k < 3; ++k) {
        box.grow(s.support(Vec3::Unit(k)));
        box.grow(s.support(-Vec3::Unit(k)));
    }
    return box.inflated(s.radius);
}

/// The ball of the tube's radius around curve point x.
ConvexSupport ballAt(const Vec3& x, double radius) {
    ConvexSupport ball;
    ball.kind = CoreKind::Point;
    ball.centre = x;
    ball.radius = radius;
    return ball;
}

/// The contacts of the shape with the ball of radius R at x, into `candidates`.
void addBallContacts(const ConvexSupport& s, const Vec3& x, double R, double margin,
                     uint32_t feature, Candidates& candidates) {
    ContactManifold points;
    collideConvexSupports(s, ballAt(x, R), margin, points);
    for (int k = 0; k < points.count; ++k) {
        points.points[k].feature = feature;
        candidates.add(points.points[k]);
    }
}

/// A pipe: the shape's farthest reach across the tangent at curve point x, pushed back inside
/// when it passes the wall.
void addPipeContact(const ConvexSupport& s, const Vec3& x, const Vec3& tangent, double R,
                    double slab, double margin, uint32_t feature, Candidates& candidates) {
    const double length = tangent.norm();
    if (!(length > kDirectionEpsilon)) return;
    const Vec3 t = tangent / length;
    const Vec3 e = anyPerpendicular(t);
    const Vec3 f = t.cross(e);
    ContactPoint best;
    best.depth = -margin - 1.0;
    const auto tryDirection = [&](const Vec3& u) {
        const Vec3 p = s.support(u) + s.radius * u;
        const double depth = (p - x).dot(u) - R;
        if (depth > best.depth) {
            best.depth = depth;
            best.normal = -u;
            best.point0 = p;
            best.point1 = p - depth * u;  // on the wall: (point1 − point0)·normal = depth
        }
    };
    Vec3 towards = s.centre - x;
    towards -= towards.dot(t) * t;
    if (towards.norm() > kDirectionEpsilon) tryDirection(towards.normalized());
    for (int k = 0; k < kPipeDirections; ++k) {
        const double angle = 2.0 * M_PI * k / kPipeDirections;
        tryDirection(std::cos(angle) * e + std::sin(angle) * f);
    }
    // The farthest point across the curve is extreme in its own direction: turn u towards the
    // best point found until it stays (a corner of a box in a round pipe).
    for (int round = 0; round < kClosestRounds; ++round) {
        Vec3 across = best.point0 - x;
        across -= across.dot(t) * t;
        const double acrossLength = across.norm();
        if (!(acrossLength > kDirectionEpsilon)) break;
        const Vec3 before = best.point0;
        tryDirection(across / acrossLength);
        if ((best.point0 - before).squaredNorm() == 0.0) break;
    }
    if (best.depth < -margin) return;
    // The sample whose slab across the curve holds the point reports it (so a shape reaching
    // past an open end, or along a bend, is measured where it actually is).
    if (std::abs((best.point0 - x).dot(t)) > slab) return;
    best.feature = feature;
    candidates.add(best);
}

/// The curve parameter of `segment` nearest the shape, by alternating closest points.
double closestParameter(const ConvexSupport& s, const CubicSegment& segment) {
    double t = closestOnCubic(segment, s.centre).t;
    for (int round = 0; round < kClosestRounds; ++round) {
        const ConvexSupport point = ballAt(segment.point(t), 0.0);
        const ConvexDistance d = convexDistance(s, point, std::numeric_limits<double>::infinity());
        const double next = closestOnCubic(segment, d.pointA).t;
        if (std::abs(next - t) < 1e-9) break;
        t = next;
    }
    return t;
}

}  // namespace

void collideConvexSpline(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                         double margin, ContactManifold& out) {
    out.clear();
    if (!b.spline) return;
    const SplineTube& tube = *b.spline;
    ConvexSupport s;
    if (!makeConvexSupport(a, pa, pb, s)) return;
    const double R = tube.radius;
    const Aabb shapeBox = supportBounds(s).inflated(margin);
    // Curve points whose ball may touch the shape (solid), or that the shape may lie beside.
    const Aabb reach = shapeBox.inflated(R);
    const double spacing = kSampleFraction * (s.size() + s.radius);

    Candidates candidates;
    tube.tree.query(reach, [&](int i) {
        const CubicSegment& segment = tube.segments[i];
        const Aabb& bounds = tube.segmentBounds[i];
        const double chord = bounds.extents().norm();
        const int samples =
            std::clamp(static_cast<int>(std::ceil(chord / spacing)), 1, kMaxSamplesPerSegment);
        const uint32_t base = static_cast<uint32_t>(i) << 12;
        // Half the distance between samples, with overlap (a point reported twice is merged
        // by the reduction; one reported by none would be missed).
        const double slab = 0.75 * chord / samples;
        for (int k = 0; k <= samples; ++k) {
            const double t = static_cast<double>(k) / samples;
            const Vec3 x = segment.point(t);
            if ((x.array() < reach.min.array()).any() || (x.array() > reach.max.array()).any()) {
                continue;
            }
            if (tube.hollow) {
                // Past an open end the pipe is gone: a shape whose centre is beyond it leaves.
                const Vec3 tangent = segment.tangent(t);
                if ((tube.isCurveStart(i, t) && (s.centre - x).dot(tangent) < 0.0) ||
                    (tube.isCurveEnd(i, t) && (s.centre - x).dot(tangent) > 0.0)) {
                    continue;
                }
                addPipeContact(s, x, tangent, R, slab, margin, base + k, candidates);
            } else {
                addBallContacts(s, x, R, margin, base + k, candidates);
            }
        }
        if (!tube.hollow) {
            const double t = closestParameter(s, segment);
            addBallContacts(s, segment.point(t), R, margin, base + 0xfff, candidates);
        }
    });

    ContactManifold local;
    appendSpanningPoints(candidates.points.data(), candidates.count, local);
    for (int k = 0; k < local.count; ++k) {
        ContactPoint p = local.points[k];
        p.point0 = pb.apply(p.point0);
        p.point1 = pb.apply(p.point1);
        p.normal = pb.rotation * p.normal;
        out.add(p);
    }
}

}  // namespace substep
