// Tests engine/physics/collision/heightfield_sphere.cpp: the sphere–heightfield narrowphase
// straight from the heights against the triangle-by-triangle reference (heightfield_reference.h),
// bit for bit, and its one-cell path against its general path; the gap bound the soft bodies'
// candidates use: never above the distance, the distance itself over a plane, and never hiding a
// contact the narrowphase would find; and the clearance over a block's highest sample, which hides
// none either and is sharp.

#include "physics/collision/heightfield_sphere.h"

#include "heightfield_reference.h"
#include "physics/collision/triangle_contact.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

namespace substep {
namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }
bool sameBits(const Vec3& a, const Vec3& b) {
    return sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) && sameBits(a.z(), b.z());
}

/// The narrowphase's contacts for a sphere against the reference's, bit for bit (success), and
/// how many the reference found.
::testing::AssertionResult sameContactsAsReference(const HeightfieldData& field, const HeightfieldGrid& grid,
                                                   const Vec3& centre, double r, const Pose& pose, double margin,
                                                   int& expectedCount) {
    ContactManifold expected, got;
    reference::collideSphereHeightfield(field, centre, r, pose, margin, expected);
    collideSphereHeightfield(grid, centre, r, pose, margin, got);
    expectedCount = expected.count;
    if (got.count != expected.count)
        return ::testing::AssertionFailure() << got.count << " contacts against the reference's " << expected.count;
    for (int i = 0; i < got.count; ++i) {
        const ContactPoint& a = got.points[i];
        const ContactPoint& b = expected.points[i];
        if (!(sameBits(a.point0, b.point0) && sameBits(a.point1, b.point1) && sameBits(a.normal, b.normal) &&
              sameBits(a.depth, b.depth) && a.feature == b.feature))
            return ::testing::AssertionFailure() << "point " << i << ": depth " << a.depth << " vs " << b.depth;
    }
    return ::testing::AssertionSuccess();
}

/// Fields of every kind the tests draw from: flat, gentle, steep (slopes of several cells' height
/// per cell), with square and oblong cells of 1 cm to 2 m.
std::shared_ptr<const HeightfieldData> randomField(std::mt19937& rng, int kind) {
    std::uniform_int_distribution<int> samples(2, 9);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const int columns = samples(rng), rows = samples(rng);
    const double sizeX = 0.01 * std::pow(200.0, unit(rng)) * (columns - 1);
    const double sizeZ = (kind == 3 ? 1.0 : 0.3 + 1.4 * unit(rng)) * sizeX / (columns - 1) * (rows - 1);
    const double cell = std::min(sizeX / (columns - 1), sizeZ / (rows - 1));
    const double relief = kind == 0 ? 0.0 : kind == 1 ? 0.1 * cell : 3.0 * cell;
    std::vector<double> heights(static_cast<size_t>(columns) * rows);
    for (double& h : heights)
        h = relief * (2.0 * unit(rng) - 1.0);
    return makeHeightfield(columns, rows, std::move(heights), sizeX, sizeZ);
}

/// A point near a feature the narrowphase must get right: anywhere over the field, on a cell
/// line, at a sample, on a cell's diagonal, or beyond the field's border; at a height about the
/// surface from well below to beyond the margin.
Vec3 pointNear(const HeightfieldData& field, std::mt19937& rng, double r) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::uniform_int_distribution<int> column(0, field.columns - 1), row(0, field.rows - 1), kind(0, 4);
    const double cx = field.cellX(), cz = field.cellZ();
    const auto tiny = [&] { return (unit(rng) - 0.5) * (unit(rng) < 0.5 ? 1e-12 : 1e-3) * cx; };
    double x = (unit(rng) - 0.5) * field.sizeX, z = (unit(rng) - 0.5) * field.sizeZ;
    switch (kind(rng)) {
        case 0: break;
        case 1: x = field.vertex(column(rng), 0).x() + tiny(); break;  // a line between cells
        case 2: {
            const Vec3 v = field.vertex(column(rng), row(rng));  // a sample
            x = v.x() + tiny(), z = v.z() + tiny();
            break;
        }
        case 3: {
            const double t = unit(rng);  // the diagonal of a cell
            const Vec3 v = field.vertex(std::min(column(rng), field.columns - 2), std::min(row(rng), field.rows - 2));
            x = v.x() + t * cx + tiny(), z = v.z() + t * cz;
            break;
        }
        default: x = (unit(rng) < 0.5 ? -1.0 : 1.0) * (0.5 * field.sizeX + (unit(rng) - 0.7) * 2.0 * r);  // the border
    }
    // The surface height there, roughly: the nearest sample's.
    const int i = std::clamp(static_cast<int>(std::lround((x + 0.5 * field.sizeX) / cx)), 0, field.columns - 1);
    const int j = std::clamp(static_cast<int>(std::lround((z + 0.5 * field.sizeZ) / cz)), 0, field.rows - 1);
    const double y = field.heights[j * field.columns + i] + r * (3.0 * unit(rng) - 1.5);
    return {x, y, z};
}

