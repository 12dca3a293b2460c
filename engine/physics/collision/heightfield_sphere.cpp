#include "physics/collision/heightfield_sphere.h"

#include "physics/collision/contact_buffer.h"
#include "physics/collision/heightfield_turns.h"
#include "physics/collision/triangle_contact.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace substep {

namespace {

/// Two contacts closer than this fraction of the sphere's radius are one (collide_mesh.cpp's
/// value for spheres on meshes).
constexpr double kMergeFraction = 0.01;

/// More cells than this under a bound's reach take the field's highest sample instead of their
/// planes (a fast particle over a fine grid).
constexpr int kMostBoundCells = 64;

/// std::floor(q) as a comparison: the baseline x86-64 the engine builds for has no rounding
/// instruction, and the library call cost as much as the rest of a cell's lookup.
double floorOf(double q) {
    if (!(std::abs(q) < 1e15)) return std::floor(q);  // also NaN
    const double truncated = static_cast<double>(static_cast<int64_t>(q));
    return truncated > q ? truncated - 1.0 : truncated;
}

/// floor(t / cell) as forTrianglesIn computes it, by a multiplication where the quotient is not
/// within 1e-9 of a whole number (a product and a quotient differ by a few ulps at most).
double cellIndex(double t, double cell, double inverseCell) {
    const double q = t * inverseCell;
    const double k = floorOf(q);
    if (q - k > 1e-9 && k + 1.0 - q > 1e-9) return k;
    return std::floor(t / cell);
}

/// The cells [first, last] along one axis that the interval [lo, hi] reaches, as
/// HeightfieldData::forTrianglesIn finds them; false where it misses the field's `cells` (or is
/// NaN).
[[gnu::always_inline]] inline bool cellRange(double lo, double hi, double origin, double cell, double inverseCell,
                                             int cells, int& first, int& last) {
    const double a = cellIndex(lo - origin, cell, inverseCell);
    const double b = cellIndex(hi - origin, cell, inverseCell);
    if (!(b >= 0.0) || !(a <= cells - 1)) return false;
    first = static_cast<int>(std::max(a, 0.0));
    last = static_cast<int>(std::min(b, static_cast<double>(cells - 1)));
    return true;
}

/// cellRange(x − reach, x + reach, ...), both ends' cell indices at once in SSE2 lanes where
/// their quotients lie within ±1e9 (their truncation to 32 bits is floorOf's) and clear of whole
/// numbers by cellIndex's 1e-9; else cellRange itself. The same operations on the same values
/// (x − reach is x + (−reach) in IEEE arithmetic), so the same cells.
[[gnu::always_inline]] inline bool cellsReached(double x, double reach, double origin, double cell, double inverseCell,
                                                int cells, int& first, int& last) {
#if defined(__SSE2__)
    const __m128d one = _mm_set1_pd(1.0), tiny = _mm_set1_pd(1e-9), limit = _mm_set1_pd(1e9);
    const __m128d ends = _mm_add_pd(_mm_set1_pd(x), _mm_set_pd(reach, -reach));  // x − reach, x + reach
    const __m128d q = _mm_mul_pd(_mm_sub_pd(ends, _mm_set1_pd(origin)), _mm_set1_pd(inverseCell));
    const __m128d small = _mm_and_pd(_mm_cmplt_pd(q, limit), _mm_cmpgt_pd(q, _mm_sub_pd(_mm_setzero_pd(), limit)));
    const __m128d truncated = _mm_cvtepi32_pd(_mm_cvttpd_epi32(q));
    const __m128d k = _mm_sub_pd(truncated, _mm_and_pd(_mm_cmpgt_pd(truncated, q), one));  // floorOf
    const __m128d clear =
        _mm_and_pd(_mm_cmpgt_pd(_mm_sub_pd(q, k), tiny), _mm_cmpgt_pd(_mm_sub_pd(_mm_add_pd(k, one), q), tiny));
    if (_mm_movemask_pd(_mm_and_pd(small, clear)) == 3) {
        const double a = _mm_cvtsd_f64(k), b = _mm_cvtsd_f64(_mm_unpackhi_pd(k, k));
        if (!(b >= 0.0) || !(a <= cells - 1)) return false;
        first = static_cast<int>(std::max(a, 0.0));
        last = static_cast<int>(std::min(b, static_cast<double>(cells - 1)));
        return true;
    }
#endif
    return cellRange(x - reach, x + reach, origin, cell, inverseCell, cells, first, last);
}

/// One cell's corners: x and z of its sides, and its four heights (h_ij at x_i, z_j).
struct CellCorners {
    double x0, x1, z0, z1;
    double h00, h10, h01, h11;
    double highest() const { return std::max({h00, h10, h01, h11}); }
};

/// visit(i, j, corners) for every cell of [i0, i1] x [j0, j1], row by row.
template <class Visit>
void forEachCell(const HeightfieldGrid& grid, int i0, int i1, int j0, int j1, Visit&& visit) {
    const int columns = grid.field->columns;
    const double* heights = grid.field->heights.data();
    for (int j = j0; j <= j1; ++j) {
        const double z0 = grid.originZ + j * grid.cellZ, z1 = grid.originZ + (j + 1) * grid.cellZ;
        for (int i = i0; i <= i1; ++i) {
            visit(i, j,
                  CellCorners{.x0 = grid.originX + i * grid.cellX,
                              .x1 = grid.originX + (i + 1) * grid.cellX,
                              .z0 = z0,
                              .z1 = z1,
                              .h00 = heights[j * columns + i],
                              .h10 = heights[j * columns + i + 1],
                              .h01 = heights[(j + 1) * columns + i],
                              .h11 = heights[(j + 1) * columns + i + 1]});
        }
    }
}

/// Whether addSphereTriangleContacts adds nothing for a sphere whose foot on a triangle's plane
/// lies beside the triangle. Its closest point then lies on an edge whose line the foot is
/// beyond, or on an end of one, at least the foot's distance past that line away (measured in
/// x–z, which only shortens distances); where those features are inactive, or the centre is
/// behind the plane, the function keeps a face-normal point only within kInactiveSideways r
/// sideways of the foot. `inside`: the foot's signed x–z distances inside the triangle's edge
/// lines (edge k from corner k to corner k + 1), none above the true one where negative;
/// `slack`: far above their rounding and closestOnTriangle's.
bool addsNothingBeside(const double (&inside)[3], uint8_t activeFeatures, double height, double r, double slack) {
    const double limit = kInactiveSideways * r * (1.0 + 1e-6) + slack;
    unsigned features = 0;
    bool beyondLimit = false;
    for (int k = 0; k < 3; ++k) {
        if (inside[k] > slack) continue;  // clearly inside this line: its edge is not the closest
        beyondLimit = beyondLimit || -inside[k] > limit;
        features |= (kEdgeActive0 << k) | (kVertexActive0 << k) | (kVertexActive0 << (k + 1) % 3);
    }
    return beyondLimit && (height <= 0.0 || (activeFeatures & features) == 0);
}

/// One query's sphere (centre c in the field's frame) and the constants its triangles share.
struct SphereQuery {
    Vec3 c;
    double r, margin, reach;
    double clearly;  ///< reach² with a relative slack of 1e-6, far above the rounding
    /// How far inside a triangle's sides a foot is clearly over its face: far above the rounding
    /// of the foot and of closestOnTriangle's regions, far below any cell.
    double inset;

