#pragma once
/// A heightfield: a regular grid of heights over the x–z extents of the shape's frame, centred
/// on its origin (x in [−size.x/2, size.x/2], z likewise), y up. Each cell is split into two
/// triangles along its diagonal from (x_i, z_j) to (x_i+1, z_j+1). It is solid underneath:
/// whatever sinks below the surface is pushed back up.

#include "physics/collision/shape.h"
#include "physics/collision/triangle_contact.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

namespace substep {

struct HeightfieldData {
    int columns = 0;  ///< samples along x (>= 2)
    int rows = 0;     ///< samples along z (>= 2)
    double sizeX = 0.0;
    double sizeZ = 0.0;
    std::vector<double> heights;          ///< heights[row * columns + column]
    std::vector<uint8_t> activeFeatures;  ///< per triangle (2 per cell), ContactTriangle flags
    double minHeight = 0.0;
    double maxHeight = 0.0;

    double cellX() const { return sizeX / (columns - 1); }
    double cellZ() const { return sizeZ / (rows - 1); }
    Vec3 vertex(int column, int row) const {
        return {-0.5 * sizeX + column * cellX(), heights[row * columns + column],
                -0.5 * sizeZ + row * cellZ()};
    }

    /// Triangle `half` (0 or 1) of the cell whose low corner is (column, row).
    ContactTriangle triangle(int column, int row, int half) const;

    /// Calls visit(const ContactTriangle&) for the triangles of every cell under `box` (x–z),
    /// skipping cells that lie wholly below the box.
    template <class Visitor>
    void forTrianglesIn(const Aabb& box, Visitor&& visit) const {
        const auto range = [](double lo, double hi, double origin, double cell, int cells,
                              int& first, int& last) {
            const double a = std::floor((lo - origin) / cell);
            const double b = std::floor((hi - origin) / cell);
            if (!(b >= 0.0) || !(a <= cells - 1)) return false;  // also rejects NaN
            first = static_cast<int>(std::max(a, 0.0));
            last = static_cast<int>(std::min(b, static_cast<double>(cells - 1)));
            return true;
        };
        int i0, i1, j0, j1;
        if (!range(box.min.x(), box.max.x(), -0.5 * sizeX, cellX(), columns - 1, i0, i1)) return;
        if (!range(box.min.z(), box.max.z(), -0.5 * sizeZ, cellZ(), rows - 1, j0, j1)) return;
        for (int j = j0; j <= j1; ++j) {
            for (int i = i0; i <= i1; ++i) {
                const double h00 = heights[j * columns + i];
                const double h10 = heights[j * columns + i + 1];
                const double h01 = heights[(j + 1) * columns + i];
                const double h11 = heights[(j + 1) * columns + i + 1];
                if (std::max({h00, h10, h01, h11}) < box.min.y()) continue;
                visit(triangle(i, j, 0));
                visit(triangle(i, j, 1));
            }
        }
    }
};

/// Builds a heightfield from `heights` (rows along z, each `columns` samples along x).
/// Throws std::invalid_argument for fewer than 2 x 2 samples, a size that does not match, or
/// non-finite values.
std::shared_ptr<const HeightfieldData> makeHeightfield(int columns, int rows,
                                                       std::vector<double> heights, double sizeX,
                                                       double sizeZ);

/// A heightfield shape with its local bounds.
Shape heightfieldShape(std::shared_ptr<const HeightfieldData> field);

}  // namespace substep