/// A box (the field's frame) over a random block of cells, part of it beyond the field at times.
Aabb someCells(const HeightfieldData& field, std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(-0.7, 0.7);
    Aabb box;
    box.grow(Vec3(unit(rng) * field.sizeX, 0.0, unit(rng) * field.sizeZ));
    box.grow(Vec3(unit(rng) * field.sizeX, 1.0, unit(rng) * field.sizeZ));
    return box;
}

Pose randomPose(std::mt19937& rng, bool turned) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    Pose pose{Vec3(unit(rng), unit(rng), unit(rng)) * 20.0, Quat::Identity()};
    if (turned) pose.rotation = Quat(Eigen::AngleAxisd(3.0 * unit(rng), Vec3(unit(rng), unit(rng), unit(rng)).normalized()));
    return pose;
}

TEST(HeightfieldSphere, GivesTheTriangleByTriangleContactsBitForBit) {
    std::mt19937 rng(14);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int withContacts = 0, several = 0, cases = 0;
    for (int f = 0; f < 400; ++f) {
        const auto field = randomField(rng, f % 4);
        HeightfieldGrid grid(*field);
        // Half the fields keep the normals of a block of cells, as a soft body's grid does.
        if (f % 2 == 1) grid.keepNormals(someCells(*field, rng), 256);
        const Pose pose = randomPose(rng, f % 3 == 0);
        for (int k = 0; k < 200; ++k) {
            // Radii from a thousandth of a cell to two cells.
            const double r = std::min(field->cellX(), field->cellZ()) * std::pow(10.0, -3.0 + 3.3 * unit(rng));
            const double margin = unit(rng) < 0.2 ? 0.0 : 0.4 * r * unit(rng);
            const Vec3 centre = pose.apply(pointNear(*field, rng, r));
            int expected = 0;
            ++cases;
            ASSERT_TRUE(sameContactsAsReference(*field, grid, centre, r, pose, margin, expected))
                << "field " << f << " case " << k;
            withContacts += expected > 0;
            several += expected > 1;
        }
    }
    // The draw reaches every outcome: no contact, one, several (edges, steep cells, big spheres).
    EXPECT_GT(withContacts, cases / 4);
    EXPECT_GT(several, cases / 50);
    EXPECT_LT(withContacts, cases);
}

