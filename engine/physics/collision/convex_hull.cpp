#include "physics/collision/convex_hull.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <unordered_map>

namespace substep {

namespace {

// The hull is built on the points mapped into [-1, 1]³ (centre and half extent), so that the
// tolerances below are relative and huge or tiny meshes behave like unit ones.

/// A point closer than this to a face's plane does not see the face (relative to half extent).
constexpr double kPlaneTolerance = 1e-10;
/// Hulls with more vertices than this find support points by hill climbing.
constexpr int kClimbAbove = 32;

/// Triangles within this of one plane become one polygonal face: well above the rounding of
/// meshes stored in single precision, so their flat sides stay flat.
constexpr double kMergeTolerance = 1e-6;

struct Triangle {
    std::array<int, 3> v{};
    Vec3 normal = Vec3::Zero();
    double offset = 0.0;
    double area = 0.0;
    std::vector<int> outside;  ///< points in front of this triangle, not yet on the hull
    bool alive = true;
    int visit = -1;        ///< the iteration that last classified it
    bool visible = false;  ///< its classification in that iteration
};

uint64_t edgeKey(int a, int b) {
    return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

class Quickhull {
  public:
    explicit Quickhull(const std::vector<Vec3>& points) : p_(points) {}

    /// False when the points span less than three dimensions.
    bool build() {
        if (!initialSimplex()) return false;
        for (std::size_t i = 0; i < tris_.size(); ++i) {
            if (tris_[i].alive && !tris_[i].outside.empty()) addPoint(static_cast<int>(i));
        }
        return true;
    }

    const std::vector<Triangle>& triangles() const { return tris_; }
    /// The triangle across the directed edge a -> b of a triangle (the one holding b -> a).
    int neighbour(int a, int b) const {
        const auto it = edges_.find(edgeKey(b, a));
        return it == edges_.end() ? -1 : it->second;
    }

  private:
    double distance(const Triangle& t, int point) const {
        return t.normal.dot(p_[point]) - t.offset;
    }

    int makeTriangle(int a, int b, int c) {
        Triangle t;
        t.v = {a, b, c};
        const Vec3 cross = (p_[b] - p_[a]).cross(p_[c] - p_[a]);
        const double length = cross.norm();
        t.area = 0.5 * length;
        // A sliver has no direction of its own; it sees no points and merges by distance.
        if (length > 0.0) t.normal = cross / length;
        t.offset = t.normal.dot((p_[a] + p_[b] + p_[c]) / 3.0);
        tris_.push_back(std::move(t));
        const int index = static_cast<int>(tris_.size()) - 1;
        edges_[edgeKey(a, b)] = index;
        edges_[edgeKey(b, c)] = index;
        edges_[edgeKey(c, a)] = index;
        return index;
    }

    /// Puts `point` into the outside set of the triangle among `candidates` it is farthest in
    /// front of; a point in front of none is inside the hull and dropped.
    void assign(int point, const std::vector<int>& candidates) {
        int best = -1;
        double bestDistance = kPlaneTolerance;
        for (int t : candidates) {
            const double d = distance(tris_[t], point);
            if (d > bestDistance) {
                bestDistance = d;
                best = t;
            }
        }
        if (best >= 0) tris_[best].outside.push_back(point);
    }

    bool initialSimplex() {
        const int n = static_cast<int>(p_.size());
        if (n < 4) return false;
        // The two farthest apart of the six axis extremes.
        std::array<int, 6> extremes{};
        extremes.fill(0);
        for (int i = 1; i < n; ++i) {
            for (int axis = 0; axis < 3; ++axis) {
                if (p_[i][axis] < p_[extremes[2 * axis]][axis]) extremes[2 * axis] = i;
                if (p_[i][axis] > p_[extremes[2 * axis + 1]][axis]) extremes[2 * axis + 1] = i;
            }
        }
        int i0 = 0, i1 = 0;
        double best = 0.0;
        for (int a : extremes) {
            for (int b : extremes) {
                const double d = (p_[a] - p_[b]).squaredNorm();
                if (d > best) best = d, i0 = a, i1 = b;
            }
        }
        if (best <= kPlaneTolerance * kPlaneTolerance) return false;  // all coincident

        // The point farthest from the line, then the one farthest from the plane.
        const Vec3 axis = (p_[i1] - p_[i0]).normalized();
        int i2 = -1;
        best = kPlaneTolerance;
        for (int i = 0; i < n; ++i) {
            const double d = (p_[i] - p_[i0]).cross(axis).norm();
            if (d > best) best = d, i2 = i;
        }
        if (i2 < 0) return false;  // collinear
        const Vec3 normal = (p_[i1] - p_[i0]).cross(p_[i2] - p_[i0]).normalized();
        int i3 = -1;
        best = kPlaneTolerance;
        for (int i = 0; i < n; ++i) {
            const double d = std::abs(normal.dot(p_[i] - p_[i0]));
            if (d > best) best = d, i3 = i;
        }
        if (i3 < 0) return false;  // coplanar

        // Wind (i0, i1, i2) so that i3 lies behind it; the other three faces share its edges.
        if (normal.dot(p_[i3] - p_[i0]) > 0.0) std::swap(i1, i2);
        const std::vector<int> faces = {makeTriangle(i0, i1, i2), makeTriangle(i0, i3, i1),
                                        makeTriangle(i1, i3, i2), makeTriangle(i2, i3, i0)};
        for (int i = 0; i < n; ++i) {
            if (i != i0 && i != i1 && i != i2 && i != i3) assign(i, faces);
        }
        return true;
    }

    /// Adds the farthest outside point of triangle `start`: removes every triangle it sees and
    /// fans new triangles from it to the horizon.
    void addPoint(int start) {
        ++iteration_;
        int eye = -1;
        double farthest = -1.0;
        for (int point : tris_[start].outside) {
            const double d = distance(tris_[start], point);
            if (d > farthest) farthest = d, eye = point;
        }

        // The visible triangles form a connected patch: grow it from `start` across edges.
        visible_.clear();
        horizon_.clear();
        tris_[start].visit = iteration_;
        tris_[start].visible = true;
        visible_.push_back(start);
        for (std::size_t k = 0; k < visible_.size(); ++k) {
            const Triangle& t = tris_[visible_[k]];
            for (int e = 0; e < 3; ++e) {
                const int a = t.v[e], b = t.v[(e + 1) % 3];
                const int other = neighbour(a, b);
                if (other < 0) continue;
                Triangle& o = tris_[other];
                if (o.visit != iteration_) {
                    o.visit = iteration_;
                    o.visible = distance(o, eye) > kPlaneTolerance;
                    if (o.visible) visible_.push_back(other);
                }
                if (!o.visible) horizon_.push_back({a, b});
            }
        }

        // Retire the visible triangles and keep their points for the new ones.
        orphans_.clear();
        for (int index : visible_) {
            Triangle& t = tris_[index];
            t.alive = false;
            for (int e = 0; e < 3; ++e) {
                const auto it = edges_.find(edgeKey(t.v[e], t.v[(e + 1) % 3]));
                if (it != edges_.end() && it->second == index) edges_.erase(it);
            }
            for (int point : t.outside) {
                if (point != eye) orphans_.push_back(point);
            }
            t.outside.clear();
            t.outside.shrink_to_fit();
        }
        created_.clear();
        for (const auto& [a, b] : horizon_)
            created_.push_back(makeTriangle(a, b, eye));
        for (int point : orphans_)
            assign(point, created_);
    }

    const std::vector<Vec3>& p_;
    std::vector<Triangle> tris_;
    std::unordered_map<uint64_t, int> edges_;  ///< directed edge -> triangle holding it
    int iteration_ = 0;
    std::vector<int> visible_, orphans_, created_;
    std::vector<std::pair<int, int>> horizon_;
};

/// Counter-clockwise convex hull of 2D points (Andrew's monotone chain), collinear points
/// dropped; returns indices into `ids`.
std::vector<int> polygonHull(std::vector<std::pair<Eigen::Vector2d, int>> points) {
    std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
        return a.first.x() < b.first.x() ||
               (a.first.x() == b.first.x() && a.first.y() < b.first.y());
    });
    const auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b) {
        return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
    };
    std::vector<std::pair<Eigen::Vector2d, int>> chain(2 * points.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        while (k >= 2 && turn(chain[k - 2].first, chain[k - 1].first, points[i].first) <= 0)
            --k;
        chain[k++] = points[i];
    }
    for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && turn(chain[k - 2].first, chain[k - 1].first, points[i].first) <= 0)
            --k;
        chain[k++] = points[i];
    }
    std::vector<int> result;
    for (std::size_t i = 0; i + 1 < k; ++i)
        result.push_back(chain[i].second);
    return result;
}