    SphereQuery(const HeightfieldGrid& grid, const Vec3& centre, double radius, double margin_)
        : c(centre), r(radius), margin(margin_), reach(radius + margin_), clearly(reach * reach * (1.0 + 1e-6)),
          inset(1e-9 * (grid.cellX + grid.cellZ) + 1e-12 * centre.cwiseAbs().maxCoeff()) {}
};

/// What addSphereTriangleContacts does with one of a cell's triangles, told without calling it.
enum class TriangleOutcome : uint8_t {
    Nothing,    ///< adds nothing
    FacePoint,  ///< adds the face-normal point (addSphereFaceNormalContact) and nothing else
    Call,       ///< anything: call it
};

/// The unit normal of triangle `half` of `cell` as HeightfieldData::triangle computes it (or as
/// kept), into `normal`; false where the sphere is clearly beyond the triangle's plane (squared,
/// with `clearly`'s slack), which it then leaves without normalising.
[[gnu::always_inline]] inline bool triangleNormal(const SphereQuery& s, const CellCorners& cell, const Vec3& offset,
                                                  const Vec3* kept, int half, Vec3& normal) {
    if (kept) {
        normal = kept[half];
        return true;
    }
    // Half 0: (i, j), (i, j+1), (i+1, j+1); half 1: (i, j), (i+1, j+1), (i+1, j).
    const Vec3 corner00(cell.x0, cell.h00, cell.z0), corner11(cell.x1, cell.h11, cell.z1);
    const Vec3 second = half == 0 ? Vec3(cell.x0, cell.h01, cell.z1) : corner11;
    const Vec3 third = half == 0 ? corner11 : Vec3(cell.x1, cell.h10, cell.z0);
    const Vec3 cross = (second - corner00).cross(third - corner00);
    const double along = offset.dot(cross);
    // The slack holds while the rounding of the height, a few ulps of |offset|, stays under 1e-7
    // of the reach: true but for cells 1e8 times the sphere.
    const bool nearby = offset.squaredNorm() < 1e16 * s.reach * s.reach;
    if (nearby && along > 0.0 && along * along > s.clearly * cross.squaredNorm()) return false;
    normal = cross.normalized();
    return true;
}

/// addSphereTriangleContacts' outcome for triangle `half` of `cell` (unit `normal`, `offset` =
/// c − its corner (i, j), `index` its HeightfieldData index), with c's `height` over its plane.
/// Its first test, then: the foot on the plane clearly inside the triangle gives the face
/// normal's point (the function's search for the nearest feature would find the face); the foot
/// beside it, the features it would meet internal and beyond the sideways limit, nothing.
[[gnu::always_inline]] inline TriangleOutcome triangleOutcome(const HeightfieldGrid& grid, const SphereQuery& s,
                                                              const CellCorners& cell, const Vec3& offset,
                                                              const Vec3& normal, int half, int index, double& height) {
    height = offset.dot(normal);
    if (height > s.reach) return TriangleOutcome::Nothing;  // addSphereTriangleContacts' first test
    const Vec3 foot = s.c - height * normal;
    const double fx = foot.x() - cell.x0, fz = foot.z() - cell.z0;
    const double across = half == 0 ? fz * grid.cellX - fx * grid.cellZ : fx * grid.cellZ - fz * grid.cellX;
    const bool inside = half == 0 ? fx > s.inset && cell.z1 - foot.z() > s.inset
                                  : fz > s.inset && cell.x1 - foot.x() > s.inset;
    if (inside && across > s.inset * (grid.cellX + grid.cellZ)) return TriangleOutcome::FacePoint;
    // The diagonal's signed x–z distance is across / √(cellX² + cellZ²): this is at most that.
    const double diagonal = across * grid.inverseSpan;
    const double insideEdges[3] = {half == 0 ? fx : diagonal, half == 0 ? cell.z1 - foot.z() : cell.x1 - foot.x(),
                                   half == 0 ? diagonal : fz};
    if (addsNothingBeside(insideEdges, grid.field->activeFeatures[index], height, s.r, s.inset))
        return TriangleOutcome::Nothing;
    return TriangleOutcome::Call;
}

/// addSphereTriangleContacts for every triangle forTrianglesIn visits under c ± (r + margin),
/// the cells [i0, i1] x [j0, j1] (cellsReached's). The corners, normals and that function's first
/// test (the height over the plane) are computed as HeightfieldData::triangle and the function
/// compute them, so the triangles kept give the same bits.
void addSphereContacts(const HeightfieldGrid& grid, const SphereQuery& s, int i0, int i1, int j0, int j1,
                       ContactBuffer& buffer) {
    const double lowest = s.c.y() - s.reach;
    const int columns = grid.field->columns;
    forEachCell(grid, i0, i1, j0, j1, [&](int i, int j, const CellCorners& cell) {
        if (cell.highest() < lowest) return;
        const Vec3 offset = s.c - Vec3(cell.x0, cell.h00, cell.z0);
        const Vec3* kept = grid.keptNormals(i, j);
        for (int half = 0; half < 2; ++half) {
            Vec3 normal;
            if (!triangleNormal(s, cell, offset, kept, half, normal)) continue;
            const int index = 2 * (j * (columns - 1) + i) + half;
            double height;
            switch (triangleOutcome(grid, s, cell, offset, normal, half, index, height)) {
                case TriangleOutcome::Nothing: break;
                case TriangleOutcome::FacePoint:
                    addSphereFaceNormalContact(normal, height, s.c, s.r, s.margin,
                                               triangleFeatureId(static_cast<uint32_t>(index), 0), buffer);
                    break;
                case TriangleOutcome::Call: {
                    // Half 0: (i, j), (i, j+1), (i+1, j+1); half 1: (i, j), (i+1, j+1), (i+1, j).
                    const Vec3 corner11(cell.x1, cell.h11, cell.z1);
                    ContactTriangle tri;
                    tri.v[0] = Vec3(cell.x0, cell.h00, cell.z0);
                    tri.v[1] = half == 0 ? Vec3(cell.x0, cell.h01, cell.z1) : corner11;
                    tri.v[2] = half == 0 ? corner11 : Vec3(cell.x1, cell.h10, cell.z0);
                    tri.normal = normal;
                    tri.activeFeatures = grid.field->activeFeatures[index];
                    tri.id = static_cast<uint32_t>(index);
                    addSphereTriangleContacts(tri, s.c, s.r, s.margin, true, buffer);
                    break;
                }
            }
        }
    });
}

/// Where the sphere's reach stays inside one cell (i, j), most of a tread particle's calls: both
/// triangles' outcomes, and where they are at most one face point, that point (or none) straight
/// into `out` (cleared), turned as ContactBuffer::emit turns it (heightfield_turns.h): no buffer,
/// sort or loop. False, `out` untouched, where a triangle needs the full test or both give a
/// point (the buffer merges those). `plain`: pose.rotation is the plain identity.
bool oneCellContact(const HeightfieldGrid& grid, const SphereQuery& s, int i, int j, const Pose& pose, bool plain,
                    ContactManifold& out) {
    const int columns = grid.field->columns;
    const double* heights = grid.field->heights.data();
    const CellCorners cell{.x0 = grid.originX + i * grid.cellX,
                           .x1 = grid.originX + (i + 1) * grid.cellX,
                           .z0 = grid.originZ + j * grid.cellZ,
                           .z1 = grid.originZ + (j + 1) * grid.cellZ,
                           .h00 = heights[j * columns + i],
                           .h10 = heights[j * columns + i + 1],
                           .h01 = heights[(j + 1) * columns + i],
                           .h11 = heights[(j + 1) * columns + i + 1]};
    if (cell.highest() < s.c.y() - s.reach) return true;  // the sphere is above the cell: nothing
    const Vec3 offset = s.c - Vec3(cell.x0, cell.h00, cell.z0);
    const Vec3* kept = grid.keptNormals(i, j);
    Vec3 normal[2];
    double height[2];
    int face = -1;
    for (int half = 0; half < 2; ++half) {
        if (!triangleNormal(s, cell, offset, kept, half, normal[half])) continue;
        const int index = 2 * (j * (columns - 1) + i) + half;
        switch (triangleOutcome(grid, s, cell, offset, normal[half], half, index, height[half])) {
            case TriangleOutcome::Nothing: break;
            case TriangleOutcome::FacePoint:
                if (face >= 0) return false;
                face = half;
                break;
            case TriangleOutcome::Call: return false;
        }
    }
    if (face < 0) return true;
    // addSphereFaceNormalContact, then ContactBuffer::emit's turn of its one point.
    const Vec3& n = normal[face];
    const double h = height[face];
    ContactPoint p;
    p.depth = s.r - h;
    if (p.depth < -s.margin) return true;
    heightfield_turns::turnContact(pose, plain, s.c - s.r * n, s.c - h * n, n, p);
    p.feature = triangleFeatureId(static_cast<uint32_t>(2 * (j * (columns - 1) + i) + face), 0);
    out.add(p);
    return true;
}

/// collideSphereHeightfield with the centre c in the field's frame; `oneCell`: whether to try
/// oneCellContact; `plain`: pose.rotation is the plain identity (heightfield_turns.h).
void collideInFieldFrame(const HeightfieldGrid& grid, const Vec3& c, double r, const Pose& pose, double margin,
                         bool oneCell, bool plain, ContactManifold& out) {
    out.clear();
    const SphereQuery s(grid, c, r, margin);
    const HeightfieldData& field = *grid.field;
    int i0, i1, j0, j1;
    if (!cellsReached(c.x(), s.reach, grid.originX, grid.cellX, grid.inverseCellX, field.columns - 1, i0, i1) ||
        !cellsReached(c.z(), s.reach, grid.originZ, grid.cellZ, grid.inverseCellZ, field.rows - 1, j0, j1))
        return;
    if (oneCell && i0 == i1 && j0 == j1 && oneCellContact(grid, s, i0, j0, pose, plain, out)) return;
    ContactBuffer buffer(kMergeFraction * r);
    addSphereContacts(grid, s, i0, i1, j0, j1, buffer);
    if (buffer.count() > 1) {
        buffer.emit(pose, out);
    } else if (buffer.count() == 1) {
        // ContactBuffer::emit for its one point, without the call to sort it.
        ContactPoint p = buffer[0];
        heightfield_turns::turnContact(pose, plain, buffer[0].point0, buffer[0].point1, buffer[0].normal, p);
        out.add(p);
    }
}

}  // namespace

