#pragma once
/// The convex hull of a point set (quickhull in 3D) as collision geometry: polygonal faces with
/// their planes (coplanar triangles merged), the edges between faces with both neighbours (for
/// the Gauss-map pruning of edge pairs in the separating-axis test), and the vertices.

#include "physics/collision/aabb.h"
#include "physics/collision/shape.h"
#include "physics/math.h"

#include <span>
#include <vector>

namespace substep {

/// One face of a hull: a convex polygon and its plane n·x = offset (n unit, pointing outwards).
struct HullFace {
    Vec3 normal = Vec3::UnitY();
    double offset = 0.0;
    int firstVertex = 0;  ///< into ConvexHull::faceVertices
    int vertexCount = 0;  ///< polygon vertices, counter-clockwise seen from outside
};

/// An edge between two faces (the arc between their normals on the Gauss map).
struct HullEdge {
    int vertex0 = 0;
    int vertex1 = 0;
    int face0 = 0;
    int face1 = 0;
};

/// The closest point of a hull's surface to a query point.
struct HullClosestPoint {
    Vec3 point = Vec3::Zero();   ///< on the hull's surface
    double signedDistance = 0;   ///< > 0 outside, < 0 inside (depth below the nearest face)
    int face = -1;               ///< the face the point lies on (any face of its edge/vertex)
    bool onFaceInterior = true;  ///< the point is inside the face polygon, not on its boundary
};

/// A convex polyhedron in its own frame. A hull of degenerate input (fewer than 4 points not
/// all in one plane) is not solid: it keeps the distinct input points and has no faces.
struct ConvexHull {
    std::vector<Vec3> vertices;
    std::vector<HullFace> faces;
    std::vector<int> faceVertices;  ///< polygon index lists of all faces, back to back
    std::vector<HullEdge> edges;
    std::vector<Aabb> faceBounds;  ///< per face, the bounds of its polygon
    /// Neighbours of vertex i along face polygons: neighbours[neighbourStart[i] ..
    /// neighbourStart[i + 1]) (for the hill-climbing support search of large hulls).
    std::vector<int> neighbourStart;
    std::vector<int> neighbours;
    /// Starting vertices for the climb: the extremes along 26 fixed directions.
    std::vector<int> climbSeeds;
    Vec3 interiorPoint = Vec3::Zero();  ///< the vertex mean: strictly inside a solid hull
    Aabb bounds;

    /// True when the hull encloses volume (has faces).
    bool isSolid() const { return !faces.empty(); }
    /// Vertex i of face f's polygon.
    const Vec3& faceVertex(const HullFace& face, int i) const {
        return vertices[faceVertices[face.firstVertex + i]];
    }
    /// Index of the vertex farthest along `direction` (need not be unit); -1 for an empty hull.
    /// Large hulls climb from `start` (any vertex; the previous answer makes it quick).
    int supportIndex(const Vec3& direction, int start = 0) const {
        return supportIndexOf(vertices, direction, start);
    }
    /// The same search over `points`, this hull's vertices moved rigidly (same topology).
    int supportIndexOf(const std::vector<Vec3>& points, const Vec3& direction, int start) const;
    /// The vertex farthest along `direction`.
    const Vec3& support(const Vec3& direction) const { return vertices[supportIndex(direction)]; }
    /// The closest surface point to `p` (both in the hull's frame); a hull that is not solid
    /// returns p itself with face -1.
    HullClosestPoint closestPoint(const Vec3& p) const;
};

/// Quickhull of `points` (Barber, Dobkin and Huhdanpaa 1996) with a tolerance relative to the
/// points' extent; faces whose triangles lie within that tolerance of one plane are merged into
/// one polygon. Hull vertices are input points. Throws std::invalid_argument for non-finite
/// coordinates; coplanar, collinear, coincident or too few points give a hull that is not solid.
ConvexHull buildConvexHull(std::span<const Vec3> points);

/// The hull's faces fanned into triangles (counter-clockwise from outside), e.g. for its mass
/// properties.
TriangleMesh hullTriangleMesh(const ConvexHull& hull);

/// A box of full extents `size` as a hull (faces ±x, ±y, ±z); `hull` is reused without
/// allocating once it has held a box.
void setBoxHull(ConvexHull& hull, const Vec3& size);

}  // namespace substep
