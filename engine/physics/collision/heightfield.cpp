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

    // The crease flags come from the same rule as meshes, on the grid as a temporary mesh.
    TriangleMesh grid;
    grid.vertices.reserve(field->heights.size());
    for (int row = 0; row < rows; ++row) {
        for (int column = 0; column < columns; ++column) {
            grid.vertices.push_back(field->vertex(column, row));
        }
    }
    std::vector<Vec3> normals;
    for (int row = 0; row + 1 < rows; ++row) {
        for (int column = 0; column + 1 < columns; ++column) {
            for (int half = 0; half < 2; ++half) {
                const auto corners = cellTriangle(column, row, half);
                std::array<int, 3> tri;
                for (int k = 0; k < 3; ++k)
                    tri[k] = corners[k][1] * columns + corners[k][0];
                grid.triangles.push_back(tri);
                const Vec3& a = grid.vertices[tri[0]];
                normals.push_back(
                    (grid.vertices[tri[1]] - a).cross(grid.vertices[tri[2]] - a).normalized());
            }
        }
    }
    field->activeFeatures = activeFeatureFlags(grid, normals);
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