void HeightfieldGrid::reset(const HeightfieldData& data) {
    field = &data;
    originX = -0.5 * data.sizeX;
    originZ = -0.5 * data.sizeZ;
    cellX = data.cellX();
    cellZ = data.cellZ();
    inverseCellX = 1.0 / cellX;
    inverseCellZ = 1.0 / cellZ;
    inverseSpan = 1.0 / (cellX + cellZ);
    keptColumns_ = keptRows_ = 0;
    keptNormals_.clear();
}

void HeightfieldGrid::keepNormals(const Aabb& box, int mostCells) {
    keptColumns_ = keptRows_ = 0;
    keptNormals_.clear();
    int i0, i1, j0, j1;
    if (!cellRange(box.min.x(), box.max.x(), originX, cellX, inverseCellX, field->columns - 1, i0, i1) ||
        !cellRange(box.min.z(), box.max.z(), originZ, cellZ, inverseCellZ, field->rows - 1, j0, j1))
        return;
    if ((i1 - i0 + 1) * (j1 - j0 + 1) > mostCells) return;
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i)
            for (int half = 0; half < 2; ++half)
                keptNormals_.push_back(field->triangle(i, j, half).normal);
    keptI0_ = i0, keptJ0_ = j0, keptColumns_ = i1 - i0 + 1, keptRows_ = j1 - j0 + 1;
}

