#include "physics/collision/triangle_contact.h"

#include "physics/collision/primitive_geometry.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace substep {

namespace {

/// num / den for den > 0, else 0: the degenerate-triangle guard of the region walk.
double ratio(double num, double den) {
    return den > 0.0 ? num / den : 0.0;
}

/// Feature ids (triangleFeatureId) of this triangle.
uint32_t featureId(const ContactTriangle& tri, uint32_t local) {
    return triangleFeatureId(tri.id, local);
}

uint32_t localCode(const TrianglePoint& p) {
    switch (p.feature) {
        case TriangleFeature::Face:
            return 0;
        case TriangleFeature::Vertex:
            return 1u + static_cast<uint32_t>(p.index);
        case TriangleFeature::Edge:
            return 4u + static_cast<uint32_t>(p.index);
    }
    return 0;
}

bool featureActive(const ContactTriangle& tri, const TrianglePoint& p) {
    switch (p.feature) {
        case TriangleFeature::Face:
            return false;
        case TriangleFeature::Vertex:
            return tri.vertexActive(p.index);
        case TriangleFeature::Edge:
            return tri.edgeActive(p.index);
    }
    return true;
}

Vec3 closestOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a;
    return a + std::clamp(ratio((p - a).dot(ab), ab.squaredNorm()), 0.0, 1.0) * ab;
}

/// A polygon vertex while clipping; `synthetic` marks points made by clipping against an
/// inactive edge (they lie on an internal edge that the neighbour triangle covers).
struct ClipVertex {
    Vec3 p;
    bool synthetic = false;
};

/// Up to 4 + 4 vertices: a quad clipped by 3 planes or a triangle clipped by 4 stays within 8.
struct ClipPolygon {
    std::array<ClipVertex, 8> v;
    int count = 0;
};

/// Keeps the part of `in` with m·p >= offset.
ClipPolygon clip(const ClipPolygon& in, const Vec3& m, double offset, bool makesSynthetic) {
    ClipPolygon out;
    for (int i = 0; i < in.count; ++i) {
        const ClipVertex& a = in.v[i];
        const ClipVertex& b = in.v[(i + 1) % in.count];
        const double da = m.dot(a.p) - offset;
        const double db = m.dot(b.p) - offset;
        if (da >= 0.0 && out.count < 8) out.v[out.count++] = a;
        if ((da >= 0.0) != (db >= 0.0) && out.count < 8) {
            const double t = da / (da - db);
            out.v[out.count++] = {a.p + t * (b.p - a.p), makesSynthetic};
        }
    }
    return out;
}

}  // namespace

TrianglePoint closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a;
    const Vec3 ac = c - a;
    const Vec3 ap = p - a;
    const double d1 = ab.dot(ap);
    const double d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0) return {a, TriangleFeature::Vertex, 0};
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp);
    const double d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3) return {b, TriangleFeature::Vertex, 1};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        return {a + ratio(d1, d1 - d3) * ab, TriangleFeature::Edge, 0};
    }
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp);
    const double d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6) return {c, TriangleFeature::Vertex, 2};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        return {a + ratio(d2, d2 - d6) * ac, TriangleFeature::Edge, 2};
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
        return {b + ratio(d4 - d3, (d4 - d3) + (d5 - d6)) * (c - b), TriangleFeature::Edge, 1};
    }
    const double sum = va + vb + vc;  // = |ab × ac|²: zero for a degenerate triangle
    if (!(sum > 1e-24 * ab.squaredNorm() * ac.squaredNorm())) {
        // No face to speak of: the nearest of the three edges.
        TrianglePoint best{closestOnSegment(p, a, b), TriangleFeature::Edge, 0};
        const Vec3 onBc = closestOnSegment(p, b, c);
        const Vec3 onCa = closestOnSegment(p, c, a);
        if ((onBc - p).squaredNorm() < (best.point - p).squaredNorm())
            best = {onBc, TriangleFeature::Edge, 1};
        if ((onCa - p).squaredNorm() < (best.point - p).squaredNorm())
            best = {onCa, TriangleFeature::Edge, 2};
        return best;
    }
    const double v = vb / sum;
    const double w = vc / sum;
    return {a + v * ab + w * ac, TriangleFeature::Face, 0};
}