TEST(HeightfieldSphere, GivesTheReferenceContactsBesideATriangle) {
    // The narrowphase leaves out a triangle the sphere's foot lies beside when the features it
    // would meet are internal and farther than kInactiveSideways r: feet placed just inside and
    // just beyond that limit from every edge of random triangles (and near their corners), over
    // flat fields (every feature internal), gentle and steep ones (convex creases active), the
    // centre in front of and behind the plane. The same contacts as the reference, bit for bit.
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::uniform_int_distribution<int> pick(0, 2);
    const double excess[] = {-1e-3, -1e-9, 0.0, 1e-12, 1e-9, 1e-7, 2e-6, 1e-4, 1e-2, 0.5, 3.0};
    int withContacts = 0, cases = 0;
    for (int f = 0; f < 300; ++f) {
        const auto field = randomField(rng, f % 4);
        HeightfieldGrid grid(*field);
        if (f % 2 == 1) grid.keepNormals(someCells(*field, rng), 256);
        const Pose pose = randomPose(rng, f % 3 == 0);
        std::uniform_int_distribution<int> column(0, field->columns - 2), row(0, field->rows - 2);
        for (int k = 0; k < 150; ++k) {
            const ContactTriangle tri = field->triangle(column(rng), row(rng), pick(rng) % 2);
            const int e = pick(rng);
            const Vec3 a = tri.v[e], b = tri.v[(e + 1) % 3], opposite = tri.v[(e + 2) % 3];
            Vec3 outward = (b - a).cross(tri.normal).normalized();
            if ((opposite - a).dot(outward) > 0.0) outward = -outward;
            const double r = std::min(field->cellX(), field->cellZ()) * std::pow(10.0, -3.0 + 2.5 * unit(rng));
            const double margin = unit(rng) < 0.2 ? 0.0 : 0.4 * r * unit(rng);
            const double along = -0.3 + 1.6 * unit(rng);  // beyond the corners at times
            const double sideways = kInactiveSideways * r * (1.0 + excess[k % std::size(excess)]);
            const double height = r * (-1.0 + 2.5 * unit(rng));
            const Vec3 local = a + along * (b - a) + sideways * outward + height * tri.normal;
            const Vec3 centre = pose.apply(local);
            int expected = 0;
            ++cases;
            ASSERT_TRUE(sameContactsAsReference(*field, grid, centre, r, pose, margin, expected))
                << "field " << f << " case " << k;
            withContacts += expected > 0;
        }
    }
    // The draw reaches both outcomes.
    EXPECT_GT(withContacts, cases / 5);
    EXPECT_LT(withContacts, cases);
}

/// Whether two manifolds hold the same points, bit for bit, in the same order.
::testing::AssertionResult sameManifolds(const ContactManifold& got, const ContactManifold& expected) {
    if (got.count != expected.count)
        return ::testing::AssertionFailure() << got.count << " contacts against " << expected.count;
    for (int i = 0; i < got.count; ++i) {
        const ContactPoint& a = got.points[i];
        const ContactPoint& b = expected.points[i];
        if (!(sameBits(a.point0, b.point0) && sameBits(a.point1, b.point1) && sameBits(a.normal, b.normal) &&
              sameBits(a.depth, b.depth) && a.feature == b.feature))
            return ::testing::AssertionFailure() << "point " << i << ": depth " << a.depth << " vs " << b.depth;
    }
    return ::testing::AssertionSuccess();
}

TEST(HeightfieldSphere, OneCellPathGivesTheCellByCellContactsBitForBit) {
    // Spheres inside one cell, the one-cell path's case, against the general path through the
    // buffer (and the triangle-by-triangle reference): anywhere in a random cell, on its sides
    // and diagonal, at its corners (within 1e-12 to 1e-3 of a cell), from 1e-4 cell to larger
    // than a cell, about the surface from below it to beyond the margin; flat, gentle and steep
    // fields of 1 cm to 2 m cells, with and without kept normals, turned or not.
    std::mt19937 rng(33);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int cases = 0, onePointInOneCell = 0, several = 0;
    for (int f = 0; f < 400; ++f) {
        const auto field = randomField(rng, f % 4);
        HeightfieldGrid grid(*field);
        if (f % 3 != 0) grid.keepNormals({Vec3(-field->sizeX, 0, -field->sizeZ), Vec3(field->sizeX, 0, field->sizeZ)}, 256);
        const Pose pose = randomPose(rng, f % 4 == 1);
        const double cx = field->cellX(), cz = field->cellZ();
        std::uniform_int_distribution<int> column(0, field->columns - 2), row(0, field->rows - 2), kind(0, 3);
        for (int k = 0; k < 200; ++k) {
            const int i = column(rng), j = row(rng);
            const auto tiny = [&] { return (unit(rng) - 0.5) * (unit(rng) < 0.5 ? 1e-12 : 1e-3); };
            double u = unit(rng), v = unit(rng);  // across the cell, in cells
            switch (kind(rng)) {
                case 0: break;
                case 1: (unit(rng) < 0.5 ? u : v) = std::round(unit(rng)) + tiny(); break;  // a side
                case 2: u = std::round(unit(rng)) + tiny(), v = std::round(unit(rng)) + tiny(); break;  // a corner
                default: v = u + tiny();  // the diagonal
            }
            const double h00 = field->heights[j * field->columns + i], h10 = field->heights[j * field->columns + i + 1];
            const double h01 = field->heights[(j + 1) * field->columns + i];
            const double h11 = field->heights[(j + 1) * field->columns + i + 1];
            // The surface there: the plane of the triangle (u, v) is over.
            const double surface = v >= u ? h00 + v * (h01 - h00) + u * (h11 - h01) : h00 + u * (h10 - h00) + v * (h11 - h10);
            const double r = std::min(cx, cz) * std::pow(10.0, -4.0 + 4.2 * unit(rng));
            const double margin = unit(rng) < 0.2 ? 0.0 : 0.4 * r * unit(rng);
            const Vec3 local(-0.5 * field->sizeX + (i + u) * cx, surface + r * (3.0 * unit(rng) - 1.5),
                             -0.5 * field->sizeZ + (j + v) * cz);
            const Vec3 centre = pose.apply(local);
            ContactManifold got, general;
            collideSphereHeightfield(grid, centre, r, pose, margin, got);
            collideSphereHeightfieldCellByCell(grid, centre, r, pose, margin, general);
            ++cases;
            ASSERT_TRUE(sameManifolds(got, general)) << "field " << f << " case " << k;
            int expected = 0;
            ASSERT_TRUE(sameContactsAsReference(*field, grid, centre, r, pose, margin, expected))
                << "field " << f << " case " << k;
            // The draw's share of the one-cell path's case: the reach inside one cell (as
            // forTrianglesIn finds the cells), one point.
            const double reach = r + margin;
            const bool oneCell = std::floor((local.x() - reach + 0.5 * field->sizeX) / cx) ==
                                     std::floor((local.x() + reach + 0.5 * field->sizeX) / cx) &&
                                 std::floor((local.z() - reach + 0.5 * field->sizeZ) / cz) ==
                                     std::floor((local.z() + reach + 0.5 * field->sizeZ) / cz);
            onePointInOneCell += oneCell && got.count == 1;
            several += got.count > 1;
        }
    }
    EXPECT_GT(onePointInOneCell, cases / 5);
    EXPECT_GT(several, cases / 50);
}

