#pragma once
/// A sphere against a heightfield, straight from the grid's heights: the narrowphase of the
/// sphere–heightfield pair (collide_mesh.cpp) and of every soft-body particle on a heightfield,
/// and a lower bound on a point's gap to the field's solid for the soft bodies' candidates
/// (soft_coupling.cpp).
///
/// A sphere of a few millimetres over 10 cm cells meets one cell in most substeps, and most of
/// its triangles are beyond reach: the cells are found by multiplications, each triangle's plane
/// is tested without a square root, and only a triangle the sphere comes within reach of is made
/// into a ContactTriangle and handed to addSphereTriangleContacts.

#include "physics/collision/contact_manifold.h"
#include "physics/collision/heightfield.h"

#include <vector>

namespace substep {

/// A field's grid constants, which a run of queries on one field shares, and optionally the unit
/// normals of a block of its cells' triangles, which the queries there then read instead of
/// computing (a soft body's particles meet the same few cells all frame).
class HeightfieldGrid {
public:
    HeightfieldGrid() = default;
    explicit HeightfieldGrid(const HeightfieldData& data) { reset(data); }

    /// Points the grid at `data` and forgets the kept normals (their storage stays).
    void reset(const HeightfieldData& data);
    /// Keeps the normals of the triangles of the cells under `box` (x–z, the field's frame), as
    /// HeightfieldData::triangle computes them, if they are at most `mostCells`; else none.
    void keepNormals(const Aabb& box, int mostCells);
    /// The two kept normals of cell (i, j) (half 0, half 1), or null where none are kept.
    const Vec3* keptNormals(int i, int j) const {
        const unsigned di = static_cast<unsigned>(i - keptI0_), dj = static_cast<unsigned>(j - keptJ0_);
        if (di >= static_cast<unsigned>(keptColumns_) || dj >= static_cast<unsigned>(keptRows_)) return nullptr;
        return &keptNormals_[2 * (dj * static_cast<unsigned>(keptColumns_) + di)];
    }

    const HeightfieldData* field = nullptr;
    double originX = 0.0, originZ = 0.0;  ///< the low corner of cell (0, 0)
    double cellX = 1.0, cellZ = 1.0;      ///< as HeightfieldData::cellX, cellZ compute them
    double inverseCellX = 1.0, inverseCellZ = 1.0;
    double inverseSpan = 0.5;  ///< 1 / (cellX + cellZ)

private:
    int keptI0_ = 0, keptJ0_ = 0, keptColumns_ = 0, keptRows_ = 0;
    std::vector<Vec3> keptNormals_;  ///< 2 per cell, row by row
};

/// The sphere–heightfield narrowphase (collide_curved.h's collideSphereHeightfield) for a sphere
/// of radius r centred at `centre` (world) on the field at `pose`: clears `out` and fills it with
/// the points that addSphereTriangleContacts gives for each HeightfieldData::triangle that
/// HeightfieldData::forTrianglesIn visits under the sphere's box grown by `margin`, merged and
/// ordered as the triangle meshes' (collide_mesh.cpp), bit for bit.
/// A sphere whose reach stays inside one cell (most of a tread particle's calls) takes a path of
/// its own: both triangles' outcomes told without a buffer, and the one point most give written
/// straight into `out`; the same bits.
void collideSphereHeightfield(const HeightfieldGrid& grid, const Vec3& centre, double r, const Pose& pose,
                              double margin, ContactManifold& out);

/// collideSphereHeightfield without the one-cell path: every cell through the buffer. The
/// general path the one-cell path is tested against.
void collideSphereHeightfieldCellByCell(const HeightfieldGrid& grid, const Vec3& centre, double r, const Pose& pose,
                                        double margin, ContactManifold& out);

/// The cells [i0, i1] x [j0, j1] the narrowphase tests for a sphere with `reach` (radius +
/// margin) centred at c (the field's frame): those HeightfieldData::forTrianglesIn visits under
/// c ± reach (x–z). False where that box misses the field (or c is NaN).
bool heightfieldCellsReached(const HeightfieldGrid& grid, const Vec3& c, double reach, int& i0, int& i1, int& j0,
                             int& j1);

/// A lower bound on the height of point p (the field's frame) above the field's solid, as the
/// narrowphase sees it: for the cells within `reach` of p (x–z), each cell's lowest height of p
/// above its two triangles' planes or above its highest sample, whichever is larger; for the
/// solid beyond those cells, p's distance to their block's side. So a sphere of radius r at p,
/// moved by any d, finds no contact within `margin` while the bound less r less d exceeds the
/// margin; `reach` only decides how tight the bound is. A point or reach that is not finite
/// gives −∞ (no bound).
double heightfieldGapBound(const HeightfieldGrid& grid, const Vec3& p, double reach);

/// Where a sphere is clear of a field whatever path it took there: while its centre (the
/// field's frame) lies inside the x–z box (lowX, highX) x (lowZ, highZ) and above `above`, the
/// sphere–heightfield narrowphase with that reach (radius + margin) visits only cells whose
/// samples all lie more than the reach below it, so it finds nothing. A vertical bound: a
/// rolling tread particle moves mostly along the ground, which a bound on its distance takes as
/// a step toward it.
struct HeightfieldClearance {
    double lowX, highX, lowZ, highZ;
    double above;  ///< −∞ where the box misses the field; +∞ where nothing is bounded
};

/// The clearance of a sphere with `reach` (radius + margin) that may roam `roam` (x–z) from p
/// (the field's frame): the box holds the cells within roam + reach of p, `above` is their
/// highest sample plus the reach, each side moved in by a slack far above the rounding of
/// the narrowphase's cell indices. A point, reach or roam that is not finite gives an empty box.
HeightfieldClearance heightfieldClearance(const HeightfieldGrid& grid, const Vec3& p, double reach, double roam);

}  // namespace substep
