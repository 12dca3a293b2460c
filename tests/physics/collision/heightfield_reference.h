#pragma once
// The sphere–heightfield narrowphase by brute force, as collide_mesh.cpp computed it before
// heightfield_sphere.cpp: a ContactTriangle for both triangles of every cell
// HeightfieldData::forTrianglesIn visits, each through addSphereTriangleContacts. The reference
// of heightfield_sphere_test.cpp and of BM_ParticleHeightfield. And heightfieldGapBound cell by
// cell, as heightfield_sphere.cpp computed it before its row-by-row loop.

#include "physics/collision/contact_buffer.h"
#include "physics/collision/heightfield.h"
#include "physics/collision/heightfield_sphere.h"
#include "physics/collision/triangle_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace substep::reference {

/// A sphere of radius r centred at `centre` (world) on the field at `pose`.
inline void collideSphereHeightfield(const HeightfieldData& field, const Vec3& centre, double r, const Pose& pose,
                                     double margin, ContactManifold& out) {
    out.clear();
    const Vec3 c = pose.applyInverse(centre);
    ContactBuffer buffer(0.01 * r);
    const Aabb box{c.array() - (r + margin), c.array() + (r + margin)};
    field.forTrianglesIn(box, [&](const ContactTriangle& tri) {
        addSphereTriangleContacts(tri, c, r, margin, true, buffer);
    });
    buffer.emit(pose, out);
}

/// heightfieldGapBound with each cell's four samples and kept normals looked up on their own.
inline double heightfieldGapBound(const HeightfieldGrid& grid, const Vec3& p, double reach) {
    if (!p.allFinite() || !std::isfinite(reach)) return -std::numeric_limits<double>::infinity();
    const HeightfieldData& field = *grid.field;
    const double rounding = 1e-12 * (1.0 + p.cwiseAbs().maxCoeff());
    const double a0 = std::floor((p.x() - reach - grid.originX) * grid.inverseCellX);
    const double a1 = std::floor((p.x() + reach - grid.originX) * grid.inverseCellX);
    const double b0 = std::floor((p.z() - reach - grid.originZ) * grid.inverseCellZ);
    const double b1 = std::floor((p.z() + reach - grid.originZ) * grid.inverseCellZ);
    double bound = std::min({p.x() - (grid.originX + a0 * grid.cellX), (grid.originX + (a1 + 1.0) * grid.cellX) - p.x(),
                             p.z() - (grid.originZ + b0 * grid.cellZ), (grid.originZ + (b1 + 1.0) * grid.cellZ) - p.z()});
    if (!(a1 >= 0.0) || !(a0 <= field.columns - 2) || !(b1 >= 0.0) || !(b0 <= field.rows - 2)) return bound - rounding;
    const int i0 = static_cast<int>(std::max(a0, 0.0)), i1 = static_cast<int>(std::min(a1, field.columns - 2.0));
    const int j0 = static_cast<int>(std::max(b0, 0.0)), j1 = static_cast<int>(std::min(b1, field.rows - 2.0));
    if ((i1 - i0 + 1) * (j1 - j0 + 1) > 64) return std::min(bound, p.y() - field.maxHeight) - rounding;
    for (int j = j0; j <= j1; ++j) {
        for (int i = i0; i <= i1; ++i) {
            const Vec3 c00 = field.vertex(i, j), c10 = field.vertex(i + 1, j), c01 = field.vertex(i, j + 1),
                       c11 = field.vertex(i + 1, j + 1);
            const double aboveSamples = p.y() - std::max({c00.y(), c10.y(), c01.y(), c11.y()});
            if (aboveSamples >= bound) continue;
            const Vec3 offset = p - c00;
            double above0, above1;
            if (const Vec3* kept = grid.keptNormals(i, j)) {
                above0 = offset.dot(kept[0]);
                above1 = offset.dot(kept[1]);
            } else {
                const Vec3 cross0 = (c01 - c00).cross(c11 - c00);
                const Vec3 cross1 = (c11 - c00).cross(c10 - c00);
                above0 = offset.dot(cross0) / cross0.norm();
                above1 = offset.dot(cross1) / cross1.norm();
            }
            bound = std::min(bound, std::max(aboveSamples, std::min(above0, above1)));
        }
    }
    return bound - rounding;
}

}  // namespace substep::reference
