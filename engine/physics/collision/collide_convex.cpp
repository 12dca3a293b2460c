#include "physics/collision/collide_convex.h"

#include "physics/collision/primitive_geometry.h"

#include "physics/collision/convex_hull.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace substep {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// A face axis wins over an edge axis (and hull a's face over hull b's) unless the other is
/// better by this fraction of the separation plus kAxisBiasSize of the hulls' size: face
/// contacts give whole manifolds, and keeping the same axis frame to frame keeps them steady.
constexpr double kAxisBiasRelative = 0.05;
constexpr double kAxisBiasSize = 1e-3;

/// Edge pairs closer to parallel than this sine have no cross-product axis of their own.
constexpr double kParallelSine = 1e-6;

/// A capsule within this cosine of lying along a face touches it along a clipped segment.
constexpr double kCapsuleAlongFace = 0.1;

/// The golden-section search along a capsule's segment stops when its bracket is shorter than
/// this fraction of the larger of the segment's length and the hull's size.
constexpr double kSegmentSearchTolerance = 1e-11;

// Scratch buffers reused across calls so that the narrowphase does not allocate.
thread_local std::vector<ContactPoint> tCandidates;

/// Appends the candidates, reduced to the four that span the largest area (the deepest, the
/// one farthest from it, the one making the largest triangle, the one adding most to it).
void appendReduced(const std::vector<ContactPoint>& c, ContactManifold& out) {
    const int n = static_cast<int>(c.size());
    if (n <= 4) {
        for (const ContactPoint& p : c)
            out.add(p);
        return;
    }
    const auto at = [&](int i) { return 0.5 * (c[i].point0 + c[i].point1); };
    int i0 = 0;
    for (int i = 1; i < n; ++i) {
        if (c[i].depth > c[i0].depth) i0 = i;
    }
    int i1 = i0 == 0 ? 1 : 0;
    for (int i = 0; i < n; ++i) {
        if ((at(i) - at(i0)).squaredNorm() > (at(i1) - at(i0)).squaredNorm()) i1 = i;
    }
    const Vec3 normal = c[i0].normal;
    int i2 = -1;
    double best = -1.0;
    for (int i = 0; i < n; ++i) {
        const double area = std::abs((at(i1) - at(i0)).cross(at(i) - at(i0)).dot(normal));
        if (i != i0 && i != i1 && area > best) best = area, i2 = i;
    }
    const std::array<int, 3> tri = {i0, i1, i2};
    const Vec3 triNormal = (at(i1) - at(i0)).cross(at(i2) - at(i0));
    int i3 = -1;
    best = 0.0;
    for (int i = 0; i < n; ++i) {
        if (i == i0 || i == i1 || i == i2) continue;
        // Area added by i: the most it lies outside one of the triangle's edges.
        double added = 0.0;
        for (int e = 0; e < 3; ++e) {
            const Vec3 u = at(tri[e]), v = at(tri[(e + 1) % 3]);
            added = std::max(added, -(v - u).cross(at(i) - u).dot(triNormal));
        }
        if (added > best) best = added, i3 = i;
    }
    for (int i : tri)
        out.add(c[i]);
    if (i3 >= 0) out.add(c[i3]);
}

/// The hull of a mesh shape, or null when it has none or it encloses no volume.
const ConvexHull* solidHull(const Shape& shape) {
    return shape.hull && shape.hull->isSolid() ? shape.hull.get() : nullptr;
}

/// A length representative of the hull, for relative tolerances.
double hullSize(const ConvexHull& hull) {
    return hull.bounds.extents().maxCoeff();
}

// ---------------------------------------------------------------------------------------------
// Hull against hull

/// Hull b seen in hull a's frame: vertices and face normals turned and moved once per call.
struct HullInFrame {
    const ConvexHull* hull = nullptr;
    std::vector<Vec3> vertices;
    std::vector<Vec3> normals;
    std::vector<double> offsets;
    std::vector<Aabb> faceBounds;
    Aabb bounds;
    Vec3 interiorPoint = Vec3::Zero();