TEST(HeightfieldSphere, AFieldInTheWorldsAxesGivesTheReferenceContactsBitForBit) {
    // A field whose rotation is the plain identity (Quat::Identity()) shifts the centre and the
    // points by its position instead of turning them (heightfield_turns.h): against the
    // reference's turns, bit for bit, where zeros of either sign meet. Flat fields (samples of
    // ±0: points at height ±0, normals with ±0 sideways), gentle and steep ones; positions and
    // centres with coordinates of ±0; identities with a −0 in their vector part, which turn.
    std::mt19937 rng(1814);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto someZero = [&] { return unit(rng) < 0.5 ? -0.0 : 0.0; };
    int cases = 0, withContacts = 0;
    for (int f = 0; f < 400; ++f) {
        const auto field = randomField(rng, f % 8 < 4 ? 0 : f % 4);
        HeightfieldGrid grid(*field);
        if (f % 2 == 1) grid.keepNormals(someCells(*field, rng), 256);
        Pose pose = randomPose(rng, false);
        for (int k = 0; k < 3; ++k)
            if (unit(rng) < 0.5) pose.position[k] = someZero();
        if (f % 5 == 4) pose.rotation.coeffs()[f % 3] = -0.0;
        for (int k = 0; k < 200; ++k) {
            const double r = std::min(field->cellX(), field->cellZ()) * std::pow(10.0, -3.0 + 3.3 * unit(rng));
            const double margin = unit(rng) < 0.2 ? 0.0 : 0.4 * r * unit(rng);
            Vec3 local = pointNear(*field, rng, r);
            for (int a = 0; a < 3; a += 2)
                if (unit(rng) < 0.1) local[a] = someZero();  // over a cell line through the origin
            Vec3 centre = pose.apply(local);
            for (int a = 0; a < 3; a += 2)
                if (unit(rng) < 0.1) centre[a] = someZero();
            int expected = 0;
            ++cases;
            ASSERT_TRUE(sameContactsAsReference(*field, grid, centre, r, pose, margin, expected))
                << "field " << f << " case " << k;
            withContacts += expected > 0;
        }
    }
    EXPECT_GT(withContacts, cases / 4);
}

