#include "physics/collision/convex_support.h"

#include "physics/collision/collide_cylinder.h"
#include "physics/collision/convex_hull.h"
#include "physics/collision/triangle_contact.h"

#include <algorithm>
#include <cmath>

namespace substep {

namespace {

/// A sign that is never zero, so a direction along a face picks one face consistently.
double signOf(double x) {
    return x < 0.0 ? -1.0 : 1.0;
}

void boxFeature(const ConvexSupport& s, const Vec3& d, SupportFeature& out) {
    const Vec3 local = s.axes.transpose() * d;
    int k = 0;
    local.cwiseAbs().maxCoeff(&k);
    const double sign = signOf(local[k]);
    const int i = (k + 1) % 3;
    const int j = (k + 2) % 3;
    const Vec3 faceCentre = s.centre + sign * s.half[k] * s.axes.col(k);
    const Vec3 u = s.half[i] * s.axes.col(i);
    const Vec3 w = s.half[j] * s.axes.col(j);
    out.count = 4;
    out.vertices[0] = faceCentre - u - w;
    out.vertices[1] = faceCentre + u - w;
    out.vertices[2] = faceCentre + u + w;
    out.vertices[3] = faceCentre - u + w;
    out.normal = sign * s.axes.col(k);
    out.alignment = std::abs(local[k]);
    out.id = static_cast<uint32_t>(2 * k + (sign > 0.0 ? 0 : 1));
}

void cylinderFeature(const ConvexSupport& s, const Vec3& d, SupportFeature& out) {
    const Vec3 axis = s.axes.col(1);
    const double along = d.dot(axis);
    const double radius = s.half.x();
    const double halfLength = s.half.y();
    const Vec3 across = d - along * axis;
    const double acrossLength = across.norm();
    if (acrossLength <= kCylinderFlatSine) {
        // Lying flat: the face as a polygon of rim points fixed in the cylinder's frame.
        const double sign = signOf(along);
        const Vec3 faceCentre = s.centre + sign * halfLength * axis;
        out.count = kCylinderFaceVertices;
        for (int k = 0; k < kCylinderFaceVertices; ++k) {
            const double angle = 2.0 * M_PI * k / kCylinderFaceVertices;
            out.vertices[k] = faceCentre + radius * (std::cos(angle) * s.axes.col(0) +
                                                     std::sin(angle) * s.axes.col(2));
        }
        out.normal = sign * axis;
        out.alignment = std::abs(along);
        out.id = sign > 0.0 ? 1u : 2u;
        return;
    }
    const Vec3 outward = across / acrossLength;
    if (std::abs(along) <= kCylinderSideCosine) {
        // On its side: the line of the side farthest along d.
        out.count = 2;
        out.vertices[0] = s.centre + radius * outward - halfLength * axis;
        out.vertices[1] = s.centre + radius * outward + halfLength * axis;
        out.normal = outward;
        out.alignment = 0.0;
        out.id = 3u;
        return;
    }
    out.count = 1;
    out.vertices[0] = s.support(d);
    out.alignment = 0.0;
    out.id = 4u;
}

void segmentFeature(const ConvexSupport& s, const Vec3& d, SupportFeature& out) {
    const Vec3 axis = s.axes.col(1);
    const double along = d.dot(axis);
    if (s.half.y() > 0.0 && std::abs(along) <= kCylinderSideCosine) {
        out.count = 2;
        out.vertices[0] = s.centre - s.half.y() * axis;
        out.vertices[1] = s.centre + s.half.y() * axis;
        out.id = 3u;
    } else {
        out.count = 1;
        out.vertices[0] = s.support(d);
        out.id = along < 0.0 ? 1u : 2u;
    }
    out.alignment = 0.0;
}

void hullFeature(const ConvexSupport& s, const Vec3& d, SupportFeature& out) {
    const ConvexHull& hull = *s.hull;
    const Vec3 local = s.axes.transpose() * d;
    // The face turned most towards d among those around the support vertex would do; the
    // faces are few enough (merged coplanar triangles) that a scan costs less than the walk.
    int best = 0;
    double bestDot = -2.0;
    for (int f = 0; f < static_cast<int>(hull.faces.size()); ++f) {
        const double dot = hull.faces[f].normal.dot(local);
        if (dot > bestDot) bestDot = dot, best = f;
    }
    const HullFace& face = hull.faces[best];
    const int n = face.vertexCount;
    // Hull faces with more vertices than a feature holds keep an even selection of them.
    const int count = std::min(n, kMaxFeatureVertices);
    out.count = count;
    for (int k = 0; k < count; ++k) {
        const int i = count == n ? k : (k * n) / count;
        out.vertices[k] = s.origin + s.axes * hull.faceVertex(face, i);
    }
    out.normal = s.axes * face.normal;
    out.alignment = bestDot;
    out.id = static_cast<uint32_t>(best);
}

}  // namespace

Vec3 ConvexSupport::support(const Vec3& d) const {
    switch (kind) {
        case CoreKind::Point:
            return centre;
        case CoreKind::Segment: {
            const Vec3 axis = axes.col(1);
            return centre + signOf(d.dot(axis)) * half.y() * axis;
        }
        case CoreKind::Box: {
            const Vec3 local = axes.transpose() * d;
            return centre + axes * Vec3(signOf(local.x()) * half.x(), signOf(local.y()) * half.y(),
                                        signOf(local.z()) * half.z());
        }
        case CoreKind::Cylinder: {
            const Vec3 local = axes.transpose() * d;
            const double across = std::hypot(local.x(), local.z());
            Vec3 p(0.0, signOf(local.y()) * half.y(), 0.0);
            if (across > kDirectionEpsilon * (std::abs(local.y()) + across)) {
                p.x() = half.x() * local.x() / across;
                p.z() = half.x() * local.z() / across;
            }
            return centre + axes * p;
        }
        case CoreKind::Hull: {
            warmStart = hull->supportIndex(axes.transpose() * d, warmStart);
            return origin + axes * hull->vertices[warmStart];
        }
        case CoreKind::Triangle: {
            const double d0 = triangle[0].dot(d), d1 = triangle[1].dot(d), d2 = triangle[2].dot(d);
            if (d0 >= d1 && d0 >= d2) return triangle[0];
            return d1 >= d2 ? triangle[1] : triangle[2];
        }
    }
    return centre;
}

void ConvexSupport::feature(const Vec3& d, SupportFeature& out) const {
    out.alignment = 0.0;
    out.id = 0;
    switch (kind) {
        case CoreKind::Point:
            out.count = 1;
            out.vertices[0] = centre;
            return;
        case CoreKind::Segment:
            segmentFeature(*this, d, out);
            return;
        case CoreKind::Box:
            boxFeature(*this, d, out);
            return;
        case CoreKind::Cylinder:
            cylinderFeature(*this, d, out);
            return;
        case CoreKind::Hull:
            hullFeature(*this, d, out);
            return;
        case CoreKind::Triangle: {
            // Seen from either side the triangle is its face (the normal follows the query).
            const double sign = signOf(triangleNormal.dot(d));
            out.count = 3;
            for (int k = 0; k < 3; ++k)
                out.vertices[k] = triangle[k];
            out.normal = sign * triangleNormal;
            out.alignment = std::abs(triangleNormal.dot(d));
            return;
        }
    }
}

double ConvexSupport::size() const {
    switch (kind) {
        case CoreKind::Point:
            return radius;
        case CoreKind::Segment:
            return radius + half.y();
        case CoreKind::Box:
            return half.maxCoeff();
        case CoreKind::Cylinder:
            return std::max(half.x(), half.y());
        case CoreKind::Hull:
            return 0.5 * hull->bounds.extents().maxCoeff();
        case CoreKind::Triangle:
            return std::max({(triangle[1] - triangle[0]).norm(), (triangle[2] - triangle[1]).norm(),
                             (triangle[0] - triangle[2]).norm()});
    }
    return radius;
}

bool makeConvexSupport(const Shape& shape, const Pose& pose, const Pose& frame,
                       ConvexSupport& out) {
    const Quat rotation = frame.rotation.conjugate() * pose.rotation;
    out = ConvexSupport{};
    out.centre = frame.applyInverse(pose.position);
    out.axes = rotation.toRotationMatrix();
    switch (shape.type) {
        case ShapeType::Sphere:
            out.kind = CoreKind::Point;
            out.radius = shape.radius;
            return true;
        case ShapeType::Capsule:
            out.kind = CoreKind::Segment;
            out.radius = shape.radius;
            out.half = Vec3(0.0, 0.5 * std::max(shape.length, 0.0), 0.0);
            return true;
        case ShapeType::Box:
            out.kind = CoreKind::Box;
            out.half = 0.5 * shape.size.cwiseAbs();
            return true;
        case ShapeType::Cylinder:
            out.kind = CoreKind::Cylinder;
            out.half = Vec3(shape.radius, 0.5 * shape.length, shape.radius);
            return true;
        case ShapeType::Mesh:
            if (!shape.convex || !shape.hull || !shape.hull->isSolid()) return false;
            out.kind = CoreKind::Hull;
            out.hull = shape.hull.get();
            out.origin = out.centre;
            out.centre = out.origin + out.axes * shape.hull->interiorPoint;
            return true;
        default:
            return false;
    }
}

ConvexSupport triangleSupport(const ContactTriangle& triangle) {
    ConvexSupport s;
    s.kind = CoreKind::Triangle;
    s.triangle = {triangle.v[0], triangle.v[1], triangle.v[2]};
    s.triangleNormal = triangle.normal;
    s.centre = (triangle.v[0] + triangle.v[1] + triangle.v[2]) / 3.0;
    return s;
}

}  // namespace substep
