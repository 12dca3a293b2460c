#include "physics/collision/heightfield.h"

#include "physics/collision/mesh_collider.h"

#include <stdexcept>

namespace substep {

namespace {

/// The corners of triangle `half` of cell (i, j), counter-clockwise seen from above (+y).
std::array<std::array<int, 2>, 3> cellTriangle(int i, int j, int half) {
    if (half == 0) return {{{i, j}, {i, j + 1}, {i + 1, j + 1}}};
    return {{{i, j}, {i + 1, j + 1}, {i + 1, j}}};
}

/// Unit normal of triangle `half` of cell (i, j), computed as HeightfieldData::triangle does;
/// zero for a degenerate one.
Vec3 cellNormal(const HeightfieldData& field, int i, int j, int half) {
    const auto c = cellTriangle(i, j, half);
    const Vec3 a = field.vertex(c[0][0], c[0][1]);
    return (field.vertex(c[1][0], c[1][1]) - a).cross(field.vertex(c[2][0], c[2][1]) - a).normalized();
}

/// The ContactTriangle flags of every triangle by activeFeatureFlags' rule (mesh_collider.h),
/// found from the grid's own neighbours: memory and time proportional to the heights (a
/// temporary mesh with sorted edge lists took 3.6 GB for 4096 x 4096 samples).
/// Edges of half 0 (corners (i,j), (i,j+1), (i+1,j+1)): 0 the left side, shared with half 1 of
/// cell (i-1, j); 1 the far side, shared with half 1 of (i, j+1); 2 the diagonal. Half 1 (corners
/// (i,j), (i+1,j+1), (i+1,j)): 0 the diagonal, 1 the right side, shared with half 0 of (i+1, j);
/// 2 the near side, shared with half 0 of (i, j-1).
std::vector<uint8_t> gridFeatureFlags(const HeightfieldData& field) {
    const int cellsX = field.columns - 1;
    const int cellsZ = field.rows - 1;
    std::vector<uint8_t> flags(2 * static_cast<std::size_t>(cellsX) * static_cast<std::size_t>(cellsZ), 0);
    std::vector<bool> vertexActive(field.heights.size(), false);
    const auto index = [&](int i, int j, int half) {
        return 2 * (static_cast<std::size_t>(j) * cellsX + i) + static_cast<std::size_t>(half);
    };
    for (int j = 0; j < cellsZ; ++j) {
        for (int i = 0; i < cellsX; ++i) {
            for (int half = 0; half < 2; ++half) {
                const Vec3 n = cellNormal(field, i, j, half);
                if (n.isZero(0.0)) continue;  // ignored, as meshes ignore degenerate triangles
                const auto corners = cellTriangle(i, j, half);
                for (int e = 0; e < 3; ++e) {
                    // The neighbour across edge e and its corner off the edge; none on a border.
                    int ni = i, nj = j, nHalf = 1 - half;
                    std::array<int, 2> off{};
                    bool inside = true;
                    if (half == 0 && e == 0) {
                        ni = i - 1, nHalf = 1, off = {i - 1, j}, inside = i > 0;
                    } else if (half == 0 && e == 1) {
                        nj = j + 1, nHalf = 1, off = {i + 1, j + 2}, inside = j + 1 < cellsZ;
                    } else if (half == 1 && e == 1) {
                        ni = i + 1, nHalf = 0, off = {i + 2, j + 1}, inside = i + 1 < cellsX;
                    } else if (half == 1 && e == 2) {
                        nj = j - 1, nHalf = 0, off = {i, j - 1}, inside = j > 0;
                    } else {
                        off = half == 0 ? std::array<int, 2>{i + 1, j} : std::array<int, 2>{i, j + 1};
                    }
                    bool active = true;  // a border
                    if (inside) {
                        const Vec3 n2 = cellNormal(field, ni, nj, nHalf);
                        if (!n2.isZero(0.0)) {
                            active = isActiveCrease(n, n2, field.vertex(corners[e][0], corners[e][1]),
                                                    field.vertex(off[0], off[1]));
                        }
                    }
                    if (!active) continue;
                    flags[index(i, j, half)] |= static_cast<uint8_t>(kEdgeActive0 << e);
                    const auto& a = corners[e];
                    const auto& b = corners[(e + 1) % 3];
                    vertexActive[static_cast<std::size_t>(a[1]) * field.columns + a[0]] = true;
                    vertexActive[static_cast<std::size_t>(b[1]) * field.columns + b[0]] = true;
                }
            }
        }
    }
    for (int j = 0; j < cellsZ; ++j) {
        for (int i = 0; i < cellsX; ++i) {
            for (int half = 0; half < 2; ++half) {
                const auto corners = cellTriangle(i, j, half);
                for (int k = 0; k < 3; ++k) {
                    if (vertexActive[static_cast<std::size_t>(corners[k][1]) * field.columns + corners[k][0]])
                        flags[index(i, j, half)] |= static_cast<uint8_t>(kVertexActive0 << k);
                }
            }
        }
    }
    return flags;
}

}  // namespace

ContactTriangle HeightfieldData::triangle(int column, int row, int half) const {
    const auto corners = cellTriangle(column, row, half);
    ContactTriangle tri;
    for (int k = 0; k < 3; ++k)
        tri.v[k] = vertex(corners[k][0], corners[k][1]);
    tri.normal = (tri.v[1] - tri.v[0]).cross(tri.v[2] - tri.v[0]).normalized();
    const int index = 2 * (row * (columns - 1) + column) + half;
    tri.activeFeatures = activeFeatures[index];
    tri.id = static_cast<uint32_t>(index);
    return tri;
}

std::shared_ptr<const HeightfieldData> makeHeightfield(int columns, int rows,
                                                       std::vector<double> heights, double sizeX,
                                                       double sizeZ) {
    if (columns < 2 || rows < 2) {
        throw std::invalid_argument("makeHeightfield: needs at least 2 x 2 samples");
    }
    if (heights.size() != static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows)) {
        throw std::invalid_argument("makeHeightfield: heights do not match columns x rows");
    }
    if (!(sizeX > 0.0) || !(sizeZ > 0.0) || !std::isfinite(sizeX) || !std::isfinite(sizeZ)) {
        throw std::invalid_argument("makeHeightfield: size must be positive and finite");
    }
    for (double h : heights) {
        if (!std::isfinite(h)) throw std::invalid_argument("makeHeightfield: non-finite height");
    }
    auto field = std::make_shared<HeightfieldData>();
    field->columns = columns;
    field->rows = rows;
    field->sizeX = sizeX;
    field->sizeZ = sizeZ;
    field->heights = std::move(heights);
    field->minHeight = *std::min_element(field->heights.begin(), field->heights.end());
    field->maxHeight = *std::max_element(field->heights.begin(), field->heights.end());

    field->activeFeatures = gridFeatureFlags(*field);
    return field;
}

Shape heightfieldShape(std::shared_ptr<const HeightfieldData> field) {
    Shape shape{.type = ShapeType::Heightfield};
    shape.localBounds = {Vec3(-0.5 * field->sizeX, field->minHeight, -0.5 * field->sizeZ),
                         Vec3(0.5 * field->sizeX, field->maxHeight, 0.5 * field->sizeZ)};
    shape.heightfield = std::move(field);
    return shape;
}

}  // namespace substep
