// Narrowphase pair of two boxes. The separating-axis test over the 15 candidate axes (3 face
// normals of each box, 9 edge cross products) finds the axis of least penetration, or a gap
// beyond the margin (no contact). A face axis makes that box's face the reference face: the
// other box's most anti-parallel face (the incident face) is clipped against the reference
// face's four side planes (Sutherland–Hodgman), and the clipped points below the reference
// face plus margin are the contacts, reduced to at most 4. An edge axis gives the one pair of
// closest points of the two edges.
//
// The solver re-runs this every substep on resting stacks, where several axes are nearly as
// good: a candidate replaces the current choice only when it is better by a relative
// tolerance, which prefers face axes over edge axes, box a's faces over box b's and the
// lower axis index, so the reference face does not flip between near-equal candidates.

#include "physics/collision/collide_primitives.h"
#include "physics/collision/primitive_geometry.h"

#include <cmath>

namespace substep {

using namespace primitive;

namespace {

/// A candidate axis must beat the current one by this fraction of its separation...
constexpr double kRelativeTolerance = 0.05;
/// ...plus this fraction of the larger box's largest half extent.
constexpr double kAbsoluteTolerance = 1e-4;
/// Edge pairs closer to parallel than this sine are covered by the face axes.
constexpr double kEdgeParallelSine = 1e-6;
/// The reference face is clipped against grown by this fraction of its larger half extent, so
/// an incident corner that lies on the face's border (equal boxes stacked) stays a corner, with
/// its feature id, instead of turning into a cut point as it wobbles across the border.
constexpr double kClipSlack = 1e-3;

struct BoxFrame {
    Vec3 centre;
    Mat3 axes;  ///< columns: the box's axes in world coordinates
    Vec3 half;
};

/// A clipped polygon: up to 8 vertices (a quad clipped by 4 planes), each with the id of the
/// feature it came from and the id of the edge that starts at it.
struct ClipPolygon {
    Vec3 vertices[8];
    uint8_t vertexIds[8];
    uint8_t edgeIds[8];
    int count = 0;