void collideSphereHeightfield(const HeightfieldGrid& grid, const Vec3& centre, double r, const Pose& pose,
                              double margin, ContactManifold& out) {
    // A field in the world's axes (rc_car's ground): its turns are shifts (heightfield_turns.h).
    const bool plain = heightfield_turns::isPlainIdentity(pose.rotation);
    collideInFieldFrame(grid, heightfield_turns::applyInverse(pose, plain, centre), r, pose, margin, true, plain, out);
}

void collideSphereHeightfieldCellByCell(const HeightfieldGrid& grid, const Vec3& centre, double r, const Pose& pose,
                                        double margin, ContactManifold& out) {
    const bool plain = heightfield_turns::isPlainIdentity(pose.rotation);
    collideInFieldFrame(grid, heightfield_turns::applyInverse(pose, plain, centre), r, pose, margin, false, plain, out);
}

bool heightfieldCellsReached(const HeightfieldGrid& grid, const Vec3& c, double reach, int& i0, int& i1, int& j0,
                             int& j1) {
    return cellsReached(c.x(), reach, grid.originX, grid.cellX, grid.inverseCellX, grid.field->columns - 1, i0, i1) &&
           cellsReached(c.z(), reach, grid.originZ, grid.cellZ, grid.inverseCellZ, grid.field->rows - 1, j0, j1);
}

