// Tests engine/physics/collision/heightfield.cpp: the grid's geometry, its triangles, crease
// flags, bounds, the work of its queries whatever the heights, and the validation of its input.

#include "physics/collision/heightfield.h"

#include "physics/collision/mesh_collider.h"
#include "physics/world.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

namespace substep {
namespace {

TEST(Heightfield, GridIsCentredOnTheOrigin) {
    const auto field = makeHeightfield(3, 2, {0, 1, 2, 3, 4, 5}, 4.0, 1.0);
    EXPECT_TRUE(field->vertex(0, 0).isApprox(Vec3(-2, 0, -0.5)));
    EXPECT_TRUE(field->vertex(2, 1).isApprox(Vec3(2, 5, 0.5)));
    EXPECT_TRUE(field->vertex(1, 1).isApprox(Vec3(0, 4, 0.5)));
    const Shape shape = heightfieldShape(field);
    EXPECT_EQ(shape.type, ShapeType::Heightfield);
    EXPECT_TRUE(shape.localBounds.min.isApprox(Vec3(-2, 0, -0.5)));
    EXPECT_TRUE(shape.localBounds.max.isApprox(Vec3(2, 5, 0.5)));
}

TEST(Heightfield, TrianglesFaceUpAndCoverTheCell) {
    const auto field = makeHeightfield(2, 2, {0, 0, 0, 0}, 2.0, 2.0);
    for (int half = 0; half < 2; ++half) {
        const ContactTriangle tri = field->triangle(0, 0, half);
        EXPECT_TRUE(tri.normal.isApprox(Vec3::UnitY()));
        EXPECT_NEAR((tri.v[1] - tri.v[0]).cross(tri.v[2] - tri.v[0]).norm(), 4.0, 1e-12);
    }
}

TEST(Heightfield, FlatInteriorEdgesAreInactive) {
    const auto field = makeHeightfield(3, 3, std::vector<double>(9, 1.0), 2.0, 2.0);
    // Cell (0, 0), triangle 0 = corners (0,0), (0,1), (1,1): its edge 0 is the field's border
    // x = -1, its edges 1 and 2 are shared with flat neighbours.
    const ContactTriangle tri = field->triangle(0, 0, 0);
    EXPECT_TRUE(tri.edgeActive(0));
    EXPECT_FALSE(tri.edgeActive(1));
    EXPECT_FALSE(tri.edgeActive(2));
    EXPECT_FALSE(tri.vertexActive(2));  // (1, 1), the grid's centre
}

TEST(Heightfield, RidgeEdgesAreActive) {
    // A ridge along z at x = 0: heights 0, 1, 0 across.
    const auto field = makeHeightfield(3, 2, {0, 1, 0, 0, 1, 0}, 2.0, 1.0);
    // Cell (0, 0), triangle 1 = (0,0), (1,1), (1,0): edge 1 runs along the ridge top.
    EXPECT_TRUE(field->triangle(0, 0, 1).edgeActive(1));
}

/// The flags activeFeatureFlags gives the grid as a triangle mesh (the rule for meshes, which
/// the heightfield used to build at 3.6 GB for 4096 x 4096 samples).
std::vector<uint8_t> flagsAsAMesh(const HeightfieldData& field) {
    TriangleMesh grid;
    for (int row = 0; row < field.rows; ++row)
        for (int column = 0; column < field.columns; ++column) grid.vertices.push_back(field.vertex(column, row));
    std::vector<Vec3> normals;
    const auto at = [&](int column, int row) { return row * field.columns + column; };
    for (int j = 0; j + 1 < field.rows; ++j) {
        for (int i = 0; i + 1 < field.columns; ++i) {
            grid.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
            grid.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
        }
    }
    for (const auto& t : grid.triangles) {
        const Vec3& a = grid.vertices[t[0]];
        normals.push_back((grid.vertices[t[1]] - a).cross(grid.vertices[t[2]] - a).normalized());
    }
    return activeFeatureFlags(grid, normals);
}

TEST(Heightfield, CreaseFlagsAreTheMeshRulesOnEveryGrid) {
    // Random bumps, flat runs, ridges and steps, on grids of several shapes and cell aspects.
    std::mt19937 random(19);
    std::uniform_real_distribution<double> height(-1.0, 1.0);
    for (const auto& [columns, rows, sizeX, sizeZ] :
         {std::tuple{2, 2, 1.0, 1.0}, std::tuple{3, 7, 4.0, 0.5}, std::tuple{9, 4, 0.1, 30.0},
          std::tuple{16, 16, 10.0, 10.0}}) {
        for (int pattern = 0; pattern < 4; ++pattern) {
            std::vector<double> heights(static_cast<std::size_t>(columns * rows));
            for (int j = 0; j < rows; ++j) {
                for (int i = 0; i < columns; ++i) {
                    double& h = heights[static_cast<std::size_t>(j * columns + i)];
                    if (pattern == 0) h = height(random);
                    if (pattern == 1) h = (i + j) % 3 == 0 ? height(random) : 0.5;  // mostly flat
                    if (pattern == 2) h = i == columns / 2 ? 1.0 : 0.0;              // a ridge
                    if (pattern == 3) h = j < rows / 2 ? 0.0 : 0.3;                  // a step
                }
            }
            const auto field = makeHeightfield(columns, rows, heights, sizeX, sizeZ);
            EXPECT_EQ(field->activeFeatures, flagsAsAMesh(*field))
                << columns << " x " << rows << ", pattern " << pattern;
        }
    }
}

TEST(Heightfield, VisitsOnlyCellsUnderTheBox) {
    const auto field = makeHeightfield(5, 5, std::vector<double>(25, 0.0), 4.0, 4.0);
    int visited = 0;
    field->forTrianglesIn({Vec3(-0.5, -1, -0.5), Vec3(0.5, 1, 0.5)},
                          [&](const ContactTriangle&) { ++visited; });
    EXPECT_EQ(visited, 8);  // 2 x 2 cells
    visited = 0;
    field->forTrianglesIn({Vec3(3, -1, 0), Vec3(4, 1, 1)},
                          [&](const ContactTriangle&) { ++visited; });
    EXPECT_EQ(visited, 0);
    // Wholly above the surface: nothing to test.
    field->forTrianglesIn({Vec3(-0.5, 0.1, -0.5), Vec3(0.5, 1, 0.5)},
                          [&](const ContactTriangle&) { ++visited; });
    EXPECT_EQ(visited, 0);
}

/// rows x rows heights drawn from [-amplitude, amplitude] over a square of `size` metres.
std::shared_ptr<const HeightfieldData> spikes(int rows, double amplitude, double size) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> height(-amplitude, amplitude);
    std::vector<double> heights(static_cast<std::size_t>(rows) * rows);
    for (double& h : heights) h = height(random);
    return makeHeightfield(rows, rows, std::move(heights), size, size);
}

// Issue 19: heights of ±1e6 m once made a frame take minutes. A query's work is the cells under
// the box in x-z, whatever the heights: at most 2 triangles for each of the
// (floor(extent / cell) + 2)² cells a box can touch; none when the box is above every height.
TEST(Heightfield, QueriesVisitTheCellsUnderTheBoxWhateverTheHeights) {
    const int rows = 513;
    const double size = 100.0;
    const double cell = size / (rows - 1);
    for (const double amplitude : {1.0, 1e6}) {
        const auto field = spikes(rows, amplitude, size);
        for (const double extent : {0.05, 1.0, 3.0}) {
            const int reach = static_cast<int>(std::floor(extent / cell)) + 2;
            for (const Vec3& centre : {Vec3(0, 0, 0), Vec3(10.3, 0, -20.7), Vec3(-49.9, 0, 49.9),
                                       Vec3(0, -3 * amplitude - 2, 0), Vec3(3, 3 * amplitude + 2, 7)}) {
                int visited = 0;
                const Vec3 half = Vec3::Constant(0.5 * extent);
                field->forTrianglesIn({centre - half, centre + half},
                                      [&](const ContactTriangle&) { ++visited; });
                EXPECT_LE(visited, 2 * reach * reach)
                    << "amplitude " << amplitude << ", extent " << extent << " at " << centre.transpose();
                if (centre.y() - half.y() > amplitude) {
                    EXPECT_EQ(visited, 0);
                }
                // Below every height (inside the solid) every cell under the box is visited.
                if (centre.y() + half.y() < -amplitude) {
                    const int inside = static_cast<int>(std::floor(extent / cell));
                    EXPECT_GE(visited, 2 * inside * inside);
                }
            }
        }
    }
}

// The same spikes under a sphere, a box and a cylinder in a world: each frame's contact work is
// a few triangles per body (the contacts found, at most 8 points a pair), and the state stays
// finite although the slopes of 1e7 launch the bodies (the loader refuses slopes above 1000).
TEST(Heightfield, FramesOnSpikesOfAMillionMetresStayFiniteAndSmall) {
    World world;
    world.createBody({.shape = heightfieldShape(spikes(513, 1e6, 100.0)), .type = BodyType::Static});
    world.createBody({.shape = sphereShape(0.5), .mass = 1, .position = {0, 2, 0}});
    world.createBody({.shape = boxShape(Vec3(1, 1, 1)), .mass = 1, .position = {3, 2, 0}});
    world.createBody({.shape = cylinderShape(0.5, 1), .mass = 1, .position = {-3, 2, 0}});
    for (int frame = 0; frame < 5; ++frame) {
        world.step(1.0 / 60.0);
        ASSERT_TRUE(world.isFinite()) << "frame " << frame;
        EXPECT_LE(world.contacts().size(), 3u * 8u) << "frame " << frame;
    }
}

TEST(Heightfield, RejectsBadInput) {
    EXPECT_THROW(makeHeightfield(1, 2, {0, 0}, 1, 1), std::invalid_argument);
    EXPECT_THROW(makeHeightfield(2, 2, {0, 0, 0}, 1, 1), std::invalid_argument);
    EXPECT_THROW(makeHeightfield(2, 2, {0, 0, 0, 0}, 0, 1), std::invalid_argument);
    EXPECT_THROW(makeHeightfield(2, 2, {0, 0, NAN, 0}, 1, 1), std::invalid_argument);
}

}  // namespace
}  // namespace substep