TEST(HeightfieldSphere, ReachesTheCellsForTrianglesInVisits) {
    // The narrowphase's cells (two ends at once in SSE2 lanes, or one by one near a cell line)
    // against HeightfieldData::forTrianglesIn's floor((t − origin) / cell), over random fields,
    // reaches from 1e-6 cell to 50 cells, ends anywhere, on cell lines (as rounded, or within
    // 1e-15 to 1e-6 of a cell), beyond the border, far off the field (1e12 cells) and NaN.
    std::mt19937 rng(52);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto range = [](double lo, double hi, double origin, double cell, int cells, int& first, int& last) {
        const double a = std::floor((lo - origin) / cell), b = std::floor((hi - origin) / cell);
        if (!(b >= 0.0) || !(a <= cells - 1)) return false;
        first = static_cast<int>(std::max(a, 0.0));
        last = static_cast<int>(std::min(b, static_cast<double>(cells - 1)));
        return true;
    };
    int onLines = 0, reached = 0;
    for (int f = 0; f < 200; ++f) {
        const auto field = randomField(rng, f % 4);
        const HeightfieldGrid grid(*field);
        const double cx = field->cellX(), cz = field->cellZ();
        std::uniform_int_distribution<int> line(-2, std::max(field->columns, field->rows) + 1), kind(0, 5);
        for (int k = 0; k < 500; ++k) {
            const double reach = std::min(cx, cz) * std::pow(10.0, -6.0 + 7.7 * unit(rng));
            // An end on a cell line: the centre a reach from it, give or take a few ulps or more.
            const auto coordinate = [&](double origin, double cell, double size) {
                const double near = unit(rng) < 0.3 ? 0.0 : std::pow(10.0, -15.0 + 9.0 * unit(rng)) * (unit(rng) - 0.5) * cell;
                switch (kind(rng)) {
                    case 0: return origin + line(rng) * cell + (unit(rng) < 0.5 ? reach : -reach) + near;
                    case 1: return (unit(rng) - 0.5) * 1e12 * cell;
                    case 2: return std::numeric_limits<double>::quiet_NaN();
                    default: return (unit(rng) - 0.5) * 1.4 * size;
                }
            };
            const Vec3 c(coordinate(grid.originX, cx, field->sizeX), 0.0, coordinate(grid.originZ, cz, field->sizeZ));
            int i0 = -7, i1 = -7, j0 = -7, j1 = -7, e0 = -7, e1 = -7, f0 = -7, f1 = -7;
            const bool got = heightfieldCellsReached(grid, c, reach, i0, i1, j0, j1);
            const bool expected = range(c.x() - reach, c.x() + reach, grid.originX, cx, field->columns - 1, e0, e1) &&
                                  range(c.z() - reach, c.z() + reach, grid.originZ, cz, field->rows - 1, f0, f1);
            ASSERT_EQ(got, expected) << "field " << f << " case " << k;
            if (!got) continue;
            ++reached;
            ASSERT_EQ(i0, e0) << "field " << f << " case " << k;
            ASSERT_EQ(i1, e1) << "field " << f << " case " << k;
            ASSERT_EQ(j0, f0) << "field " << f << " case " << k;
            ASSERT_EQ(j1, f1) << "field " << f << " case " << k;
            const double q = (c.x() - reach - grid.originX) / cx;
            onLines += std::abs(q - std::round(q)) < 1e-9;
        }
    }
    EXPECT_GT(reached, 20000);
    EXPECT_GT(onLines, 1000);
}

TEST(HeightfieldSphere, KeepsTheNormalsOfTheCellsUnderABox) {
    const auto field = makeHeightfield(5, 4, {0, 1, 0, 2, 0, 0, 3, 0, 1, 0, 2, 0, 0, 1, 0, 0, 0, 2, 0, 1}, 4.0, 3.0);
    HeightfieldGrid grid(*field);
    EXPECT_EQ(grid.keptNormals(1, 1), nullptr);
    // x in [-0.5, 0.5] reaches cells 1 and 2 (lines at -1, 0, 1), z in [0.2, 0.4] cell 1 (-0.5 to 0.5).
    grid.keepNormals({Vec3(-0.5, 0, 0.2), Vec3(0.5, 0, 0.4)}, 8);
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 4; ++i) {
            const Vec3* kept = grid.keptNormals(i, j);
            ASSERT_EQ(kept != nullptr, (i == 1 || i == 2) && j == 1) << i << " " << j;
            if (!kept) continue;
            EXPECT_TRUE(sameBits(kept[0], field->triangle(i, j, 0).normal));
            EXPECT_TRUE(sameBits(kept[1], field->triangle(i, j, 1).normal));
        }
    // More cells than allowed: none kept.
    grid.keepNormals({Vec3(-2, 0, -1.5), Vec3(2, 0, 1.5)}, 11);
    EXPECT_EQ(grid.keptNormals(1, 2), nullptr);
}