void closestSegmentSegment(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1,
                           double& s, double& t) {
    primitive::closestParametersBetweenSegments(p0, p1 - p0, q0, q1 - q0, s, t);
}

void addSphereTriangleContacts(const ContactTriangle& tri, const Vec3& c, double r, double margin,
                               bool solidBelow, ContactBuffer& buffer) {
    const Vec3& n = tri.normal;
    const double height = (c - tri.v[0]).dot(n);
    if (height > r + margin) return;
    if (!solidBelow && height < -r) return;  // passed through: a one-sided mesh lets it go
    const TrianglePoint closest = closestOnTriangle(c, tri.v[0], tri.v[1], tri.v[2]);
    const Vec3 offset = c - closest.point;

    if (height <= 0.0 || !featureActive(tri, closest)) {
        // Face normal: over the face, behind it, or on an internal edge or vertex.
        if (closest.feature != TriangleFeature::Face) {
            const Vec3 sideways = offset - offset.dot(n) * n;
            if (sideways.squaredNorm() > (kInactiveSideways * r) * (kInactiveSideways * r)) return;
        }
        addSphereFaceNormalContact(n, height, c, r, margin, featureId(tri, localCode(closest)), buffer);
        return;
    }
    // An active edge or vertex: along the direction to it.
    const double d = offset.norm();
    if (d > r + margin) return;
    ContactPoint contact;
    contact.normal = d > kDirectionEpsilon ? Vec3(offset / d) : n;
    contact.depth = r - d;
    contact.point1 = closest.point;
    if (contact.depth < -margin) return;
    contact.point0 = c - r * contact.normal;
    contact.feature = featureId(tri, localCode(closest));
    buffer.add(contact);
}

void addCapsuleTriangleContacts(const ContactTriangle& tri, const Vec3& e0, const Vec3& e1,
                                double r, double margin, bool solidBelow, ContactBuffer& buffer) {
    const Vec3& n = tri.normal;
    // The caps: support at both ends of a capsule lying on the triangle.
    addSphereTriangleContacts(tri, e0, r, margin, solidBelow, buffer);
    addSphereTriangleContacts(tri, e1, r, margin, solidBelow, buffer);

    // An axis through the face: push the end behind the plane out the front.
    const double h0 = (e0 - tri.v[0]).dot(n);
    const double h1 = (e1 - tri.v[0]).dot(n);
    if ((h0 > 0.0) != (h1 > 0.0)) {
        const Vec3 crossing = e0 + (h0 / (h0 - h1)) * (e1 - e0);
        if (closestOnTriangle(crossing, tri.v[0], tri.v[1], tri.v[2]).feature ==
            TriangleFeature::Face) {
            const Vec3& back = h0 < h1 ? e0 : e1;
            const double height = std::min(h0, h1);
            ContactPoint contact;
            contact.normal = n;
            contact.depth = r - height;
            contact.point0 = back - r * n;
            contact.point1 = back - height * n;
            contact.feature = featureId(tri, 10);
            buffer.add(contact);
        }
    }

    // The axis against active edges: a capsule lying across a ridge or the mesh's border.
    for (int i = 0; i < 3; ++i) {
        if (!tri.edgeActive(i)) continue;
        const Vec3& a = tri.v[i];
        const Vec3& b = tri.v[(i + 1) % 3];
        double s, t;
        closestSegmentSegment(e0, e1, a, b, s, t);
        if (s <= 0.0 || s >= 1.0) continue;  // the caps cover the ends
        const Vec3 onAxis = e0 + s * (e1 - e0);
        const Vec3 onEdge = a + t * (b - a);
        const Vec3 offset = onAxis - onEdge;
        const double d = offset.norm();
        if (d > r + margin || d <= kDirectionEpsilon) continue;
        if ((onAxis - tri.v[0]).dot(n) <= 0.0) continue;
        // Only where the edge, not the face, is what the axis point is nearest.
        const TrianglePoint nearest = closestOnTriangle(onAxis, tri.v[0], tri.v[1], tri.v[2]);
        if (nearest.feature == TriangleFeature::Face ||
            (nearest.point - onEdge).squaredNorm() > 1e-12 * (d + r) * (d + r)) {
            continue;
        }
        ContactPoint contact;
        contact.normal = offset / d;
        contact.depth = r - d;
        contact.point0 = onAxis - r * contact.normal;
        contact.point1 = onEdge;
        contact.feature = featureId(tri, 11u + static_cast<uint32_t>(i));
        buffer.add(contact);
    }
}

