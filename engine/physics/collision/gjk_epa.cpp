#include "physics/collision/gjk_epa.h"

#include <array>
#include <cmath>
#include <limits>

namespace substep {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// GJK stops when a new support point brings v closer by less than this fraction of |v|²
/// (van den Bergen's relative test); curved cores converge linearly, so the cap on iterations
/// ends the rest.
constexpr double kGjkRelativeTolerance = 1e-10;
constexpr int kMaxGjkIterations = 64;
/// Fresh starts allowed when a near-flat simplex stalls short of the distance.
constexpr int kMaxGjkRestarts = 2;
/// Cores nearer than this fraction of their size are treated as touching and handed to EPA,
/// which finds the normal from the polytope rather than from a vanishing v.
constexpr double kTouchingFraction = 1e-9;
/// A GJK that stopped with its distance this fraction of the size above its lower bound, and
/// the bound this close to zero, hands the pair to EPA.
constexpr double kStallFraction = 1e-6;
/// EPA stops when the support along the nearest face's normal lies within this fraction of the
/// size beyond the face.
constexpr double kEpaTolerance = 1e-9;
constexpr int kMaxEpaIterations = 128;
constexpr int kMaxEpaVertices = kMaxEpaIterations + 4;
constexpr int kMaxEpaFaces = 4 * kMaxEpaVertices;
constexpr int kMaxHorizonEdges = 3 * kMaxEpaFaces / 2;

/// A point of A − B and the two support points that made it.
struct MinkowskiPoint {
    Vec3 w = Vec3::Zero();
    Vec3 a = Vec3::Zero();
    Vec3 b = Vec3::Zero();
};

MinkowskiPoint supportOf(const ConvexSupport& a, const ConvexSupport& b, const Vec3& direction) {
    MinkowskiPoint p;
    p.a = a.support(direction);
    p.b = b.support(-direction);
    p.w = p.a - p.b;
    return p;
}

struct Simplex {
    std::array<MinkowskiPoint, 4> points;
    std::array<double, 4> weights{};  ///< barycentric weights of the closest point
    int count = 0;
};

/// Keeps the listed vertices of `s` with their weights.
void keep(Simplex& s, std::initializer_list<std::pair<int, double>> kept) {
    Simplex reduced;
    for (const auto& [index, weight] : kept) {
        reduced.points[reduced.count] = s.points[index];
        reduced.weights[reduced.count++] = weight;
    }
    s = reduced;
}

/// The closest point of segment (i, j) of `s` to the origin: weights and squared distance.
double segmentClosest(const Simplex& s, int i, int j, double& ti) {
    const Vec3& a = s.points[i].w;
    const Vec3 ab = s.points[j].w - a;
    const double ab2 = ab.squaredNorm();
    double t = ab2 > 0.0 ? -a.dot(ab) / ab2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    ti = t;
    return (a + t * ab).squaredNorm();
}

/// Reduces a two-point simplex to the feature nearest the origin.
void closestOnSegment(Simplex& s) {
    double t;
    segmentClosest(s, 0, 1, t);
    if (t <= 0.0) keep(s, {{0, 1.0}});
    else if (t >= 1.0) keep(s, {{1, 1.0}});
    else keep(s, {{0, 1.0 - t}, {1, t}});
}

/// Reduces the triangle (i, j, k) of `s` to the feature nearest the origin (Ericson's Voronoi
/// region walk, Real-Time Collision Detection 5.1.5, with p at the origin).
void closestOnTriangle(Simplex& s, int i, int j, int k) {
    const Vec3& a = s.points[i].w;
    const Vec3& b = s.points[j].w;
    const Vec3& c = s.points[k].w;
    const Vec3 ab = b - a, ac = c - a;
    const double d1 = -ab.dot(a), d2 = -ac.dot(a);
    if (d1 <= 0.0 && d2 <= 0.0) return keep(s, {{i, 1.0}});
    const double d3 = -ab.dot(b), d4 = -ac.dot(b);
    if (d3 >= 0.0 && d4 <= d3) return keep(s, {{j, 1.0}});
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        const double t = d1 / (d1 - d3);
        return keep(s, {{i, 1.0 - t}, {j, t}});
    }
    const double d5 = -ab.dot(c), d6 = -ac.dot(c);
    if (d6 >= 0.0 && d5 <= d6) return keep(s, {{k, 1.0}});
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        const double t = d2 / (d2 - d6);
        return keep(s, {{i, 1.0 - t}, {k, t}});
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
        const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return keep(s, {{j, 1.0 - t}, {k, t}});
    }
    const double sum = va + vb + vc;
    if (!(sum > 0.0)) {
        // A degenerate (zero-area) triangle: the nearest of its edges.
        double tij, tjk, tki;
        const double dij = segmentClosest(s, i, j, tij);
        const double djk = segmentClosest(s, j, k, tjk);
        const double dki = segmentClosest(s, k, i, tki);
        if (dij <= djk && dij <= dki) return keep(s, {{i, 1.0 - tij}, {j, tij}});
        if (djk <= dki) return keep(s, {{j, 1.0 - tjk}, {k, tjk}});
        return keep(s, {{k, 1.0 - tki}, {i, tki}});
    }
    keep(s, {{i, va / sum}, {j, vb / sum}, {k, vc / sum}});
}