ConvexHull degenerateHull(std::span<const Vec3> points) {
    ConvexHull hull;
    hull.vertices.assign(points.begin(), points.end());
    std::sort(hull.vertices.begin(), hull.vertices.end(), [](const Vec3& a, const Vec3& b) {
        return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    });
    hull.vertices.erase(std::unique(hull.vertices.begin(), hull.vertices.end()),
                        hull.vertices.end());
    for (const Vec3& v : hull.vertices) {
        hull.bounds.grow(v);
        hull.interiorPoint += v;
    }
    if (!hull.vertices.empty()) hull.interiorPoint /= static_cast<double>(hull.vertices.size());
    return hull;
}

}  // namespace

ConvexHull buildConvexHull(std::span<const Vec3> points) {
    Aabb box;
    for (const Vec3& p : points) {
        if (!p.allFinite()) throw std::invalid_argument("convex hull: a point is not finite");
        box.grow(p);
    }
    if (points.empty()) return {};

    // Map into [-1, 1]³ so that the tolerances are relative to the extent.
    const Vec3 center = box.center();
    const double half = 0.5 * box.extents().maxCoeff();
    if (!(half > 0.0) || !std::isfinite(half)) return degenerateHull(points);
    std::vector<Vec3> unit(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
        unit[i] = (points[i] - center) / half;

    Quickhull quickhull(unit);
    if (!quickhull.build()) return degenerateHull(points);
    const std::vector<Triangle>& tris = quickhull.triangles();

    // Merge neighbouring triangles that lie on one plane, grown from the largest ones so that
    // a gently curved surface is never folded into one face.
    std::vector<int> order;
    for (int i = 0; i < static_cast<int>(tris.size()); ++i) {
        if (tris[i].alive) order.push_back(i);
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return tris[a].area > tris[b].area; });
    std::vector<int> group(tris.size(), -1);
    std::vector<Vec3> groupNormal;
    int groupCount = 0;
    std::vector<int> stack;
    for (int seed : order) {
        if (group[seed] >= 0) continue;
        const Vec3 n = tris[seed].normal;
        const double d = tris[seed].offset;
        group[seed] = groupCount;
        stack.assign(1, seed);
        while (!stack.empty()) {
            const Triangle& t = tris[stack.back()];
            stack.pop_back();
            for (int e = 0; e < 3; ++e) {
                const int other = quickhull.neighbour(t.v[e], t.v[(e + 1) % 3]);
                if (other < 0 || group[other] >= 0) continue;
                const Triangle& o = tris[other];
                const bool onPlane = std::all_of(o.v.begin(), o.v.end(), [&](int v) {
                    return std::abs(n.dot(unit[v]) - d) <= kMergeTolerance;
                });
                if (onPlane && o.normal.dot(n) >= 0.0) {
                    group[other] = groupCount;
                    stack.push_back(other);
                }
            }
        }
        groupNormal.push_back(n);
        ++groupCount;
    }

    // Each group's polygon: the 2D hull of its vertices in its plane.
    std::vector<std::vector<int>> members(groupCount);
    for (int t : order) {
        for (int v : tris[t].v)
            members[group[t]].push_back(v);
    }
    ConvexHull hull;
    std::vector<int> newIndex(points.size(), -1);
    const auto vertexIndex = [&](int v) {
        if (newIndex[v] < 0) {
            newIndex[v] = static_cast<int>(hull.vertices.size());
            hull.vertices.push_back(points[v]);
        }
        return newIndex[v];
    };
    std::vector<int> faceOfGroup(groupCount, -1);
    for (int g = 0; g < groupCount; ++g) {
        std::vector<int>& ids = members[g];
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        const Vec3 n = groupNormal[g];
        const Vec3 u = anyPerpendicular(n);
        const Vec3 w = n.cross(u);
        std::vector<std::pair<Eigen::Vector2d, int>> flat;
        for (int v : ids)
            flat.push_back({Eigen::Vector2d(u.dot(unit[v]), w.dot(unit[v])), v});
        const std::vector<int> polygon = polygonHull(std::move(flat));
        if (polygon.size() < 3) continue;  // a sliver group: its neighbours cover it

        // Newell's normal of the polygon, then the plane pushed out to the farthest input point
        // so that every point is inside.
        Vec3 newell = Vec3::Zero();
        for (std::size_t i = 0; i < polygon.size(); ++i) {
            const Vec3& a = unit[polygon[i]];
            const Vec3& b = unit[polygon[(i + 1) % polygon.size()]];
            newell += (a - b).cross(a + b) * 0.5;
        }
        const Vec3 normal = newell.norm() > 0.0 ? Vec3(newell.normalized()) : n;
        double offset = -std::numeric_limits<double>::infinity();
        for (const Vec3& p : unit)
            offset = std::max(offset, normal.dot(p));

        HullFace face;
        face.normal = normal;
        face.offset = half * offset + normal.dot(center);
        face.firstVertex = static_cast<int>(hull.faceVertices.size());
        face.vertexCount = static_cast<int>(polygon.size());
        for (int v : polygon)
            hull.faceVertices.push_back(vertexIndex(v));
        faceOfGroup[g] = static_cast<int>(hull.faces.size());
        hull.faces.push_back(face);
    }

    // Edges between faces: the triangle edges whose two sides lie in different faces; collinear
    // pieces between the same two faces are joined into one edge spanning their extremes.
    std::unordered_map<uint64_t, int> edgeOfPair;
    std::vector<HullEdge> pieces;  // in input point indices until the extremes are known
    for (int t : order) {
        for (int e = 0; e < 3; ++e) {
            const int a = tris[t].v[e], b = tris[t].v[(e + 1) % 3];
            const int other = quickhull.neighbour(a, b);
            if (other < 0) continue;
            const int f0 = faceOfGroup[group[t]], f1 = faceOfGroup[group[other]];
            if (f0 < 0 || f1 < 0 || f0 >= f1) continue;  // each pair once, from its lower face
            const auto [it, added] =
                edgeOfPair.emplace(edgeKey(f0, f1), static_cast<int>(pieces.size()));
            if (added) {
                pieces.push_back({a, b, f0, f1});
                continue;
            }
            HullEdge& edge = pieces[it->second];
            const Vec3 start = unit[edge.vertex0];
            const Vec3 direction = unit[edge.vertex1] - start;
            for (int v : {a, b}) {
                const double s = direction.dot(unit[v] - start);
                if (s < 0.0)
                    edge.vertex0 = v;
                else if (s > direction.squaredNorm())
                    edge.vertex1 = v;
            }
        }
    }
    for (HullEdge& edge : pieces) {
        edge.vertex0 = vertexIndex(edge.vertex0);
        edge.vertex1 = vertexIndex(edge.vertex1);
        hull.edges.push_back(edge);
    }

    // Vertex neighbours along the face polygons, sorted and unique per vertex.
    std::vector<std::vector<int>> adjacent(hull.vertices.size());
    for (const HullFace& face : hull.faces) {
        for (int i = 0; i < face.vertexCount; ++i) {
            const int a = hull.faceVertices[face.firstVertex + i];
            const int b = hull.faceVertices[face.firstVertex + (i + 1) % face.vertexCount];
            adjacent[a].push_back(b);
            adjacent[b].push_back(a);
        }
    }
    for (const HullEdge& e : hull.edges) {
        adjacent[e.vertex0].push_back(e.vertex1);
        adjacent[e.vertex1].push_back(e.vertex0);
    }
    hull.neighbourStart.push_back(0);
    for (std::vector<int>& list : adjacent) {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
        hull.neighbours.insert(hull.neighbours.end(), list.begin(), list.end());
        hull.neighbourStart.push_back(static_cast<int>(hull.neighbours.size()));
    }

    for (int x = -1; x <= 1; ++x) {
        for (int y = -1; y <= 1; ++y) {
            for (int z = -1; z <= 1; ++z) {
                if (x == 0 && y == 0 && z == 0) continue;
                int best = 0;
                for (int i = 1; i < static_cast<int>(hull.vertices.size()); ++i) {
                    if (hull.vertices[i].dot(Vec3(x, y, z)) >
                        hull.vertices[best].dot(Vec3(x, y, z)))
                        best = i;
                }
                hull.climbSeeds.push_back(best);
            }
        }
    }
    std::sort(hull.climbSeeds.begin(), hull.climbSeeds.end());
    hull.climbSeeds.erase(std::unique(hull.climbSeeds.begin(), hull.climbSeeds.end()),
                          hull.climbSeeds.end());
    for (const HullFace& face : hull.faces) {
        Aabb faceBox;
        for (int i = 0; i < face.vertexCount; ++i)
            faceBox.grow(hull.faceVertex(face, i));
        hull.faceBounds.push_back(faceBox);
    }
    for (const Vec3& v : hull.vertices) {
        hull.bounds.grow(v);
        hull.interiorPoint += v;
    }
    hull.interiorPoint /= static_cast<double>(hull.vertices.size());
    return hull;
}