    void set(const ConvexHull& h, const Mat3& rotation, const Vec3& translation) {
        hull = &h;
        vertices.resize(h.vertices.size());
        for (std::size_t i = 0; i < h.vertices.size(); ++i) {
            vertices[i] = rotation * h.vertices[i] + translation;
        }
        normals.resize(h.faces.size());
        offsets.resize(h.faces.size());
        faceBounds.resize(h.faces.size());
        for (std::size_t f = 0; f < h.faces.size(); ++f) {
            const HullFace& face = h.faces[f];
            normals[f] = rotation * face.normal;
            offsets[f] = face.offset + normals[f].dot(translation);
            faceBounds[f] = {};
            for (int i = 0; i < face.vertexCount; ++i) {
                faceBounds[f].grow(vertices[h.faceVertices[face.firstVertex + i]]);
            }
        }
        bounds = {};
        for (const Vec3& v : vertices)
            bounds.grow(v);
        interiorPoint = rotation * h.interiorPoint + translation;
    }
    /// The vertex farthest along `direction`; `start` is the previous answer (warm start).
    const Vec3& support(const Vec3& direction, int& start) const {
        start = hull->supportIndexOf(vertices, direction, start);
        return vertices[start];
    }
    const Vec3& faceVertex(int face, int i) const {
        const HullFace& f = hull->faces[face];
        return vertices[hull->faceVertices[f.firstVertex + i]];
    }
};

thread_local HullInFrame tOther;
thread_local std::vector<int> tEdgesA, tEdgesB;

/// Whether segment p-q meets the box (slab test).
bool segmentTouchesBox(const Vec3& p, const Vec3& q, const Aabb& box) {
    if (box.isEmpty()) return false;
    double t0 = 0.0, t1 = 1.0;
    const Vec3 d = q - p;
    for (int i = 0; i < 3; ++i) {
        if (d[i] == 0.0) {
            if (p[i] < box.min[i] || p[i] > box.max[i]) return false;
            continue;
        }
        double ta = (box.min[i] - p[i]) / d[i], tb = (box.max[i] - p[i]) / d[i];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1) return false;
    }
    return true;
}
thread_local ConvexHull tBoxHull;

struct FaceQuery {
    int face = -1;
    double separation = -kInfinity;
};

struct EdgeQuery {
    int edgeA = -1, edgeB = -1;
    double separation = -kInfinity;
    Vec3 axis = Vec3::Zero();  ///< from a towards b
};

/// Whether the Gauss-map arcs a-b and c-d cross, i.e. the edge pair makes a face of the
/// Minkowski difference and its cross product is a candidate axis (Gregorius 2013).
bool isMinkowskiFace(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const Vec3 bxa = b.cross(a);
    const Vec3 dxc = d.cross(c);
    const double cba = c.dot(bxa), dba = d.dot(bxa);
    const double adc = a.dot(dxc), bdc = b.dot(dxc);
    return cba * dba < 0.0 && adc * bdc < 0.0 && cba * bdc > 0.0;
}

/// Closest points of the segments p + s u and q + t v, s, t in [0, 1] (Ericson 5.1.9).
void closestOnSegments(const Vec3& p, const Vec3& u, const Vec3& q, const Vec3& v, Vec3& onFirst,
                       Vec3& onSecond) {
    double s = 0.0, t = 0.0;
    primitive::closestParametersBetweenSegments(p, u, q, v, s, t);
    onFirst = p + s * u;
    onSecond = q + t * v;
}

/// A clipped polygon vertex and the feature it came from.
struct ClipVertex {
    Vec3 point;
    uint32_t feature;
};
thread_local std::vector<ClipVertex> tClipIn, tClipOut;

/// Sutherland–Hodgman: keeps the part of `in` with m·x <= offset.
void clipByPlane(const std::vector<ClipVertex>& in, const Vec3& m, double offset, uint32_t plane,
                 std::vector<ClipVertex>& out) {
    out.clear();
    const int n = static_cast<int>(in.size());
    for (int i = 0; i < n; ++i) {
        const ClipVertex& a = in[i];
        const ClipVertex& b = in[(i + 1) % n];
        const double da = m.dot(a.point) - offset, db = m.dot(b.point) - offset;
        if (da <= 0.0) out.push_back(a);
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
            const double t = da / (da - db);
            out.push_back(
                {a.point + t * (b.point - a.point), 0x8000u | (plane << 8) | (a.feature & 0xffu)});
        }
    }
}