Vec3 weightedPoint(const Simplex& s) {
    Vec3 v = Vec3::Zero();
    for (int i = 0; i < s.count; ++i)
        v += s.weights[i] * s.points[i].w;
    return v;
}

/// Reduces a tetrahedron to the face feature nearest the origin; returns false (keeping all
/// four) when the origin lies inside it.
bool closestOnTetrahedron(Simplex& s) {
    static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 3, 1, 2}, {0, 2, 3, 1}, {1, 3, 2, 0}};
    bool outside = false;
    for (const auto& f : kFaces) {
        const Vec3& p0 = s.points[f[0]].w;
        const Vec3 n = (s.points[f[1]].w - p0).cross(s.points[f[2]].w - p0);
        const double originSide = n.dot(-p0);
        const double oppositeSide = n.dot(s.points[f[3]].w - p0);
        // The origin on the other side of this face's plane from the fourth vertex (or a flat
        // tetrahedron): it is outside.
        if (!(originSide * oppositeSide > 0.0 && oppositeSide != 0.0)) outside = true;
    }
    if (!outside) return false;
    // The nearest of all four faces: the sign tests above are unreliable on a near-flat
    // tetrahedron, the distances are not.
    double best = kInfinity;
    Simplex bestSimplex;
    for (const auto& f : kFaces) {
        Simplex candidate = s;
        closestOnTriangle(candidate, f[0], f[1], f[2]);
        const double d = weightedPoint(candidate).squaredNorm();
        if (d < best) best = d, bestSimplex = candidate;
    }
    s = bestSimplex;
    return true;
}

/// Reduces `s` (with a new point last) to the smallest feature holding its point nearest the
/// origin. Returns false when the simplex (a tetrahedron) encloses the origin.
bool reduce(Simplex& s) {
    switch (s.count) {
        case 1:
            s.weights[0] = 1.0;
            return true;
        case 2:
            closestOnSegment(s);
            return true;
        case 3:
            closestOnTriangle(s, 0, 1, 2);
            return true;
        default:
            return closestOnTetrahedron(s);
    }
}

// ---------------------------------------------------------------------------------------------
// EPA

struct EpaFace {
    int v[3];
    Vec3 normal;
    double distance;
    bool alive;
};

struct EpaEdge {
    int from, to;
};

struct Polytope {
    std::array<MinkowskiPoint, kMaxEpaVertices> vertices;
    int vertexCount = 0;
    std::array<EpaFace, kMaxEpaFaces> faces;
    int faceCount = 0;
    Vec3 interior = Vec3::Zero();

    /// Adds face (i, j, k), wound so that its normal points away from the interior point.
    bool addFace(int i, int j, int k) {
        int slot = -1;
        for (int f = 0; f < faceCount; ++f) {
            if (!faces[f].alive) {
                slot = f;
                break;
            }
        }
        if (slot < 0) {
            if (faceCount == kMaxEpaFaces) return false;
            slot = faceCount++;
        }
        EpaFace& face = faces[slot];
        const Vec3& p0 = vertices[i].w;
        Vec3 n = (vertices[j].w - p0).cross(vertices[k].w - p0);
        if (n.dot(interior - p0) > 0.0) {
            n = -n;
            std::swap(j, k);
        }
        face.v[0] = i, face.v[1] = j, face.v[2] = k;
        const double length = n.norm();
        face.alive = true;
        if (length > 0.0) {
            face.normal = n / length;
            face.distance = face.normal.dot(p0);
        } else {
            face.normal = Vec3::UnitY();  // a sliver: kept for the closure, never chosen
            face.distance = kInfinity;
        }
        return true;
    }

    int nearestFace() const {
        int best = -1;
        double bestDistance = kInfinity;
        for (int f = 0; f < faceCount; ++f) {
            if (faces[f].alive && faces[f].distance < bestDistance) {
                bestDistance = faces[f].distance;
                best = f;
            }
        }
        return best;
    }
};