int ConvexHull::supportIndexOf(const std::vector<Vec3>& points, const Vec3& direction,
                               int start) const {
    const int n = static_cast<int>(points.size());
    if (n <= kClimbAbove || neighbourStart.size() != points.size() + 1) {
        int best = -1;
        double bestDot = -std::numeric_limits<double>::infinity();
        for (int i = 0; i < n; ++i) {
            const double d = points[i].dot(direction);
            if (d > bestDot) bestDot = d, best = i;
        }
        return best;
    }
    // A linear function's local maximum over a convex polytope's vertex graph is global: step
    // to a better neighbour until there is none, from the best of the seeds and `start`.
    int current = start >= 0 && start < n ? start : 0;
    double currentDot = points[current].dot(direction);
    for (int seed : climbSeeds) {
        const double d = points[seed].dot(direction);
        if (d > currentDot) currentDot = d, current = seed;
    }
    for (bool moved = true; moved;) {
        moved = false;
        for (int k = neighbourStart[current]; k < neighbourStart[current + 1]; ++k) {
            const double d = points[neighbours[k]].dot(direction);
            if (d > currentDot) {
                currentDot = d;
                current = neighbours[k];
                moved = true;
            }
        }
    }
    return current;
}

HullClosestPoint ConvexHull::closestPoint(const Vec3& p) const {
    if (faces.empty()) return {p, 0.0, -1, false};  // not solid: no surface to be near
    // The face the point is farthest in front of decides inside or out.
    int deepest = 0;
    double largest = -std::numeric_limits<double>::infinity();
    for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
        const double s = faces[f].normal.dot(p) - faces[f].offset;
        if (s > largest) largest = s, deepest = f;
    }
    if (largest <= 0.0) {
        // Inside: the nearest face plane is the way out.
        return {p - largest * faces[deepest].normal, largest, deepest, true};
    }
    // The farthest plane bounds the distance from below: when the point projects into that
    // face's polygon, the bound is met and the projection is the closest point.
    {
        const HullFace& face = faces[deepest];
        const Vec3 q = p - largest * face.normal;
        bool inside = true;
        for (int i = 0; i < face.vertexCount && inside; ++i) {
            const Vec3& a = faceVertex(face, i);
            inside =
                (faceVertex(face, (i + 1) % face.vertexCount) - a).cross(q - a).dot(face.normal) >=
                0.0;
        }
        if (inside) return {q, largest, deepest, true};
    }

    // Outside: the closest point lies on a face that faces the point. The nearest vertex
    // bounds the distance from above, so faces whose bounds lie farther are skipped.
    HullClosestPoint best{p, std::numeric_limits<double>::infinity(), deepest, true};
    double bestSquared = std::numeric_limits<double>::infinity();
    for (const Vec3& v : vertices)
        bestSquared = std::min(bestSquared, (v - p).squaredNorm());
    bestSquared *= 1.0 + 1e-12;  // so that the face holding that vertex is still visited
    for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
        const HullFace& face = faces[f];
        const double s = face.normal.dot(p) - face.offset;
        if (s <= 0.0 || s * s >= bestSquared) continue;
        const Vec3 gap = (faceBounds[f].min - p).cwiseMax(p - faceBounds[f].max).cwiseMax(0.0);
        if (gap.squaredNorm() >= bestSquared) continue;
        const Vec3 q = p - s * face.normal;
        bool inside = true;
        Vec3 nearest = q;
        double nearestSquared = std::numeric_limits<double>::infinity();
        for (int i = 0; i < face.vertexCount; ++i) {
            const Vec3& a = faceVertex(face, i);
            const Vec3& b = faceVertex(face, (i + 1) % face.vertexCount);
            const Vec3 edge = b - a;
            if (edge.cross(q - a).dot(face.normal) >= 0.0) continue;
            inside = false;
            const double length2 = edge.squaredNorm();
            const double t = length2 > 0.0 ? std::clamp(edge.dot(p - a) / length2, 0.0, 1.0) : 0.0;
            const Vec3 c = a + t * edge;
            const double d2 = (p - c).squaredNorm();
            if (d2 < nearestSquared) nearestSquared = d2, nearest = c;
        }
        const double d2 = inside ? s * s : nearestSquared;
        if (d2 < bestSquared) {
            bestSquared = d2;
            best = {inside ? q : nearest, 0.0, f, inside};
        }
    }
    best.signedDistance = std::sqrt(bestSquared);
    return best;
}

