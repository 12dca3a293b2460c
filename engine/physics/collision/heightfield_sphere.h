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

namespace substep {

/// A field's grid constants, which a run of queries on one field shares.
struct HeightfieldGrid {
    explicit HeightfieldGrid(const HeightfieldData& field);

    const HeightfieldData* field;
    double originX, originZ;  ///< the low corner of cell (0, 0)
    double cellX, cellZ;      ///< as HeightfieldData::cellX, cellZ compute them
    double inverseCellX, inverseCellZ;
};

/// The sphere–heightfield narrowphase (collide_curved.h's collideSphereHeightfield) for a sphere
/// of radius r centred at `centre` (world) on the field at `pose`: clears `out` and fills it with
/// the points that addSphereTriangleContacts gives for each HeightfieldData::triangle that
/// HeightfieldData::forTrianglesIn visits under the sphere's box grown by `margin`, merged and
/// ordered as the triangle meshes' (collide_mesh.cpp), bit for bit.
void collideSphereHeightfield(const HeightfieldGrid& grid, const Vec3& centre, double r, const Pose& pose,
                              double margin, ContactManifold& out);

/// A lower bound on the height of point p (the field's frame) above the field's solid, as the
/// narrowphase sees it: for the cells within `reach` of p (x–z), each cell's lowest height of p
/// above its two triangles' planes or above its highest sample, whichever is larger; for the
/// solid beyond those cells, p's distance to their block's side. So a sphere of radius r at p,
/// moved by any d, finds no contact within `margin` while the bound less r less d exceeds the
/// margin; `reach` only decides how tight the bound is. A point or reach that is not finite
/// gives −∞ (no bound).
double heightfieldGapBound(const HeightfieldGrid& grid, const Vec3& p, double reach);

}  // namespace substep