double heightfieldGapBound(const HeightfieldGrid& grid, const Vec3& p, double reach) {
    if (!p.allFinite() || !std::isfinite(reach)) return -std::numeric_limits<double>::infinity();
    const HeightfieldData& field = *grid.field;
    // Taken off the result: the heights here and the narrowphase's later ones are rounded apart
    // by a few ulps of the coordinates.
    const double rounding = 1e-12 * (1.0 + p.cwiseAbs().maxCoeff());
    // The block of whole cells around p ± reach, on the field or not: the solid of every other
    // cell lies beyond its sides.
    const double a0 = floorOf((p.x() - reach - grid.originX) * grid.inverseCellX);
    const double a1 = floorOf((p.x() + reach - grid.originX) * grid.inverseCellX);
    const double b0 = floorOf((p.z() - reach - grid.originZ) * grid.inverseCellZ);
    const double b1 = floorOf((p.z() + reach - grid.originZ) * grid.inverseCellZ);
    double bound = std::min({p.x() - (grid.originX + a0 * grid.cellX), (grid.originX + (a1 + 1.0) * grid.cellX) - p.x(),
                             p.z() - (grid.originZ + b0 * grid.cellZ), (grid.originZ + (b1 + 1.0) * grid.cellZ) - p.z()});
    if (!(a1 >= 0.0) || !(a0 <= field.columns - 2) || !(b1 >= 0.0) || !(b0 <= field.rows - 2)) return bound - rounding;
    const int i0 = static_cast<int>(std::max(a0, 0.0)), i1 = static_cast<int>(std::min(a1, field.columns - 2.0));
    const int j0 = static_cast<int>(std::max(b0, 0.0)), j1 = static_cast<int>(std::min(b1, field.rows - 2.0));
    if ((i1 - i0 + 1) * (j1 - j0 + 1) > kMostBoundCells) return std::min(bound, p.y() - field.maxHeight) - rounding;
    // Row by row, each cell's highest sample from its sides' (a side's two samples shared with
    // the cell before): the max is exact, so the same value. (Its zero's sign may differ, and
    // with it the bound's: the result, the bound less a positive rounding, does not.)
    const int columns = field.columns;
    const double* heights = field.heights.data();
    for (int j = j0; j <= j1; ++j) {
        const double z0 = grid.originZ + j * grid.cellZ, z1 = grid.originZ + (j + 1) * grid.cellZ;
        const double* near = heights + j * columns;  // samples at z_j
        const double* far = near + columns;          // at z_j+1
        double leftSide = std::max(near[i0], far[i0]);
        for (int i = i0; i <= i1; ++i) {
            const double rightSide = std::max(near[i + 1], far[i + 1]);
            // Above the cell's highest sample by at least the bound: nothing lower here.
            const double aboveSamples = p.y() - std::max(leftSide, rightSide);
            leftSide = rightSide;
            if (aboveSamples >= bound) continue;
            // The solid under a triangle lies below its plane (its normal points up).
            const double x0 = grid.originX + i * grid.cellX;
            const Vec3 corner00(x0, near[i], z0);
            const Vec3 offset = p - corner00;
            double above0, above1;
            if (const Vec3* kept = grid.keptNormals(i, j)) {
                above0 = offset.dot(kept[0]);
                above1 = offset.dot(kept[1]);
            } else {
                const double x1 = grid.originX + (i + 1) * grid.cellX;
                const Vec3 corner11(x1, far[i + 1], z1);
                const Vec3 cross0 = (Vec3(x0, far[i], z1) - corner00).cross(corner11 - corner00);
                const Vec3 cross1 = (corner11 - corner00).cross(Vec3(x1, near[i + 1], z0) - corner00);
                above0 = offset.dot(cross0) / cross0.norm();
                above1 = offset.dot(cross1) / cross1.norm();
            }
            bound = std::min(bound, std::max(aboveSamples, std::min(above0, above1)));
        }
    }
    return bound - rounding;
}