/// Contact points of reference face `ref` (normal n, offset d, polygon given by `refVertex`)
/// against the incident face of the other hull, all in hull a's frame.
template <class RefVertex, class IncVertex>
void clipFaces(const Vec3& n, double d, int refCount, RefVertex refVertex, int incCount,
               IncVertex incVertex, bool referenceIsA, uint32_t refFeature, double margin,
               const Pose& pa, std::vector<ContactPoint>& candidates) {
    tClipIn.clear();
    for (int i = 0; i < incCount; ++i)
        tClipIn.push_back({incVertex(i), static_cast<uint32_t>(i + 1)});
    for (int i = 0; i < refCount && !tClipIn.empty(); ++i) {
        const Vec3& a = refVertex(i);
        const Vec3& b = refVertex((i + 1) % refCount);
        const Vec3 side = (b - a).cross(n);  // outwards for a counter-clockwise polygon
        clipByPlane(tClipIn, side, side.dot(a), static_cast<uint32_t>(i & 0x7f), tClipOut);
        std::swap(tClipIn, tClipOut);
    }
    const Vec3 worldNormal = pa.rotation * (referenceIsA ? Vec3(-n) : n);
    for (const ClipVertex& v : tClipIn) {
        const double s = n.dot(v.point) - d;
        if (s > margin) continue;
        const Vec3 onReference = pa.apply(v.point - s * n);
        const Vec3 onIncident = pa.apply(v.point);
        ContactPoint c;
        c.point0 = referenceIsA ? onReference : onIncident;
        c.point1 = referenceIsA ? onIncident : onReference;
        c.normal = worldNormal;
        c.depth = (c.point1 - c.point0).dot(worldNormal);
        c.feature = (referenceIsA ? 0u : 0x80000000u) | (refFeature << 16) | v.feature;
        candidates.push_back(c);
    }
}