    void push(const Vec3& v, uint8_t vertexId, uint8_t edgeId) {
        vertices[count] = v;
        vertexIds[count] = vertexId;
        edgeIds[count] = edgeId;
        ++count;
    }
};

/// Keeps the part of `in` where sign·p[axis] <= limit. Vertex ids: incident corners 0-3;
/// a cut point is 8 + 4·(id of the edge it cuts, 0-7) + plane (0-3). Edge ids: incident
/// edges 0-3, edges along a clip plane 4 + plane.
void clipPolygon(const ClipPolygon& in, int axis, double sign, double limit, int plane,
                 ClipPolygon& out) {
    out.count = 0;
    if (in.count == 0) return;
    int previous = in.count - 1;
    double previousDistance = sign * in.vertices[previous][axis] - limit;
    for (int current = 0; current < in.count; ++current) {
        const double distance = sign * in.vertices[current][axis] - limit;
        const bool currentInside = distance <= 0.0;
        const bool previousInside = previousDistance <= 0.0;
        if (currentInside != previousInside) {
            const double f = previousDistance / (previousDistance - distance);
            const Vec3 cut =
                in.vertices[previous] + f * (in.vertices[current] - in.vertices[previous]);
            const uint8_t cutEdge = in.edgeIds[previous];
            const auto cutId = static_cast<uint8_t>(8 + 4 * cutEdge + plane);
            // Entering: the cut starts a piece of the cut edge; leaving: a piece of the plane.
            out.push(cut, cutId, currentInside ? cutEdge : static_cast<uint8_t>(4 + plane));
        }
        if (currentInside)
            out.push(in.vertices[current], in.vertexIds[current], in.edgeIds[current]);
        previous = current;
        previousDistance = distance;
    }
}

/// Twice the signed area of triangle (p, q, r) projected on the plane of axes u, v.
double signedArea(const Vec3& p, const Vec3& q, const Vec3& r, int u, int v) {
    return (q[u] - p[u]) * (r[v] - p[v]) - (q[v] - p[v]) * (r[u] - p[u]);
}

/// Chooses at most 4 of `count` (> 4) points: the deepest, the farthest from it, the one
/// spanning the largest triangle with those two, and the one adding the most area to it.
int reduceToFour(const ClipPolygon& polygon, const double* depth, const int* candidates, int count,
                 int u, int v, int* kept) {
    const auto at = [&](int k) -> const Vec3& { return polygon.vertices[candidates[k]]; };
    int first = 0;
    for (int k = 1; k < count; ++k) {
        if (depth[k] > depth[first]) first = k;
    }
    int second = first == 0 ? 1 : 0;
    double farthest = -1.0;
    for (int k = 0; k < count; ++k) {
        const double du = at(k)[u] - at(first)[u];
        const double dv = at(k)[v] - at(first)[v];
        const double d2 = du * du + dv * dv;
        if (k != first && d2 > farthest) {
            farthest = d2;
            second = k;
        }
    }
    int third = -1;
    double largest = -1.0;
    for (int k = 0; k < count; ++k) {
        if (k == first || k == second) continue;
        const double area = std::abs(signedArea(at(first), at(second), at(k), u, v));
        if (area > largest) {
            largest = area;
            third = k;
        }
    }
    // Orient the triangle counter-clockwise; a point outside edge (p, q) has area(p, q, x) < 0.
    if (signedArea(at(first), at(second), at(third), u, v) < 0.0) std::swap(first, second);
    int fourth = -1;
    double added = 0.0;
    for (int k = 0; k < count; ++k) {
        if (k == first || k == second || k == third) continue;
        const double gain = std::max({-signedArea(at(first), at(second), at(k), u, v),
                                      -signedArea(at(second), at(third), at(k), u, v),
                                      -signedArea(at(third), at(first), at(k), u, v)});
        if (gain > added) {
            added = gain;
            fourth = k;
        }
    }
    kept[0] = first;
    kept[1] = second;
    kept[2] = third;
    if (fourth < 0) return 3;
    kept[3] = fourth;
    return 4;
}

/// Face contact: the incident box's face most opposed to the reference face (axis refAxis,
/// side refSign of `ref`) clipped against it. `refIsA` says whether the reference box is
/// shape 0, which sets the normal's direction and the order of the points.
/// Returns the number of points added.
int addFaceContact(const BoxFrame& ref, int refAxis, double refSign, const BoxFrame& inc,
                   bool refIsA, uint32_t refFaceId, double margin, ContactManifold& out) {
    // The incident box in the reference box's frame.
    const Mat3 rel = ref.axes.transpose() * inc.axes;
    const Vec3 relCentre = ref.axes.transpose() * (inc.centre - ref.centre);

    // Incident face: the axis most parallel to the reference normal (first on near-ties),
    // its side facing the reference face.
    int incAxis = 0;
    for (int k = 1; k < 3; ++k) {
        if (std::abs(rel(refAxis, k)) > std::abs(rel(refAxis, incAxis)) + 1e-9) incAxis = k;
    }
    const double incSign = refSign * rel(refAxis, incAxis) > 0.0 ? -1.0 : 1.0;
    const int iu = (incAxis + 1) % 3;
    const int iv = (incAxis + 2) % 3;
    const Vec3 faceCentre = relCentre + (incSign * inc.half[incAxis]) * rel.col(incAxis);
    const Vec3 du = inc.half[iu] * rel.col(iu);
    const Vec3 dv = inc.half[iv] * rel.col(iv);

    ClipPolygon polygon;
    polygon.push(faceCentre + du + dv, 0, 0);
    polygon.push(faceCentre - du + dv, 1, 1);
    polygon.push(faceCentre - du - dv, 2, 2);
    polygon.push(faceCentre + du - dv, 3, 3);

    // Clip against the reference face's side planes.
    const int ru = (refAxis + 1) % 3;
    const int rv = (refAxis + 2) % 3;
    const double slack = kClipSlack * std::max(ref.half[ru], ref.half[rv]);
    ClipPolygon scratch;
    clipPolygon(polygon, ru, 1.0, ref.half[ru] + slack, 0, scratch);
    clipPolygon(scratch, ru, -1.0, ref.half[ru] + slack, 1, polygon);
    clipPolygon(polygon, rv, 1.0, ref.half[rv] + slack, 2, scratch);
    clipPolygon(scratch, rv, -1.0, ref.half[rv] + slack, 3, polygon);

    // Points below the reference face plus margin.
    const double faceLevel = refSign * ref.half[refAxis];
    int candidates[8];
    double depth[8];
    int count = 0;
    for (int k = 0; k < polygon.count; ++k) {
        const double d = ref.half[refAxis] - refSign * polygon.vertices[k][refAxis];
        if (d >= -margin) {
            candidates[count] = k;
            depth[count] = d;
            ++count;
        }
    }
    int kept[4] = {0, 1, 2, 3};
    const int keptCount =
        count > 4 ? reduceToFour(polygon, depth, candidates, count, ru, rv, kept) : count;

    const Vec3 refNormal = refSign * ref.axes.col(refAxis);  // out of the reference face
    const Vec3 n = refIsA ? Vec3(-refNormal) : refNormal;    // from shape 1 towards shape 0
    const uint32_t incFaceId = static_cast<uint32_t>(2 * incAxis + (incSign > 0.0 ? 0 : 1));
    const int before = out.count;
    for (int k = 0; k < keptCount; ++k) {
        const int index = candidates[kept[k]];
        const Vec3& local = polygon.vertices[index];
        Vec3 onReference = local;
        onReference[refAxis] = faceLevel;
        // Within the slack (or rounding) the point may lie beyond the border: keep it on the face.
        onReference[ru] = std::clamp(onReference[ru], -ref.half[ru], ref.half[ru]);
        onReference[rv] = std::clamp(onReference[rv], -ref.half[rv], ref.half[rv]);
        const Vec3 incidentPoint = ref.centre + ref.axes * local;
        const Vec3 referencePoint = ref.centre + ref.axes * onReference;
        const uint32_t feature = (refFaceId << 12) | (incFaceId << 8) | polygon.vertexIds[index];
        if (refIsA) {
            addContact(out, referencePoint, incidentPoint, n, margin, feature);
        } else {
            addContact(out, incidentPoint, referencePoint, n, margin, feature);
        }
    }
    return out.count - before;
}

}  // namespace

void collideBoxBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                   ContactManifold& out) {
    const BoxFrame boxA{pa.position, pa.rotation.toRotationMatrix(), halfExtents(a)};
    const BoxFrame boxB{pb.position, pb.rotation.toRotationMatrix(), halfExtents(b)};
    const Vec3& ha = boxA.half;
    const Vec3& hb = boxB.half;
    // Everything in a's frame: r(i, j) = a_i · b_j, t = b's centre.
    const Mat3 r = boxA.axes.transpose() * boxB.axes;
    const Mat3 absR = r.cwiseAbs();
    const Vec3 t = boxA.axes.transpose() * (boxB.centre - boxA.centre);

    const double absoluteTolerance = kAbsoluteTolerance * std::max(ha.maxCoeff(), hb.maxCoeff());
    const auto beats = [&](double candidate, double current) {
        return candidate > current + kRelativeTolerance * std::abs(current) + absoluteTolerance;
    };

    // Face axes of a: separation = |t·a_i| − (a's extent + b's extent along a_i).
    int faceA = 0;
    double separationA = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double s = std::abs(t[i]) - ha[i] - hb.dot(absR.row(i));
        if (s > margin) return;
        if (i == 0 || beats(s, separationA)) {
            separationA = s;
            faceA = i;
        }
    }
    // Face axes of b.
    const Vec3 tB = r.transpose() * t;  // b's centre relative to a, in b's axes
    int faceB = 0;
    double separationB = 0.0;
    for (int j = 0; j < 3; ++j) {
        const double s = std::abs(tB[j]) - ha.dot(absR.col(j)) - hb[j];
        if (s > margin) return;
        if (j == 0 || beats(s, separationB)) {
            separationB = s;
            faceB = j;
        }
    }
    // Edge axes a_i × b_j, normalised. In a's axes a_i × b_j has two non-zero components,
    // −r(i2, j) at i1 and r(i1, j) at i2 (i1, i2 the next axes in cyclic order), so every
    // product below is written with those two alone: the sums are the full ones' bit for bit
    // (the third term is an exact zero) at two thirds of the arithmetic.
    int edge = -1;
    double separationEdge = 0.0;
    Vec3 edgeAxis = Vec3::Zero();
    for (int i = 0; i < 3; ++i) {
        const int i1 = (i + 1) % 3;
        const int i2 = (i + 2) % 3;
        for (int j = 0; j < 3; ++j) {
            const double axis1 = -r(i2, j);
            const double axis2 = r(i1, j);
            const double length = std::sqrt(axis1 * axis1 + axis2 * axis2);
            if (length < kEdgeParallelSine) continue;
            const double extentA = ha[i1] * std::abs(axis1) + ha[i2] * std::abs(axis2);
            double extentB = 0.0;  // hb · |rᵀ axis|
            for (int k = 0; k < 3; ++k) extentB += hb[k] * std::abs(r(i1, k) * axis1 + r(i2, k) * axis2);
            const double s = (std::abs(t[i1] * axis1 + t[i2] * axis2) - extentA - extentB) / length;
            if (s > margin) return;
            if (edge < 0 || beats(s, separationEdge)) {
                separationEdge = s;
                edge = 3 * i + j;
                edgeAxis = Vec3::Zero();
                edgeAxis[i1] = axis1 / length;
                edgeAxis[i2] = axis2 / length;
            }
        }
    }

    const bool useB = beats(separationB, separationA);
    const double separationFace = useB ? separationB : separationA;
    if (edge < 0 || !beats(separationEdge, separationFace)) {
        int added = 0;
        if (useB) {
            // b's face towards a: a's centre lies at −tB in b's axes.
            const double sign = tB[faceB] <= 0.0 ? 1.0 : -1.0;
            const uint32_t faceId = 6 + 2 * faceB + (sign > 0.0 ? 0 : 1);
            added = addFaceContact(boxB, faceB, sign, boxA, false, faceId, margin, out);
        } else {
            const double sign = t[faceA] >= 0.0 ? 1.0 : -1.0;
            const uint32_t faceId = 2 * faceA + (sign > 0.0 ? 0 : 1);
            added = addFaceContact(boxA, faceA, sign, boxB, true, faceId, margin, out);
        }
        // A face preferred over a slightly better edge axis can clip to nothing when the
        // contact is really between edges: fall back to the edges then.
        if (added > 0 || edge < 0) return;
    }

    // Edge-edge: the normal from b towards a, then each box's edge parallel to its axis that
    // lies furthest towards the other box.
    const int i = edge / 3;
    const int j = edge % 3;
    const Vec3 n = edgeAxis.dot(t) > 0.0 ? Vec3(-edgeAxis) : edgeAxis;
    Vec3 edgeA;
    for (int k = 0; k < 3; ++k)
        edgeA[k] = n[k] > 0.0 ? -ha[k] : ha[k];
    edgeA[i] = -ha[i];
    const Vec3 nInB = r.transpose() * n;
    Vec3 edgeBLocal;
    for (int k = 0; k < 3; ++k)
        edgeBLocal[k] = nInB[k] > 0.0 ? hb[k] : -hb[k];
    edgeBLocal[j] = -hb[j];
    const Vec3 edgeB = r * edgeBLocal + t;
    const Vec3 deltaA = (2.0 * ha[i]) * Vec3::Unit(i);
    const Vec3 deltaB = (2.0 * hb[j]) * r.col(j);
    double s = 0.0;
    double u = 0.0;
    closestParametersBetweenSegments(edgeA, deltaA, edgeB, deltaB, s, u);
    const Vec3 point0 = boxA.centre + boxA.axes * (edgeA + s * deltaA);
    const Vec3 point1 = boxA.centre + boxA.axes * (edgeB + u * deltaB);
    addContact(out, point0, point1, boxA.axes * n, margin,
               (1u << 16) | static_cast<uint32_t>(edge));
}

}  // namespace substep