HeightfieldClearance heightfieldClearance(const HeightfieldGrid& grid, const Vec3& p, double reach, double roam) {
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    const HeightfieldClearance none{.lowX = kInfinity, .highX = -kInfinity, .lowZ = kInfinity, .highZ = -kInfinity,
                                    .above = kInfinity};
    if (!p.allFinite() || !std::isfinite(reach) || !std::isfinite(roam)) return none;
    const HeightfieldData& field = *grid.field;
    const double spread = reach + roam;
    // The narrowphase's cell indices and its height test are rounded by a few ulps of these.
    const double slack = 1e-9 * (1.0 + p.cwiseAbs().maxCoeff() + std::abs(grid.originX) + std::abs(grid.originZ) +
                                 grid.cellX + grid.cellZ + spread + std::max(std::abs(field.minHeight),
                                                                             std::abs(field.maxHeight)));
    const double a0 = floorOf((p.x() - spread - grid.originX) * grid.inverseCellX);
    const double a1 = floorOf((p.x() + spread - grid.originX) * grid.inverseCellX);
    const double b0 = floorOf((p.z() - spread - grid.originZ) * grid.inverseCellZ);
    const double b1 = floorOf((p.z() + spread - grid.originZ) * grid.inverseCellZ);
    HeightfieldClearance clearance{.lowX = grid.originX + a0 * grid.cellX + reach + slack,
                                   .highX = grid.originX + (a1 + 1.0) * grid.cellX - reach - slack,
                                   .lowZ = grid.originZ + b0 * grid.cellZ + reach + slack,
                                   .highZ = grid.originZ + (b1 + 1.0) * grid.cellZ - reach - slack,
                                   .above = -kInfinity};
    if (!(a1 >= 0.0) || !(a0 <= field.columns - 2) || !(b1 >= 0.0) || !(b0 <= field.rows - 2)) return clearance;
    const int i0 = static_cast<int>(std::max(a0, 0.0)), i1 = static_cast<int>(std::min(a1, field.columns - 2.0));
    const int j0 = static_cast<int>(std::max(b0, 0.0)), j1 = static_cast<int>(std::min(b1, field.rows - 2.0));
    double highest = -kInfinity;
    if ((i1 - i0 + 1) * (j1 - j0 + 1) > kMostBoundCells) {
        highest = field.maxHeight;
    } else {
        const double* heights = field.heights.data();
        for (int j = j0; j <= j1 + 1; ++j)
            for (int i = i0; i <= i1 + 1; ++i) highest = std::max(highest, heights[j * field.columns + i]);
    }
    clearance.above = highest + reach + slack;
    return clearance;
}

}  // namespace substep