void collideHulls(const ConvexHull& a, const Pose& pa, const ConvexHull& hb, const Pose& pb,
                  double margin, ContactManifold& out) {
    const Quat qaInverse = pa.rotation.conjugate();
    tOther.set(hb, (qaInverse * pb.rotation).toRotationMatrix(),
               qaInverse * (pb.position - pa.position));
    const HullInFrame& b = tOther;

    // A first bound on the depth, along the line between the centres: no face axis can be
    // deeper than that, so a face whose polygon stays out of the region where the hulls'
    // bounds overlap (grown by that depth or the margin) cannot be the axis of least overlap.
    Vec3 centreLine = b.interiorPoint - a.interiorPoint;
    centreLine = centreLine.norm() > 0.0 ? Vec3(centreLine.normalized()) : Vec3(Vec3::UnitY());
    int warmA = 0, warmB = 0;
    const Vec3& lowestOfB = b.support(-centreLine, warmB);
    warmA = a.supportIndex(centreLine, warmA);
    const double first = centreLine.dot(lowestOfB) - centreLine.dot(a.vertices[warmA]);
    if (first > margin) return;
    const double reach = std::max(margin, -first);
    const Aabb region{a.bounds.min.cwiseMax(b.bounds.min).array() - reach,
                      a.bounds.max.cwiseMin(b.bounds.max).array() + reach};
    if (region.isEmpty()) return;

    // Faces of a: b's deepest vertex below each.
    FaceQuery faceA;
    int warm = warmB;
    for (int f = 0; f < static_cast<int>(a.faces.size()); ++f) {
        if (!a.faceBounds[f].overlaps(region)) continue;
        const HullFace& face = a.faces[f];
        const double s = face.normal.dot(b.support(-face.normal, warm)) - face.offset;
        if (s > margin) return;
        if (s > faceA.separation) faceA = {f, s};
    }
    // Faces of b: a's deepest vertex below each.
    FaceQuery faceB;
    warm = warmA;
    for (int f = 0; f < static_cast<int>(hb.faces.size()); ++f) {
        if (!b.faceBounds[f].overlaps(region)) continue;
        warm = a.supportIndex(-b.normals[f], warm);
        const double s = b.normals[f].dot(a.vertices[warm]) - b.offsets[f];
        if (s > margin) return;
        if (s > faceB.separation) faceB = {f, s};
    }

    // Edge pairs that form faces of the Minkowski difference. Only edges that reach into the
    // region where the hulls overlap (grown by the margin or the best face depth, whichever is
    // larger) can be the pair an edge axis beats the faces with: its witness points lie there.
    // (Should no face of a hull reach the region, numerically, test them all.)
    for (int f = 0; faceA.face < 0 && f < static_cast<int>(a.faces.size()); ++f) {
        const double s =
            a.faces[f].normal.dot(b.support(-a.faces[f].normal, warm)) - a.faces[f].offset;
        if (s > margin) return;
        if (s > faceA.separation) faceA = {f, s};
    }
    for (int f = 0; faceB.face < 0 && f < static_cast<int>(hb.faces.size()); ++f) {
        warm = a.supportIndex(-b.normals[f], warm);
        const double s = b.normals[f].dot(a.vertices[warm]) - b.offsets[f];
        if (s > margin) return;
        if (s > faceB.separation) faceB = {f, s};
    }
    const double grow = std::max(margin, -std::max(faceA.separation, faceB.separation));
    const Aabb overlap{a.bounds.min.cwiseMax(b.bounds.min).array() - grow,
                       a.bounds.max.cwiseMin(b.bounds.max).array() + grow};
    tEdgesA.clear();
    for (int i = 0; i < static_cast<int>(a.edges.size()); ++i) {
        if (segmentTouchesBox(a.vertices[a.edges[i].vertex0], a.vertices[a.edges[i].vertex1],
                              overlap)) {
            tEdgesA.push_back(i);
        }
    }
    tEdgesB.clear();
    if (!tEdgesA.empty()) {
        for (int j = 0; j < static_cast<int>(hb.edges.size()); ++j) {
            if (segmentTouchesBox(b.vertices[hb.edges[j].vertex0], b.vertices[hb.edges[j].vertex1],
                                  overlap)) {
                tEdgesB.push_back(j);
            }
        }
    }
    EdgeQuery edge;
    for (int i : tEdgesA) {
        const HullEdge& ea = a.edges[i];
        const Vec3& n0 = a.faces[ea.face0].normal;
        const Vec3& n1 = a.faces[ea.face1].normal;
        const Vec3& pA = a.vertices[ea.vertex0];
        const Vec3 dA = a.vertices[ea.vertex1] - pA;
        for (int j : tEdgesB) {
            const HullEdge& eb = hb.edges[j];
            if (!isMinkowskiFace(n0, n1, -b.normals[eb.face0], -b.normals[eb.face1])) continue;
            const Vec3& pB = b.vertices[eb.vertex0];
            const Vec3 dB = b.vertices[eb.vertex1] - pB;
            Vec3 axis = dA.cross(dB);
            const double length = axis.norm();
            if (length <= kParallelSine * std::sqrt(dA.squaredNorm() * dB.squaredNorm())) continue;
            axis /= length;
            if (axis.dot(pA - a.interiorPoint) < 0.0) axis = -axis;
            const double s = axis.dot(pB - pA);
            if (s > margin) return;
            if (s > edge.separation) edge = {i, j, s, axis};
        }
    }

    const double size = std::max(hullSize(a), hullSize(hb));
    const auto clearlyBetter = [&](double candidate, double incumbent) {
        return candidate >
               incumbent + kAxisBiasRelative * std::abs(incumbent) + kAxisBiasSize * size;
    };
    const double bestFace = std::max(faceA.separation, faceB.separation);
    tCandidates.clear();
    if (edge.edgeA >= 0 && clearlyBetter(edge.separation, bestFace)) {
        // Edge against edge: one point, the closest points of the two edges.
        const HullEdge& ea = a.edges[edge.edgeA];
        const HullEdge& eb = hb.edges[edge.edgeB];
        Vec3 onA, onB;
        closestOnSegments(a.vertices[ea.vertex0], a.vertices[ea.vertex1] - a.vertices[ea.vertex0],
                          b.vertices[eb.vertex0], b.vertices[eb.vertex1] - b.vertices[eb.vertex0],
                          onA, onB);
        ContactPoint c;
        c.normal = pa.rotation * Vec3(-edge.axis);
        c.point0 = pa.apply(onA);
        c.point1 = pa.apply(onB);
        c.depth = (c.point1 - c.point0).dot(c.normal);
        c.feature = 0x40000000u | (static_cast<uint32_t>(edge.edgeA & 0x7fff) << 15) |
                    static_cast<uint32_t>(edge.edgeB & 0x7fff);
        if (c.depth >= -margin) out.add(c);
        return;
    }

    if (!clearlyBetter(faceB.separation, faceA.separation)) {
        // Reference face on a; incident face: b's face most against it.
        const HullFace& ref = a.faces[faceA.face];
        int incident = 0;
        double lowest = kInfinity;
        for (int f = 0; f < static_cast<int>(hb.faces.size()); ++f) {
            const double d = b.normals[f].dot(ref.normal);
            if (d < lowest) lowest = d, incident = f;
        }
        clipFaces(
            ref.normal, ref.offset, ref.vertexCount,
            [&](int i) -> const Vec3& { return a.faceVertex(ref, i); },
            hb.faces[incident].vertexCount,
            [&](int i) -> const Vec3& { return b.faceVertex(incident, i); }, true,
            static_cast<uint32_t>(faceA.face & 0x3fff), margin, pa, tCandidates);
    } else {
        // Reference face on b; incident face: a's face most against it.
        const Vec3& n = b.normals[faceB.face];
        int incident = 0;
        double lowest = kInfinity;
        for (int f = 0; f < static_cast<int>(a.faces.size()); ++f) {
            const double d = a.faces[f].normal.dot(n);
            if (d < lowest) lowest = d, incident = f;
        }
        const HullFace& inc = a.faces[incident];
        clipFaces(
            n, b.offsets[faceB.face], hb.faces[faceB.face].vertexCount,
            [&](int i) -> const Vec3& { return b.faceVertex(faceB.face, i); }, inc.vertexCount,
            [&](int i) -> const Vec3& { return a.faceVertex(inc, i); }, false,
            static_cast<uint32_t>(faceB.face & 0x3fff), margin, pa, tCandidates);
    }
    appendReduced(tCandidates, out);
}

}  // namespace

