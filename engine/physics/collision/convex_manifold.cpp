#include "physics/collision/convex_manifold.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace substep {

namespace {

/// A 16-gon clipped by 16 side planes has at most 32 vertices.
constexpr int kMaxClipVertices = 2 * kMaxFeatureVertices;

struct ClipPolygon {
    std::array<Vec3, kMaxClipVertices> v;
    int count = 0;
};

/// Sutherland–Hodgman: keeps the part of polygon `in` with m·(p − origin) >= 0.
void clipPolygon(const ClipPolygon& in, const Vec3& m, const Vec3& origin, ClipPolygon& out) {
    out.count = 0;
    for (int i = 0; i < in.count; ++i) {
        const Vec3& a = in.v[i];
        const Vec3& b = in.v[(i + 1) % in.count];
        const double da = m.dot(a - origin);
        const double db = m.dot(b - origin);
        if (da >= 0.0 && out.count < kMaxClipVertices) out.v[out.count++] = a;
        if ((da >= 0.0) != (db >= 0.0) && out.count < kMaxClipVertices) {
            out.v[out.count++] = a + (da / (da - db)) * (b - a);
        }
    }
}

/// Keeps the part of segment [p0, p1] with m·(p − origin) >= 0 as parameters [t0, t1].
void clipSegment(const Vec3& p0, const Vec3& p1, const Vec3& m, const Vec3& origin, double& t0,
                 double& t1) {
    const double d0 = m.dot(p0 - origin);
    const double d1 = m.dot(p1 - origin);
    if (d0 < 0.0 && d1 < 0.0) {
        t0 = 1.0, t1 = 0.0;  // empty
        return;
    }
    if (d0 < 0.0) t0 = std::max(t0, d0 / (d0 - d1));
    if (d1 < 0.0) t1 = std::min(t1, d0 / (d0 - d1));
}

/// The incident feature clipped to the prism swept by the reference polygon along the contact
/// normal n, into `clipped`: every point kept lies over the reference polygon along n, so its
/// partner on the reference plane is a point of the reference face.
void clipToReference(const SupportFeature& reference, const SupportFeature& incident,
                     const Vec3& n, ClipPolygon& clipped) {
    Vec3 centroid = Vec3::Zero();
    for (int i = 0; i < reference.count; ++i)
        centroid += reference.vertices[i];
    centroid /= reference.count;
    // Inward side-plane normals of the reference polygon's edges.
    std::array<Vec3, kMaxFeatureVertices> inward;
    for (int i = 0; i < reference.count; ++i) {
        const Vec3& r0 = reference.vertices[i];
        const Vec3& r1 = reference.vertices[(i + 1) % reference.count];
        Vec3 m = (r1 - r0).cross(n);
        if (m.dot(centroid - r0) < 0.0) m = -m;
        inward[i] = m;
    }
    clipped.count = 0;
    if (incident.count == 1) {
        const Vec3& p = incident.vertices[0];
        for (int i = 0; i < reference.count; ++i) {
            if (inward[i].dot(p - reference.vertices[i]) < 0.0) return;
        }
        clipped.v[clipped.count++] = p;
        return;
    }
    if (incident.count == 2) {
        const Vec3& p0 = incident.vertices[0];
        const Vec3& p1 = incident.vertices[1];
        double t0 = 0.0, t1 = 1.0;
        for (int i = 0; i < reference.count && t0 <= t1; ++i)
            clipSegment(p0, p1, inward[i], reference.vertices[i], t0, t1);
        if (t0 > t1) return;
        clipped.v[clipped.count++] = p0 + t0 * (p1 - p0);
        if (t1 > t0) clipped.v[clipped.count++] = p0 + t1 * (p1 - p0);
        return;
    }
    ClipPolygon buffers[2];
    int current = 0;
    buffers[0].count = incident.count;
    for (int i = 0; i < incident.count; ++i)
        buffers[0].v[i] = incident.vertices[i];
    for (int i = 0; i < reference.count && buffers[current].count > 0; ++i) {
        clipPolygon(buffers[current], inward[i], reference.vertices[i], buffers[1 - current]);
        current = 1 - current;
    }
    clipped = buffers[current];
}

}  // namespace

void appendSpanningPoints(const ContactPoint* c, int n, ContactManifold& out) {
    if (n <= kGeneralContactPoints) {
        for (int i = 0; i < n; ++i)
            out.add(c[i]);
        return;
    }
    int i0 = 0;
    for (int i = 1; i < n; ++i) {
        if (c[i].depth > c[i0].depth) i0 = i;
    }
    const auto at = [&](int i) -> const Vec3& { return c[i].point1; };
    int i1 = i0 == 0 ? 1 : 0;
    for (int i = 0; i < n; ++i) {
        if ((at(i) - at(i0)).squaredNorm() > (at(i1) - at(i0)).squaredNorm()) i1 = i;
    }
    const Vec3& normal = c[i0].normal;
    int i2 = -1;
    double best = -1.0;
    for (int i = 0; i < n; ++i) {
        if (i == i0 || i == i1) continue;
        const double area = std::abs((at(i1) - at(i0)).cross(at(i) - at(i0)).dot(normal));
        if (area > best) best = area, i2 = i;
    }
    const int triangle[3] = {i0, i1, i2};
    // The triangle's orientation about the normal, so "outside an edge" has one sign.
    const double orientation = (at(i1) - at(i0)).cross(at(i2) - at(i0)).dot(normal) < 0.0 ? -1.0
                                                                                         : 1.0;
    int i3 = -1;
    best = 0.0;
    for (int i = 0; i < n; ++i) {
        if (i == i0 || i == i1 || i == i2) continue;
        double added = 0.0;
        for (int e = 0; e < 3; ++e) {
            const Vec3& u = at(triangle[e]);
            const Vec3& v = at(triangle[(e + 1) % 3]);
            added = std::max(added, -orientation * (v - u).cross(at(i) - u).dot(normal));
        }
        if (added > best) best = added, i3 = i;
    }
    for (int i : triangle)
        out.add(c[i]);
    if (i3 >= 0) out.add(c[i3]);
}