TEST(HeightfieldSphere, MissesAFieldItIsNotOver) {
    const auto field = makeHeightfield(3, 3, std::vector<double>(9, 0.0), 2.0, 2.0);
    ContactManifold m;
    collideSphereHeightfield(HeightfieldGrid(*field), Vec3(1.2, 0.0, 0.0), 0.1, Pose{}, 0.05, m);
    EXPECT_EQ(m.count, 0);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    collideSphereHeightfield(HeightfieldGrid(*field), Vec3(nan, 0.0, 0.0), 0.1, Pose{}, 0.05, m);
    EXPECT_EQ(m.count, 0);
}

/// The distance from p to the solid under the field, by brute force over every triangle: the
/// closest point of the surface, 0 below it.
double distanceToSolid(const HeightfieldData& field, const Vec3& p) {
    double best = std::numeric_limits<double>::infinity();
    for (int j = 0; j + 1 < field.rows; ++j)
        for (int i = 0; i + 1 < field.columns; ++i)
            for (int half = 0; half < 2; ++half) {
                const ContactTriangle tri = field.triangle(i, j, half);
                best = std::min(best, (p - closestOnTriangle(p, tri.v[0], tri.v[1], tri.v[2]).point).norm());
            }
    return best;
}

TEST(HeightfieldSphere, GapBoundIsTheHeightOverAPlane) {
    // A plane of slopes 0.3 along x and 0.2 along z in 12 x 7 samples: the bound is the distance
    // along its normal wherever the reach stays inside the field and the side is farther.
    const int columns = 12, rows = 7;
    const auto surface = [](double x, double z) { return 1.0 + 0.3 * x + 0.2 * z; };
    std::vector<double> heights;
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i)
            heights.push_back(surface(-2.75 + 0.5 * i, -1.5 + 0.5 * j));
    const auto field = makeHeightfield(columns, rows, heights, 5.5, 3.0);
    const HeightfieldGrid grid(*field);
    const Vec3 normal = Vec3(-0.3, 1.0, -0.2).normalized();
    for (double lift : {0.0, 0.01, 0.2}) {
        const Vec3 p = Vec3(0.3, surface(0.3, 0.1), 0.1) + lift * normal;
        EXPECT_NEAR(heightfieldGapBound(grid, p, 0.6), lift, 1e-9) << lift;
    }
}

TEST(HeightfieldSphere, GapBoundNeverExceedsTheDistance) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int tight = 0;
    for (int f = 0; f < 100; ++f) {
        const auto field = randomField(rng, f % 4);
        HeightfieldGrid grid(*field);
        if (f % 2 == 1) grid.keepNormals(someCells(*field, rng), 256);
        const double cell = std::min(field->cellX(), field->cellZ());
        for (int k = 0; k < 100; ++k) {
            const double reach = cell * 3.0 * unit(rng);
            const Vec3 p = pointNear(*field, rng, 0.5 * cell);
            const double distance = distanceToSolid(*field, p);
            const double bound = heightfieldGapBound(grid, p, reach);
            // Under the surface the distance to the solid is 0 and the bound negative or 0.
            EXPECT_LE(bound, distance + 1e-12 * (1.0 + distance)) << "field " << f << " case " << k;
            tight += bound > 0.5 * distance;
        }
    }
    EXPECT_GT(tight, 2000);  // not a bound that says nothing
}

