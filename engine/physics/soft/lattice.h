#pragma once
/// Hexahedral lattices: particles and 8-particle elements of a box or a tyre in the soft body's
/// own frame, and the boundary quads of a lattice.
///
/// An element's corner n (0-7) sits at lattice offsets (n & 1, (n >> 1) & 1, (n >> 2) & 1)
/// along the lattice's three directions, which are right-handed, so a rest element has
/// positive volume.

#include "physics/math.h"

#include <array>
#include <cstdint>
#include <vector>

namespace substep {

using HexElement = std::array<uint32_t, 8>;

struct Lattice {
    std::vector<Vec3> positions;  ///< rest positions in the body's frame
    std::vector<HexElement> elements;
    std::vector<uint8_t> inner;   ///< per particle: 1 on a tyre's innermost radial layer
    /// Per element: its rest shape (elements of one shape are the same cell turned and moved:
    /// a box's cells are all one shape; a tyre's cells of one ring, radial layer and place
    /// across are one shape turned about the axis) and the turn from the first element of
    /// that shape to it. The soft body stores each shape once, in that first element's frame,
    /// so that the cells of one shape share their rest offsets bit for bit (element_batch.h).
    std::vector<uint32_t> shape;
    std::vector<Quat> shapeTurn;
};

/// A box of full extents `size` centred on the origin, cells[0..2] cells along x, y, z.
Lattice buildBoxLattice(const Vec3& size, const std::array<int, 3>& cells);

/// A ring about the y axis between `innerRadius` and `outerRadius`, `width` along y centred on
/// the origin: cells[0] around (closed), cells[1] radial, cells[2] across. Its innermost
/// particles are marked `inner`.
Lattice buildTyreLattice(double outerRadius, double innerRadius, double width,
                         const std::array<int, 3>& cells);

/// Each shape's rest offsets from its centroid (Lattice::shape), in the frame of its first
/// element in the lattice's order: element k's own offsets are shapeTurn[k] times its shape's,
/// up to rounding.
std::vector<std::array<Vec3, 8>> restShapes(const Lattice& lattice);

/// Volume of a trilinear hexahedron, ∫ det J over its parameter cube (2 x 2 x 2 Gauss points,
/// exact for the trilinear map); negative when inverted.
double hexVolume(const std::array<Vec3, 8>& corners);

/// The faces that belong to one element only, each wound counter-clockwise seen from outside
/// (for a lattice at rest).
std::vector<std::array<uint32_t, 4>> boundaryQuads(const std::vector<HexElement>& elements);

}  // namespace substep