// ---------------------------------------------------------------------------------------------

void collideConvexPlane(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                        double margin, ContactManifold& out) {
    const ConvexHull* hull = solidHull(a);
    if (!hull) return;
    // The plane in world coordinates (its pose is the identity for a scene's plane), then in
    // the hull's frame.
    const Vec3 worldNormal = (pb.rotation * b.normal).normalized();
    const double worldOffset = b.offset + worldNormal.dot(pb.position);
    const Vec3 n = pa.rotation.conjugate() * worldNormal;
    const double d = worldOffset - worldNormal.dot(pa.position);

    if (n.dot(hull->support(-n)) - d > margin) return;
    tCandidates.clear();
    for (int i = 0; i < static_cast<int>(hull->vertices.size()); ++i) {
        const double s = n.dot(hull->vertices[i]) - d;
        if (s > margin) continue;
        ContactPoint c;
        c.point0 = pa.apply(hull->vertices[i]);
        c.point1 = c.point0 - s * worldNormal;
        c.normal = worldNormal;
        c.depth = -s;
        c.feature = static_cast<uint32_t>(i + 1);
        tCandidates.push_back(c);
    }
    appendReduced(tCandidates, out);
}

void collideConvexSphere(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                         double margin, ContactManifold& out) {
    const ConvexHull* hull = solidHull(a);
    if (!hull) return;
    const Vec3 center = pa.applyInverse(pb.position);
    const HullClosestPoint closest = hull->closestPoint(center);
    if (b.radius - closest.signedDistance < -margin) return;

    // From the sphere towards the hull: along centre -> closest point when that is defined,
    // else out through the nearest face.
    Vec3 n = -hull->faces[closest.face].normal;
    if (closest.signedDistance > kDirectionEpsilon * hullSize(*hull)) {
        n = (closest.point - center) / closest.signedDistance;
    }
    ContactPoint c;
    c.normal = pa.rotation * n;
    c.point0 = pa.apply(closest.point);
    c.point1 = pb.position + b.radius * c.normal;
    c.depth = (c.point1 - c.point0).dot(c.normal);
    c.feature = static_cast<uint32_t>(closest.face + 1);
    out.add(c);
}

