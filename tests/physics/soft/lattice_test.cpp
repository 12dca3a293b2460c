// Tests engine/physics/soft/lattice.cpp: lattice counts, exact element volumes against the
// solids' closed forms, and a closed, outward-wound surface.
#include "physics/soft/lattice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace substep {
namespace {

std::array<Vec3, 8> cornersOf(const Lattice& lattice, const HexElement& e) {
    std::array<Vec3, 8> c;
    for (int j = 0; j < 8; ++j) c[j] = lattice.positions[e[j]];
    return c;
}

double latticeVolume(const Lattice& lattice) {
    double volume = 0.0;
    for (const HexElement& e : lattice.elements) volume += hexVolume(cornersOf(lattice, e));
    return volume;
}

/// Volume enclosed by the boundary triangles, (1/6) Σ a·(b × c): positive only if every face
/// is wound counter-clockwise seen from outside.
double enclosedVolume(const Lattice& lattice) {
    double volume = 0.0;
    for (const auto& q : boundaryQuads(lattice.elements)) {
        const Vec3& a = lattice.positions[q[0]];
        const Vec3& b = lattice.positions[q[1]];
        const Vec3& c = lattice.positions[q[2]];
        const Vec3& d = lattice.positions[q[3]];
        volume += (a.dot(b.cross(c)) + a.dot(c.cross(d))) / 6.0;
    }
    return volume;
}

TEST(Lattice, BoxCountsVolumeAndSurface) {
    const Vec3 size(0.3, 0.5, 0.7);
    const Lattice box = buildBoxLattice(size, {3, 4, 5});
    EXPECT_EQ(box.positions.size(), 4u * 5u * 6u);
    EXPECT_EQ(box.elements.size(), 60u);
    EXPECT_NEAR(latticeVolume(box), size.prod(), 1e-12);
    for (const HexElement& e : box.elements) EXPECT_NEAR(hexVolume(cornersOf(box, e)), size.prod() / 60.0, 1e-14);
    EXPECT_EQ(boundaryQuads(box.elements).size(), 2u * (3 * 4 + 4 * 5 + 3 * 5));
    EXPECT_NEAR(enclosedVolume(box), size.prod(), 1e-12);
}

TEST(Lattice, TyreVolumeIsThePolygonRing) {
    // Straight-edged cells: the ring's cross-section in the wheel plane is the difference of two
    // regular n-gons, area (n/2) sin(2π/n) (ro² − ri²).
    const double ro = 0.5, ri = 0.3, width = 0.2;
    const int around = 24;
    const Lattice tyre = buildTyreLattice(ro, ri, width, {around, 3, 2});
    EXPECT_EQ(tyre.elements.size(), 24u * 3u * 2u);
    EXPECT_EQ(tyre.positions.size(), 24u * 4u * 3u);
    const double expected = 0.5 * around * std::sin(2.0 * M_PI / around) * (ro * ro - ri * ri) * width;
    EXPECT_NEAR(latticeVolume(tyre), expected, 1e-12);
    for (const HexElement& e : tyre.elements) EXPECT_GT(hexVolume(cornersOf(tyre, e)), 0.0);
    // Two side faces per (around, radial) cell, inner and outer faces per (around, across).
    EXPECT_EQ(boundaryQuads(tyre.elements).size(), 2u * 24 * 3 + 2u * 24 * 2);
    EXPECT_NEAR(enclosedVolume(tyre), expected, 1e-12);
    int inner = 0;
    for (size_t i = 0; i < tyre.positions.size(); ++i) {
        const Vec3& p = tyre.positions[i];
        const double radius = std::hypot(p.x(), p.z());
        EXPECT_EQ(tyre.inner[i] != 0, std::abs(radius - ri) < 1e-12);
        inner += tyre.inner[i];
    }
    EXPECT_EQ(inner, 24 * 3);
}

TEST(Lattice, HexVolumeOfASkewedCellAndAnInvertedOne) {
    // A parallelepiped spanned by u, v, w has volume u·(v × w); mirrored it is negative.
    const Vec3 u(1.0, 0.1, 0.0), v(0.2, 0.9, 0.1), w(0.0, 0.3, 1.2);
    std::array<Vec3, 8> c;
    for (int n = 0; n < 8; ++n) c[n] = (n & 1) * u + ((n >> 1) & 1) * v + ((n >> 2) & 1) * w;
    EXPECT_NEAR(hexVolume(c), u.dot(v.cross(w)), 1e-14);
    for (Vec3& p : c) p.z() = -p.z();
    EXPECT_NEAR(hexVolume(c), -u.dot(v.cross(w)), 1e-14);
}

TEST(Lattice, ElementsAreTheirShapeTurned) {
    // Every element's rest offsets from its centroid are its shape's turned by its shapeTurn,
    // to rounding; a box has one shape, a tyre one per radial layer and place across (the ring
    // turned about its axis), whatever the counts.
    struct Case {
        Lattice lattice;
        size_t shapes;
    };
    const Case cases[] = {{buildBoxLattice(Vec3(0.3, 0.2, 0.4), {3, 2, 4}), 1},
                          {buildBoxLattice(Vec3(1, 1, 1), {1, 1, 1}), 1},
                          {buildTyreLattice(0.07, 0.05, 0.06, {46, 4, 6}), 24},
                          {buildTyreLattice(0.3, 0.2, 0.15, {7, 2, 3}), 6},
                          {buildTyreLattice(0.3, 0.1, 0.1, {3, 1, 1}), 1}};
    for (const Case& c : cases) {
        const Lattice& lattice = c.lattice;
        ASSERT_EQ(lattice.shape.size(), lattice.elements.size());
        ASSERT_EQ(lattice.shapeTurn.size(), lattice.elements.size());
        const std::vector<std::array<Vec3, 8>> shapes = restShapes(lattice);
        EXPECT_EQ(shapes.size(), c.shapes);
        double size = 0.0, worst = 0.0;
        for (const Vec3& p : lattice.positions) size = std::max(size, p.norm());
        for (size_t k = 0; k < lattice.elements.size(); ++k) {
            ASSERT_LT(lattice.shape[k], shapes.size());
            Vec3 centre = Vec3::Zero();
            for (uint32_t p : lattice.elements[k]) centre += 0.125 * lattice.positions[p];
            for (int j = 0; j < 8; ++j) {
                const Vec3 own = lattice.positions[lattice.elements[k][j]] - centre;
                worst = std::max(worst, (lattice.shapeTurn[k] * shapes[lattice.shape[k]][j] - own).norm());
            }
        }
        EXPECT_LT(worst, 1e-14 * size) << lattice.elements.size() << " elements";
    }
}

}  // namespace
}  // namespace substep