namespace {

/// Whether the two 2-point features run side by side (within kParallelEdgeSine).
bool sideBySide(const SupportFeature& fa, const SupportFeature& fb) {
    if (fa.count != 2 || fb.count != 2) return false;
    const Vec3 da = fa.vertices[1] - fa.vertices[0];
    const Vec3 db = fb.vertices[1] - fb.vertices[0];
    const double la = da.norm(), lb = db.norm();
    if (!(la > 0.0) || !(lb > 0.0)) return false;
    return da.cross(db).norm() <= kParallelEdgeSine * la * lb;
}

}  // namespace

void buildConvexManifold(const ConvexSupport& a, const ConvexSupport& b,
                         const ConvexDistance& deepest, double margin, uint32_t featureBase,
                         ContactManifold& out) {
    const Vec3& n = deepest.normal;
    const double ra = a.radius, rb = b.radius;
    const double deepestDepth = ra + rb - deepest.separation;
    if (!(deepestDepth >= -margin)) return;

    SupportFeature fa, fb;
    a.feature(-n, fa);
    b.feature(n, fb);

    std::array<ContactPoint, kMaxClipVertices + 1> candidates;
    int count = 0;
    const auto addCandidate = [&](const Vec3& onA, const Vec3& onB, uint32_t index) {
        ContactPoint p;
        p.normal = n;
        p.point0 = onA - ra * n;
        p.point1 = onB + rb * n;
        p.depth = (p.point1 - p.point0).dot(n);
        if (!(p.depth >= -margin)) return;
        p.feature = featureBase + ((fa.id & 0xffu) << 16) + ((fb.id & 0xffu) << 8) + index;
        candidates[count++] = p;
    };

    const bool faceB = fb.count >= 3 && fb.alignment >= kReferenceCosine;
    const bool faceA = fa.count >= 3 && fa.alignment >= kReferenceCosine;
    if (faceA || faceB) {
        const bool referenceIsB = faceB && (!faceA || fb.alignment >= fa.alignment - 1e-9);
        const SupportFeature& reference = referenceIsB ? fb : fa;
        const SupportFeature& incident = referenceIsB ? fa : fb;
        ClipPolygon clipped;
        clipToReference(reference, incident, n, clipped);
        const Vec3& nf = reference.normal;
        const double along = n.dot(nf);  // near ±1 for a reference face
        for (int k = 0; k < clipped.count; ++k) {
            const Vec3& p = clipped.v[k];
            // From the incident point along the normal to the reference face's plane.
            const Vec3 q = p + ((reference.vertices[0] - p).dot(nf) / along) * n;
            if (referenceIsB) addCandidate(p, q, static_cast<uint32_t>(k));
            else addCandidate(q, p, static_cast<uint32_t>(k));
        }
    } else if (sideBySide(fa, fb)) {
        // Two lines side by side (capsules, cylinders on their sides): A's line clipped to the
        // stretch beside B's, each end measured against B's line.
        const Vec3& b0 = fb.vertices[0];
        const Vec3 db = fb.vertices[1] - b0;
        const double lb2 = db.squaredNorm();
        const Vec3& p0 = fa.vertices[0];
        const Vec3& p1 = fa.vertices[1];
        double t0 = 0.0, t1 = 1.0;
        clipSegment(p0, p1, db, b0, t0, t1);
        clipSegment(p0, p1, -db, fb.vertices[1], t0, t1);
        for (int k = 0; k < 2 && t0 <= t1; ++k) {
            const Vec3 p = p0 + (k == 0 ? t0 : t1) * (p1 - p0);
            const double s = std::clamp((p - b0).dot(db) / lb2, 0.0, 1.0);
            const Vec3 q = b0 + s * db;
            // The gap between the lines measured along the normal (they are parallel to it).
            addCandidate(p, p + (q - p).dot(n) * n, static_cast<uint32_t>(k));
            if (t1 <= t0) break;
        }
    }

    // The deepest pair itself when clipping found nothing as deep (a rim point of a curved
    // feature, a vertex over an edge, two crossing lines).
    double deepestCandidate = -margin - 1.0;
    for (int k = 0; k < count; ++k)
        deepestCandidate = std::max(deepestCandidate, candidates[k].depth);
    const double scale = a.size() + b.size();
    if (count == 0 || deepestCandidate < deepestDepth - 1e-6 * scale) {
        addCandidate(deepest.pointA, deepest.pointB, 0xffu);
    }
    appendSpanningPoints(candidates.data(), count, out);
}

void collideConvexSupports(const ConvexSupport& a, const ConvexSupport& b, double margin,
                           ContactManifold& out) {
    const ConvexDistance deepest = convexDistance(a, b, margin + a.radius + b.radius);
    if (deepest.beyondCutoff) return;
    buildConvexManifold(a, b, deepest, margin, 0, out);
}

void collideGeneralConvex(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                          double margin, ContactManifold& out) {
    ConvexSupport sa, sb;
    const Pose world;
    if (!makeConvexSupport(a, pa, world, sa) || !makeConvexSupport(b, pb, world, sb)) return;
    collideConvexSupports(sa, sb, margin, out);
}

}  // namespace substep