TEST(HeightfieldSphere, GapBoundIsTheCellByCellBoundBitForBit) {
    // The row-by-row loop against the cell-by-cell one (heightfield_reference.h): random fields,
    // none, all or part of their normals kept, points near samples, sides, diagonals and the
    // border, reaches from none to past kMostBoundCells cells.
    std::mt19937 rng(41);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int overCells = 0;
    for (int f = 0; f < 300; ++f) {
        const auto field = randomField(rng, f % 4);
        HeightfieldGrid grid(*field);
        if (f % 3 == 1) grid.keepNormals(someCells(*field, rng), 256);
        if (f % 3 == 2) grid.keepNormals({Vec3(-field->sizeX, 0, -field->sizeZ), Vec3(field->sizeX, 0, field->sizeZ)}, 256);
        const double cell = std::min(field->cellX(), field->cellZ());
        for (int k = 0; k < 200; ++k) {
            const double reach = unit(rng) < 0.1 ? 0.0 : cell * std::pow(10.0, -3.0 + 4.0 * unit(rng));
            const Vec3 p = pointNear(*field, rng, cell * unit(rng));
            const double got = heightfieldGapBound(grid, p, reach);
            const double expected = reference::heightfieldGapBound(grid, p, reach);
            ASSERT_TRUE(sameBits(got, expected)) << "field " << f << " case " << k << ": " << got << " vs " << expected;
            overCells += got < reach - 1e-6 * cell;  // below the block's sides: a cell decided
        }
    }
    EXPECT_GT(overCells, 10000);
}

TEST(HeightfieldSphere, GapBoundHidesNoContact) {
    // A sphere moved by d from p finds no contact while bound − r − |d| > margin: check it over
    // random moves, with the narrowphase itself.
    std::mt19937 rng(18);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int skipped = 0;
    for (int f = 0; f < 200; ++f) {
        const auto field = randomField(rng, f % 4);
        HeightfieldGrid grid(*field);
        if (f % 2 == 1) grid.keepNormals(someCells(*field, rng), 256);
        const double cell = std::min(field->cellX(), field->cellZ());
        for (int k = 0; k < 100; ++k) {
            const double r = cell * 0.05 * (0.1 + unit(rng)), margin = 0.2 * r;
            const Vec3 p = pointNear(*field, rng, 4.0 * r);
            const double bound = heightfieldGapBound(grid, p, r + 2.0 * margin + cell * unit(rng));
            const Vec3 d = Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5) * 4.0 * r;
            if (!(bound - r - d.norm() > margin)) continue;
            ++skipped;
            ContactManifold m;
            reference::collideSphereHeightfield(*field, p + d, r, Pose{}, margin, m);
            EXPECT_EQ(m.count, 0) << "field " << f << " case " << k;
        }
    }
    EXPECT_GT(skipped, 3000);
}