/// Grows the GJK simplex (which holds the origin, possibly on its boundary) to a tetrahedron of
/// non-zero volume. Returns false when A − B is flat (it has no volume to grow into).
bool growToTetrahedron(const ConvexSupport& a, const ConvexSupport& b, Simplex& s, double eps) {
    static const Vec3 kAxes[6] = {Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(),
                                  -Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ()};
    if (s.count == 0) s.points[s.count++] = supportOf(a, b, Vec3::UnitX());
    if (s.count == 1) {
        for (const Vec3& axis : kAxes) {
            const MinkowskiPoint p = supportOf(a, b, axis);
            if ((p.w - s.points[0].w).norm() > eps) {
                s.points[s.count++] = p;
                break;
            }
        }
        if (s.count == 1) return false;
    }
    if (s.count == 2) {
        const Vec3 d = (s.points[1].w - s.points[0].w).normalized();
        const Vec3 e = anyPerpendicular(d);
        const Vec3 f = d.cross(e);
        for (int k = 0; k < 6 && s.count == 2; ++k) {
            const double angle = k * M_PI / 3.0;
            const MinkowskiPoint p = supportOf(a, b, std::cos(angle) * e + std::sin(angle) * f);
            if ((p.w - s.points[0].w).cross(d).norm() > eps) s.points[s.count++] = p;
        }
        if (s.count == 2) return false;
    }
    if (s.count == 3) {
        const Vec3 n = (s.points[1].w - s.points[0].w)
                           .cross(s.points[2].w - s.points[0].w)
                           .normalized();
        MinkowskiPoint p = supportOf(a, b, n);
        if (std::abs((p.w - s.points[0].w).dot(n)) <= eps) p = supportOf(a, b, -n);
        if (std::abs((p.w - s.points[0].w).dot(n)) <= eps) return false;
        s.points[s.count++] = p;
    }
    return true;
}

/// EPA from a tetrahedron holding the origin: fills the deepest pair into `result`.
void expandPolytope(const ConvexSupport& a, const ConvexSupport& b, const Simplex& s,
                    double tolerance, ConvexDistance& result) {
    Polytope poly;
    for (int i = 0; i < 4; ++i) {
        poly.vertices[i] = s.points[i];
        poly.interior += 0.25 * s.points[i].w;
    }
    poly.vertexCount = 4;
    poly.addFace(0, 1, 2);
    poly.addFace(0, 3, 1);
    poly.addFace(0, 2, 3);
    poly.addFace(1, 3, 2);

    std::array<EpaEdge, kMaxHorizonEdges> horizon;
    for (int iteration = 0; iteration < kMaxEpaIterations; ++iteration) {
        const int nearest = poly.nearestFace();
        if (nearest < 0) break;
        const EpaFace& face = poly.faces[nearest];
        const MinkowskiPoint p = supportOf(a, b, face.normal);
        if (p.w.dot(face.normal) - face.distance <= tolerance) break;
        if (poly.vertexCount == kMaxEpaVertices) break;
        const int added = poly.vertexCount++;
        poly.vertices[added] = p;

        // Remove every face the new point sees; the edges they do not share form the horizon.
        int edgeCount = 0;
        bool overflow = false;
        for (int f = 0; f < poly.faceCount; ++f) {
            EpaFace& g = poly.faces[f];
            if (!g.alive) continue;
            const Vec3& g0 = poly.vertices[g.v[0]].w;
            // Slivers (no normal) stay: the faces built on the horizon close the polytope.
            const bool visible = g.distance != kInfinity && g.normal.dot(p.w - g0) > 0.0;
            if (!visible) continue;
            g.alive = false;
            for (int e = 0; e < 3; ++e) {
                const int from = g.v[e], to = g.v[(e + 1) % 3];
                int shared = -1;
                for (int k = 0; k < edgeCount; ++k) {
                    if (horizon[k].from == to && horizon[k].to == from) {
                        shared = k;
                        break;
                    }
                }
                if (shared >= 0) horizon[shared] = horizon[--edgeCount];
                else if (edgeCount < kMaxHorizonEdges) horizon[edgeCount++] = {from, to};
                else overflow = true;
            }
        }
        if (overflow) break;
        bool ok = true;
        for (int k = 0; k < edgeCount && ok; ++k)
            ok = poly.addFace(horizon[k].from, horizon[k].to, added);
        if (!ok) break;
    }

    const int nearest = poly.nearestFace();
    if (nearest < 0) return;
    const EpaFace& face = poly.faces[nearest];
    // The origin's projection onto the face, in barycentric weights of its three vertices.
    const MinkowskiPoint& p0 = poly.vertices[face.v[0]];
    const MinkowskiPoint& p1 = poly.vertices[face.v[1]];
    const MinkowskiPoint& p2 = poly.vertices[face.v[2]];
    const Vec3 projection = face.distance * face.normal;
    const Vec3 e1 = p1.w - p0.w, e2 = p2.w - p0.w, q = projection - p0.w;
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
    const double q1 = q.dot(e1), q2 = q.dot(e2);
    const double denominator = d11 * d22 - d12 * d12;
    double u = 0.0, v = 0.0;
    if (denominator > 0.0) {
        u = (d22 * q1 - d12 * q2) / denominator;
        v = (d11 * q2 - d12 * q1) / denominator;
    }
    result.pointA = p0.a + u * (p1.a - p0.a) + v * (p2.a - p0.a);
    result.pointB = p0.b + u * (p1.b - p0.b) + v * (p2.b - p0.b);
    result.normal = -face.normal;
    // The face's distance is a lower bound of the depth along its normal (the polytope lies
    // inside A − B; for curved cores it may end short of the surface); the support along the
    // normal is the depth there. B's point moves along the normal to match it.
    const double depth = std::max(face.distance, supportOf(a, b, face.normal).w.dot(face.normal));
    result.pointB -= (depth - face.distance) * face.normal;
    result.separation = -depth;
}

}  // namespace