void addBoxTriangleContacts(const ContactTriangle& tri, const OrientedBox& box, double margin,
                            bool solidBelow, ContactBuffer& buffer) {
    const Vec3& n = tri.normal;
    const Vec3* v = tri.v;
    const Vec3& C = box.centre;
    const auto boxRadius = [&](const Vec3& L) {
        return box.half.x() * std::abs(box.axes.col(0).dot(L)) +
               box.half.y() * std::abs(box.axes.col(1).dot(L)) +
               box.half.z() * std::abs(box.axes.col(2).dot(L));
    };
    // Separation along unit axis L (either orientation); L is turned to point from the
    // triangle to the box.
    const auto separation = [&](Vec3& L) {
        const double centre = C.dot(L);
        const double radius = boxRadius(L);
        const double t0 = v[0].dot(L), t1 = v[1].dot(L), t2 = v[2].dot(L);
        const double boxAbove = (centre - radius) - std::max({t0, t1, t2});
        const double boxBelow = std::min({t0, t1, t2}) - (centre + radius);
        if (boxBelow > boxAbove) {
            L = -L;
            return boxBelow;
        }
        return boxAbove;
    };

    // 1. The face normal (one-sided: the box is always pushed out the front).
    const double extentAlongNormal = boxRadius(n);
    const double centreHeight = (C - v[0]).dot(n);
    if (!solidBelow && centreHeight < -extentAlongNormal) return;
    const double faceSeparation = centreHeight - extentAlongNormal;
    if (faceSeparation > margin) return;

    enum class Axis { TriangleFace, BoxFace, EdgePair };
    Axis bestKind = Axis::TriangleFace;
    Vec3 bestAxis = n;
    double best = faceSeparation;
    int bestBoxAxis = 0, bestEdge = 0;
    // Prefer the triangle's face, then the box's faces, unless another axis is clearly better:
    // face contacts give whole patches of points and are stable from substep to substep.
    const double bias = 1e-3 * box.half.maxCoeff();

    // 2. The box's face normals.
    for (int k = 0; k < 3; ++k) {
        Vec3 L = box.axes.col(k);
        const double sep = separation(L);
        if (sep > margin) return;
        if (L.dot(n) >= -1e-6 && sep > best + bias) {
            best = sep;
            bestAxis = L;
            bestKind = Axis::BoxFace;
            bestBoxAxis = k;
        }
    }
    // 3. Edge pairs; internal edges have no say (they would snag boxes sliding across them).
    for (int j = 0; j < 3; ++j) {
        const Vec3 edge = v[(j + 1) % 3] - v[j];
        for (int k = 0; k < 3; ++k) {
            Vec3 L = box.axes.col(k).cross(edge);
            const double length = L.norm();
            if (length <= 1e-6 * edge.norm()) continue;  // parallel: the face axes cover it
            L /= length;
            const double sep = separation(L);
            if (sep > margin) return;
            if (tri.edgeActive(j) && L.dot(n) >= -1e-6 && sep > best + 2.0 * bias) {
                best = sep;
                bestAxis = L;
                bestKind = Axis::EdgePair;
                bestBoxAxis = k;
                bestEdge = j;
            }
        }
    }

    if (bestKind == Axis::TriangleFace) {
        // The box face turned most against the normal, clipped to the triangle's prism.
        int k = 0;
        (box.axes.transpose() * n).cwiseAbs().maxCoeff(&k);
        const Vec3 outward = box.axes.col(k) * (box.axes.col(k).dot(n) > 0.0 ? -1.0 : 1.0);
        const Vec3 faceCentre = C + box.half[k] * outward;
        const Vec3 u = box.axes.col((k + 1) % 3) * box.half[(k + 1) % 3];
        const Vec3 w = box.axes.col((k + 2) % 3) * box.half[(k + 2) % 3];
        ClipPolygon polygon;
        polygon.count = 4;
        polygon.v[0] = {faceCentre - u - w};
        polygon.v[1] = {faceCentre + u - w};
        polygon.v[2] = {faceCentre + u + w};
        polygon.v[3] = {faceCentre - u + w};
        for (int i = 0; i < 3 && polygon.count > 0; ++i) {
            const Vec3 inward = n.cross(v[(i + 1) % 3] - v[i]);
            polygon = clip(polygon, inward, inward.dot(v[i]), !tri.edgeActive(i));
        }
        for (int i = 0; i < polygon.count; ++i) {
            if (polygon.v[i].synthetic) continue;
            const Vec3& p = polygon.v[i].p;
            ContactPoint contact;
            contact.normal = n;
            contact.depth = (v[0] - p).dot(n);
            if (contact.depth < -margin) continue;
            contact.point0 = p;
            contact.point1 = p + contact.depth * n;
            contact.feature = featureId(tri, 16u + static_cast<uint32_t>(i));
            buffer.add(contact);
        }
    } else if (bestKind == Axis::BoxFace) {
        // The triangle clipped to the side planes of the box face that faces it.
        const double faceLevel = C.dot(bestAxis) - box.half[bestBoxAxis];
        ClipPolygon polygon;
        polygon.count = 3;
        for (int i = 0; i < 3; ++i)
            polygon.v[i] = {v[i]};
        for (int m = 1; m < 3 && polygon.count > 0; ++m) {
            const int axis = (bestBoxAxis + m) % 3;
            const Vec3 a = box.axes.col(axis);
            const double centre = a.dot(C);
            polygon = clip(polygon, a, centre - box.half[axis], false);
            polygon = clip(polygon, -a, -(centre + box.half[axis]), false);
        }
        for (int i = 0; i < polygon.count; ++i) {
            const Vec3& p = polygon.v[i].p;
            ContactPoint contact;
            contact.normal = bestAxis;
            contact.depth = p.dot(bestAxis) - faceLevel;
            if (contact.depth < -margin) continue;
            contact.point1 = p;
            contact.point0 = p - contact.depth * bestAxis;
            contact.feature = featureId(tri, 24u + static_cast<uint32_t>(i));
            buffer.add(contact);
        }
    } else {
        // The box edge along the chosen axis that reaches furthest against the normal.
        Vec3 base = C;
        for (int m = 0; m < 3; ++m) {
            if (m == bestBoxAxis) continue;
            const Vec3 a = box.axes.col(m);
            base -= (a.dot(bestAxis) > 0.0 ? 1.0 : -1.0) * box.half[m] * a;
        }
        const Vec3 along = box.half[bestBoxAxis] * box.axes.col(bestBoxAxis);
        const Vec3& a = v[bestEdge];
        const Vec3& b = v[(bestEdge + 1) % 3];
        double s, t;
        closestSegmentSegment(base - along, base + along, a, b, s, t);
        ContactPoint contact;
        contact.normal = bestAxis;
        contact.point0 = base - along + s * (2.0 * along);
        contact.point1 = a + t * (b - a);
        contact.depth = (contact.point1 - contact.point0).dot(bestAxis);
        if (contact.depth < -margin) return;
        contact.feature = featureId(
            tri, 32u + 3u * static_cast<uint32_t>(bestEdge) + static_cast<uint32_t>(bestBoxAxis));
        buffer.add(contact);
    }
}

}  // namespace substep