TEST(HeightfieldSphere, ClearanceHidesNoContact) {
    // A sphere whose centre lies inside a clearance's box and above its height finds nothing,
    // wherever it is in that box: over random fields, reaches and roams, centres anywhere near
    // the box (its sides, above and below its height) and beyond the field's border.
    std::mt19937 rng(19);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int clear = 0, sharp = 0;
    for (int f = 0; f < 200; ++f) {
        const auto field = randomField(rng, f % 4);
        const HeightfieldGrid grid(*field);
        const double cell = std::min(field->cellX(), field->cellZ());
        for (int k = 0; k < 100; ++k) {
            const double r = cell * 0.05 * (0.1 + unit(rng)), margin = 0.2 * r, reach = r + margin;
            const Vec3 p = pointNear(*field, rng, 4.0 * r);
            const double roam = cell * unit(rng) * (unit(rng) < 0.2 ? 10.0 : 0.5);
            const HeightfieldClearance clearance = heightfieldClearance(grid, p, reach, roam);
            ASSERT_LE(clearance.lowX, p.x() - roam + 1e-9 * (1.0 + cell)) << "field " << f << " case " << k;
            ASSERT_GE(clearance.highX, p.x() + roam - 1e-9 * (1.0 + cell)) << "field " << f << " case " << k;
            ASSERT_LE(clearance.lowZ, p.z() - roam + 1e-9 * (1.0 + cell));
            ASSERT_GE(clearance.highZ, p.z() + roam - 1e-9 * (1.0 + cell));
            ASSERT_LE(clearance.above, field->maxHeight + reach + 1e-3 * reach);
            for (int m = 0; m < 10; ++m) {
                // Near the box's sides (a tenth of the reach either way) or anywhere in it.
                const auto near = [&](double lo, double hi) {
                    const double side = unit(rng) < 0.5 ? lo : hi;
                    return unit(rng) < 0.5 ? side + (unit(rng) - 0.5) * 0.2 * reach : lo + unit(rng) * (hi - lo);
                };
                const double top = std::isfinite(clearance.above) ? clearance.above : field->maxHeight + reach;
                const Vec3 q(near(clearance.lowX, clearance.highX), top + (unit(rng) - 0.3) * 0.1 * reach,
                             near(clearance.lowZ, clearance.highZ));
                if (!(q.y() > clearance.above && q.x() > clearance.lowX && q.x() < clearance.highX &&
                      q.z() > clearance.lowZ && q.z() < clearance.highZ))
                    continue;
                ++clear;
                ContactManifold found;
                reference::collideSphereHeightfield(*field, q, r, Pose{}, margin, found);
                EXPECT_EQ(found.count, 0) << "field " << f << " case " << k << " at " << q.transpose();
            }
            // The height is sharp: over the highest sample, a thousandth of the reach below it,
            // the sphere finds that sample.
            const Vec3 below(p.x(), clearance.above - 1e-3 * reach, p.z());
            int column = 0, row = 0;
            double highest = -std::numeric_limits<double>::infinity();
            for (int j = 0; j < field->rows; ++j)
                for (int i = 0; i < field->columns; ++i) {
                    const Vec3 v = field->vertex(i, j);
                    if (v.x() > clearance.lowX && v.x() < clearance.highX && v.z() > clearance.lowZ &&
                        v.z() < clearance.highZ && v.y() > highest)
                        highest = v.y(), column = i, row = j;
                }
            if (!(highest + reach > clearance.above - 1e-3 * reach)) continue;  // the top is on the box's rim
            const Vec3 v = field->vertex(column, row);
            ContactManifold found;
            reference::collideSphereHeightfield(*field, Vec3(v.x(), below.y(), v.z()), r, Pose{}, margin, found);
            EXPECT_GT(found.count, 0) << "field " << f << " case " << k;
            ++sharp;
        }
    }
    EXPECT_GT(clear, 20000);
    EXPECT_GT(sharp, 2000);
}

TEST(HeightfieldSphere, ClearanceOfANonFinitePointIsEmpty) {
    const auto field = makeHeightfield(2, 2, {0, 0, 0, 0}, 1.0, 1.0);
    const HeightfieldGrid grid(*field);
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    for (const HeightfieldClearance& c : {heightfieldClearance(grid, Vec3(nan, 0, 0), 0.1, 0.1),
                                          heightfieldClearance(grid, Vec3(0, 1, 0), inf, 0.1),
                                          heightfieldClearance(grid, Vec3(0, 1, 0), 0.1, nan)}) {
        EXPECT_FALSE(c.lowX < c.highX);  // holds no point
        EXPECT_FALSE(c.lowZ < c.highZ);
    }
    // Off the field: no sample under the box, clear at any height inside it.
    const HeightfieldClearance off = heightfieldClearance(grid, Vec3(40.0, -5.0, 3.0), 0.1, 0.1);
    EXPECT_EQ(off.above, -inf);
    EXPECT_LT(off.lowX, 39.9);
    EXPECT_GT(off.highX, 40.1);
}

TEST(HeightfieldSphere, GapBoundOfANonFinitePointIsMinusInfinity) {
    const auto field = makeHeightfield(2, 2, {0, 0, 0, 0}, 1.0, 1.0);
    const HeightfieldGrid grid(*field);
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    EXPECT_EQ(heightfieldGapBound(grid, Vec3(nan, 0, 0), 0.1), -inf);
    EXPECT_EQ(heightfieldGapBound(grid, Vec3(0, inf, 0), 0.1), -inf);
    EXPECT_EQ(heightfieldGapBound(grid, Vec3(0, 1, 0), inf), -inf);
    // Far off the field: the side of the block around it, at least the reach.
    EXPECT_GE(heightfieldGapBound(grid, Vec3(1e4, 0, 0), 0.1), 0.1 - 1e-7);
    EXPECT_GE(heightfieldGapBound(grid, Vec3(40.0, -5.0, 3.0), 0.1), 0.1 - 1e-9);
}

}  // namespace
}  // namespace substep