void collideConvexCapsule(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                          double margin, ContactManifold& out) {
    const ConvexHull* hull = solidHull(a);
    if (!hull) return;
    // The capsule's segment in the hull's frame.
    const Vec3 axisWorld = pb.rotation * Vec3::UnitY();
    const Vec3 p0 = pa.applyInverse(pb.position - 0.5 * b.length * axisWorld);
    const Vec3 p1 = pa.applyInverse(pb.position + 0.5 * b.length * axisWorld);
    const Vec3 segment = p1 - p0;

    // The signed distance to a convex set is convex along a segment: golden-section search
    // finds its minimum, the segment point deepest in (or closest to) the hull.
    const auto distanceAt = [&](double t) {
        return hull->closestPoint(p0 + t * segment).signedDistance;
    };
    double lo = 0.0, hi = 1.0;
    if (b.length > 0.0) {
        const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
        double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
        double f1 = distanceAt(x1), f2 = distanceAt(x2);
        const double length = segment.norm();
        const double tolerance =
            kSegmentSearchTolerance * std::max(length, hullSize(*hull)) / length;
        while (hi - lo > tolerance) {
            if (f1 <= f2) {
                hi = x2, x2 = x1, f2 = f1;
                x1 = hi - ratio * (hi - lo);
                f1 = distanceAt(x1);
            } else {
                lo = x1, x1 = x2, f1 = f2;
                x2 = lo + ratio * (hi - lo);
                f2 = distanceAt(x2);
            }
        }
    }
    double t = 0.5 * (lo + hi);
    // The ends, in case the minimum sits on one (the search only approaches it).
    for (double end : {0.0, 1.0}) {
        if (distanceAt(end) <= distanceAt(t)) t = end;
    }
    const Vec3 core = p0 + t * segment;
    const HullClosestPoint closest = hull->closestPoint(core);
    if (b.radius - closest.signedDistance < -margin) return;

    const HullFace& face = hull->faces[closest.face];
    Vec3 n = -face.normal;
    if (closest.signedDistance > kDirectionEpsilon * hullSize(*hull)) {
        n = (closest.point - core) / closest.signedDistance;
    }

    // Lying along a face: the segment clipped to the face's side planes gives two points.
    const double length = segment.norm();
    if (closest.onFaceInterior && length > 0.0 &&
        std::abs(segment.dot(face.normal)) < kCapsuleAlongFace * length) {
        double t0 = 0.0, t1 = 1.0;
        for (int i = 0; i < face.vertexCount && t0 <= t1; ++i) {
            const Vec3& u = hull->faceVertex(face, i);
            const Vec3& v = hull->faceVertex(face, (i + 1) % face.vertexCount);
            const Vec3 side = (v - u).cross(face.normal);
            const double d0 = side.dot(p0 - u), rate = side.dot(segment);
            // Keep side·(p0 + t segment − u) <= 0.
            if (rate > 0.0)
                t1 = std::min(t1, -d0 / rate);
            else if (rate < 0.0)
                t0 = std::max(t0, -d0 / rate);
            else if (d0 > 0.0)
                t1 = -1.0;
        }
        if (t1 - t0 > 1e-6) {
            const Vec3 worldNormal = pa.rotation * Vec3(-face.normal);
            int added = 0;
            for (double end : {t0, t1}) {
                const Vec3 q = p0 + end * segment;
                const double s = face.normal.dot(q) - face.offset;
                if (b.radius - s < -margin) continue;
                ContactPoint c;
                c.normal = worldNormal;
                c.point0 = pa.apply(q - s * face.normal);
                c.point1 = pa.apply(q) + b.radius * worldNormal;
                c.depth = (c.point1 - c.point0).dot(worldNormal);
                c.feature = static_cast<uint32_t>(closest.face + 1) | (end == t0 ? 0u : 0x10000u);
                out.add(c);
                ++added;
            }
            if (added > 0) return;
        }
    }

    ContactPoint c;
    c.normal = pa.rotation * n;
    c.point0 = pa.apply(closest.point);
    c.point1 = pa.apply(core) + b.radius * c.normal;
    c.depth = (c.point1 - c.point0).dot(c.normal);
    c.feature = static_cast<uint32_t>(closest.face + 1);
    out.add(c);
}

void collideConvexBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                      ContactManifold& out) {
    const ConvexHull* hull = solidHull(a);
    if (!hull) return;
    setBoxHull(tBoxHull, b.size);
    collideHulls(*hull, pa, tBoxHull, pb, margin, out);
}

void collideConvexConvex(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                         double margin, ContactManifold& out) {
    const ConvexHull* hullA = solidHull(a);
    const ConvexHull* hullB = solidHull(b);
    if (!hullA || !hullB) return;
    collideHulls(*hullA, pa, *hullB, pb, margin, out);
}

namespace {

/// Turns the points from `first` on into the swapped pair's: points exchanged, normal reversed
/// (the depth, (point1 − point0)·normal, is unchanged).
void swapShapes(ContactManifold& out, int first) {
    for (int i = first; i < out.count; ++i) {
        ContactPoint& c = out.points[i];
        std::swap(c.point0, c.point1);
        c.normal = -c.normal;
    }
}

}  // namespace

void collideSphereConvex(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                         double margin, ContactManifold& out) {
    const int first = out.count;
    collideConvexSphere(b, pb, a, pa, margin, out);
    swapShapes(out, first);
}

void collideCapsuleConvex(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                          double margin, ContactManifold& out) {
    const int first = out.count;
    collideConvexCapsule(b, pb, a, pa, margin, out);
    swapShapes(out, first);
}

void collideBoxConvex(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                      ContactManifold& out) {
    const int first = out.count;
    collideConvexBox(b, pb, a, pa, margin, out);
    swapShapes(out, first);
}

}  // namespace substep