TriangleMesh hullTriangleMesh(const ConvexHull& hull) {
    TriangleMesh mesh;
    mesh.vertices = hull.vertices;
    for (const HullFace& face : hull.faces) {
        const int* polygon = &hull.faceVertices[face.firstVertex];
        for (int i = 1; i + 1 < face.vertexCount; ++i) {
            mesh.triangles.push_back({polygon[0], polygon[i], polygon[i + 1]});
        }
    }
    return mesh;
}

void setBoxHull(ConvexHull& hull, const Vec3& size) {
    static const ConvexHull unitBox = [] {
        std::vector<Vec3> corners;
        for (int i = 0; i < 8; ++i) {
            corners.emplace_back(i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0);
        }
        return buildConvexHull(corners);
    }();
    if (hull.faces.size() != unitBox.faces.size() ||
        hull.vertices.size() != unitBox.vertices.size()) {
        hull = unitBox;
    }
    const Vec3 half = 0.5 * size;
    for (std::size_t i = 0; i < hull.vertices.size(); ++i) {
        hull.vertices[i] = unitBox.vertices[i].cwiseProduct(half);
    }
    for (std::size_t f = 0; f < hull.faces.size(); ++f) {
        HullFace& face = hull.faces[f];
        face.offset = face.normal.dot(hull.faceVertex(face, 0));
        hull.faceBounds[f] = {};
        for (int i = 0; i < face.vertexCount; ++i)
            hull.faceBounds[f].grow(hull.faceVertex(face, i));
    }
    hull.bounds = {-half, half};
    hull.interiorPoint = Vec3::Zero();
}

}  // namespace substep