ConvexDistance convexDistance(const ConvexSupport& a, const ConvexSupport& b, double cutoff) {
    ConvexDistance result;
    const double scale = a.size() + b.size() + a.radius + b.radius;
    const double touching = kTouchingFraction * scale;

    Simplex s;
    Vec3 v = a.centre - b.centre;
    if (v.squaredNorm() <= touching * touching) v = Vec3::UnitX();
    double previous = kInfinity;
    double lowerBound = -kInfinity;  // of the distance, from the last support query
    bool overlap = false;
    int restarts = 0;
    for (int iteration = 0; iteration < kMaxGjkIterations; ++iteration) {
        const double vv = v.squaredNorm();
        if (vv <= touching * touching) {
            overlap = true;
            break;
        }
        const MinkowskiPoint p = supportOf(a, b, -v);
        const double vw = v.dot(p.w);
        // A lower bound on the distance (vw / |v|) beyond the cut-off: no contact.
        if (vw > 0.0 && vw * vw > cutoff * cutoff * vv) {
            result.beyondCutoff = true;
            return result;
        }
        lowerBound = vw / std::sqrt(vv);
        if (vv - vw <= kGjkRelativeTolerance * vv) break;
        bool repeated = false;
        for (int i = 0; i < s.count; ++i)
            repeated = repeated || s.points[i].w == p.w;
        if (repeated) break;
        const Simplex before = s;
        s.points[s.count++] = p;
        if (!reduce(s)) {
            overlap = true;
            break;
        }
        const Vec3 next = weightedPoint(s);
        const double distance2 = next.squaredNorm();
        if (distance2 >= previous) {
            // No progress (a near-flat simplex where rounding has the last word): keep the
            // closest simplex found, or, while the bound says the distance is clearly smaller,
            // start a fresh simplex from this support point.
            s = before;
            if (restarts < kMaxGjkRestarts &&
                std::sqrt(previous) - lowerBound > kStallFraction * scale) {
                ++restarts;
                s.count = 0;
                s.points[s.count++] = p;
                s.weights[0] = 1.0;
                v = p.w;
                previous = v.squaredNorm();
                continue;
            }
            break;
        }
        v = next;
        previous = distance2;
    }

    if (!overlap) {
        Vec3 pa = Vec3::Zero(), pb = Vec3::Zero();
        for (int i = 0; i < s.count; ++i) {
            pa += s.weights[i] * s.points[i].a;
            pb += s.weights[i] * s.points[i].b;
        }
        const double distance = (pa - pb).norm();
        // Unconverged that close (a near-flat simplex stalled): the polytope decides instead.
        const bool stalled = distance - lowerBound > kStallFraction * scale &&
                             lowerBound < kStallFraction * scale;
        if (distance > touching && !stalled) {
            result.pointA = pa;
            result.pointB = pb;
            result.normal = (pa - pb) / distance;
            result.separation = distance;
            return result;
        }
    }

    // Touching or overlapping: the polytope's nearest face gives depth and normal.
    if (s.count == 4 && !overlap) s.count = 3;  // a separated tetrahedron cannot happen; guard
    if (!growToTetrahedron(a, b, s, touching)) {
        // A − B is flat (a point against a triangle in its plane): touching along the flat
        // direction, the normal from B's centre towards A's.
        Vec3 pa = s.count > 0 ? s.points[0].a : a.centre;
        Vec3 pb = s.count > 0 ? s.points[0].b : b.centre;
        const Vec3 d = a.centre - b.centre;
        result.pointA = pa;
        result.pointB = pb;
        result.normal = d.norm() > kDirectionEpsilon ? Vec3(d.normalized()) : Vec3(Vec3::UnitY());
        result.separation = 0.0;
        return result;
    }
    result.pointA = s.points[0].a;
    result.pointB = s.points[0].b;
    result.normal = Vec3::UnitY();
    result.separation = 0.0;
    expandPolytope(a, b, s, kEpaTolerance * scale, result);
    return result;
}

}  // namespace substep
