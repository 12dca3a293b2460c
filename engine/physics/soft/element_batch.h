#pragma once
/// Shape-matching projections four elements at a time.
///
/// A soft body's elements are coloured at creation so that no two elements of one colour share
/// a particle (colourElements) and stored colour by colour; runs of up to four consecutive
/// elements of one colour form a batch. The elements of a batch are independent, so projecting
/// them side by side, one per SIMD lane, gives exactly what projecting them one after the
/// other would: a Gauss-Seidel sweep in colour order. The kernel is the one of
/// shape_matching.h (Eq. 4 on C = sqrt(Σ ⅛ |x_j − c − R q_j|²)) with one warm-started Newton
/// step of the rotation extraction in the lanes; the rare element that needs more (a turn over
/// 1e-3 rad, an inverted or collapsed shape) and the optional volume constraint run through the
/// scalar functions of shape_matching.h.

#include "physics/math.h"
#include "physics/soft/lattice.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace substep {

/// Elements projected side by side.
inline constexpr int kBatchLanes = 4;

/// Up to kBatchLanes consecutive elements of one colour, with their rest offsets and corner
/// inverse masses laid out lane-innermost (lanes past `lanes` repeat lane 0 and are not
/// written back).
struct ElementBatch {
    alignas(32) double rest[3][8][kBatchLanes];  ///< q_j, component by corner by lane
    alignas(32) double invMass[8][kBatchLanes];  ///< w_j
    uint32_t firstElement = 0;
    uint32_t lanes = 0;
};

/// The state the kernel reads and writes, the SoftSystem's arrays.
struct ElementArrays {
    std::span<Vec3> positions;
    std::span<const HexElement> elements;
    std::span<const std::array<Vec3, 8>> restOffsets;
    std::span<const std::array<Vec3, 8>> volumeGradients;
    std::span<Quat> rotations;
    std::span<const double> scale2;
    std::span<const double> compliance;
    std::span<const double> volumeCompliance;
    std::span<double> lambda;
    std::span<double> volumeLambda;
    std::span<const double> invMass;  ///< per particle
};

/// A colour per element (0, 1, ...) such that elements sharing a particle differ; greedy in
/// element order, at most 27 colours for a hexahedral lattice (the element and its 26
/// neighbours).
std::vector<uint8_t> colourElements(std::span<const HexElement> elements, size_t particleCount);

/// The batches of elements [first, first + count), which must be sorted by `colour`.
void appendBatches(const ElementArrays& arrays, std::span<const uint8_t> colour, uint32_t first,
                   uint32_t count, std::vector<ElementBatch>& batches);

/// One Gauss-Seidel sweep of the shape-matching (and volume) constraints over the batches, with
/// α̃ = α_e invH2.
void solveElementBatches(std::span<const ElementBatch> batches, const ElementArrays& arrays, double invH2);

}  // namespace substep
