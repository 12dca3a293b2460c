#pragma once
/// Shape-matching projections four elements at a time (eight with AVX-512).
///
/// A soft body's elements get a wave at creation (elementWaves): one more than the latest wave
/// of the elements before them in the lattice's order that share a particle with them. Stored
/// wave by wave, each element still comes after every earlier element it shares a particle
/// with and before every later one, so the sweep is the Gauss-Seidel sweep in the lattice's
/// order (the order decides how fast a stiff lattice converges: a sweep bottom to top carries a
/// push through a whole column). Elements of one wave share no particle; runs of up to four
/// consecutive elements of one wave form a batch (of one rest shape, where its first two have
/// one: a tyre's ring), projected side by side, one per SIMD lane. The
/// kernel is the one of shape_matching.h (Eq. 4 on C = sqrt(Σ ⅛ |x_j − c − R q_j|²)) with
/// projectionRotation's warm-started Newton step of the rotation extraction in the lanes; the
/// rare element that needs more (a turn over 0.1 rad, an inverted or collapsed shape) and the
/// optional volume constraint run through the scalar functions of shape_matching.h.
///
/// Each element's rest offsets q_j are its rest shape's (lattice.h) in that shape's own frame,
/// and its rotation R maps them to the world: a tyre's 1104 cells are 24 shapes, each turned
/// about the axis. The batches keep each shape once (BatchShape), so a sweep reads 24 records
/// and the particles' inverse masses rather than 1.2 kB of rest data per batch.

#include "physics/math.h"
#include "physics/soft/lattice.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace substep {

/// Elements projected side by side.
inline constexpr int kBatchLanes = 4;

/// An element's rest data as the kernel reads it: the rest offsets q_j coordinate by coordinate,
/// ℓ² and α_e. Elements of one rest shape (lattice.h) and compliance share one: the tyres of the
/// RC car have 24 of them for 4416 elements, so the batches' rest data stays in the L1 cache
/// instead of streaming 1.4 MB a sweep.
struct BatchShape {
    static constexpr int kScale2 = 24, kCompliance = 25;  ///< row() of ℓ² and α_e
    alignas(64) double rest[3][8];  ///< q_j: component by corner
    double scale2 = 0.0;
    double compliance = 0.0;
    /// The doubles in order, rest row by row then ℓ² and α_e: rest[r][j] is row(8 r + j).
    const double* row(int index) const { return &rest[0][0] + index; }
};
static_assert(sizeof(BatchShape) == 256, "208 bytes, padded to four cache lines");

/// Up to kBatchLanes consecutive elements of one wave: their corners' particles lane-innermost
/// (lanes past `lanes` repeat lane 0 and are not written back) and their rest shapes.
struct ElementBatch {
    uint32_t particle[8][kBatchLanes];  ///< the corners' particle indices
    uint32_t shape[kBatchLanes];        ///< each lane's BatchShape
    uint32_t firstElement = 0;
    uint32_t lanes = 0;
    bool volume = false;  ///< a lane has the volume constraint
    bool oneShape = false;  ///< every lane has lane 0's shape
    /// Four lanes of one shape without the volume constraint, each corner's particles
    /// consecutive (lane l's is lane 0's + l, as a tyre's are): the kernel loads corners and
    /// rotations as rows and transposes them in registers instead of gathering them value by value.
    bool contiguous = false;
    /// Not contiguous, but loaded as rows all the same when paired (`rowsPair`): at least two
    /// lanes of one shape without the volume constraint, each corner's particles consecutive for
    /// its first `run[j]` lanes (lane l's is lane 0's + l) and at most one more lane, a "stray",
    /// anywhere. A tyre's batch at the end of a ring: three cells, and on the odd cells the last
    /// one's corners wrap around to the ring's first particles. The kernel reads four rows from
    /// lane 0's particle and element, which must be the body's (`rows` is false where they would
    /// run past its particles or elements: another thread may be solving the next body), puts
    /// each corner's stray in by a select, and writes back the batch's own doubles, rotations,
    /// multipliers and strays only.
    bool rows = false;
    uint8_t run[8] = {};          ///< per corner, the lanes consecutive from lane 0's particle
    uint8_t strayLane[8] = {};    ///< per corner, the stray's lane (none: lane 0, its own particle)
    uint32_t strayParticle[8] = {};  ///< per corner, the stray's particle (none: lane 0's)
    uint8_t strayCorners = 0;        ///< bit j: corner j has a stray
    /// A contiguous or rows batch of the same wave and body this many batches ahead (0: none) is
    /// projected with this one, side by side in eight lanes, on a CPU with AVX-512 (elements of
    /// one wave share no particle: projecting a later one early gives the same bits); the
    /// partner records the distance back. Contiguous batches pair first, each with one of its
    /// own shape where its wave has one; then the rest and the rows batches, with `rowsPair` set
    /// on both partners.
    uint32_t partnerAhead = 0, partnerBehind = 0;
    bool rowsPair = false;
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
    /// The batches' shapes (appendBatches' `shapes`).
    std::span<const BatchShape> shapes = {};
    /// Per particle: the unit normal of the contact holding it, zero for a free particle (empty:
    /// none held). A held particle does not take an element's correction along its normal into
    /// the contact: its inverse mass along the normal is 0 for it (W_j = w_j (1 − n nᵀ)), so the
    /// element corrects its other corners as if the particle stood on the ground, and the
    /// contact carries the element's push (`heldImpulse`).
    std::span<const Vec3> holdNormals = {};
    /// Per batch: 1 where a corner is held (the kernel reads holdNormals only there).
    std::span<const uint8_t> heldBatches = {};
    /// Per particle: Σ of the elements' pushes into its contact that a held particle did not
    /// take (positional impulses, kg m, like λ); solveContacts adds them to the contact's λ_n.
    std::span<double> heldImpulse = {};
};

/// Each element's wave (0, 1, ...): one more than the largest wave of the earlier elements it
/// shares a particle with (0 if none). About nx + 2 ny + 4 nz waves for a box lattice.
std::vector<uint32_t> elementWaves(std::span<const HexElement> elements, size_t particleCount);

/// The batches of elements [first, first + count), which must be sorted by `wave`
/// (wave[k] belongs to element first + k), and their shapes appended to `shapes` (one per
/// distinct rest offsets, ℓ² and α_e, bit for bit; arrays.shapes is not read).
void appendBatches(const ElementArrays& arrays, std::span<const uint32_t> wave, uint32_t first,
                   uint32_t count, std::vector<ElementBatch>& batches, std::vector<BatchShape>& shapes);

/// The vector width of a sweep: eight lanes (pairs of batches) where the CPU has x86-64-v4
/// (AVX-512), else four; or four lanes whatever the CPU. Both give the same bits: elements of
/// one wave share no particle, and each lane's arithmetic is the same.
enum class ElementLanes { Widest, Four };

/// One Gauss-Seidel sweep of the shape-matching (and volume) constraints over the batches, with
/// α̃ = α_e invH2; batches with a held corner (arrays.heldBatches) project it with zero inverse
/// mass along its contact normal where the correction would push it into the contact. Returns
/// how many elements' rotations the lanes handed to extractRotation.
uint32_t solveElementBatches(std::span<const ElementBatch> batches, const ElementArrays& arrays,
                             double invH2, ElementLanes lanes = ElementLanes::Widest);

/// Whether this CPU runs the eight-lane sweep (x86-64-v4: AVX-512F, VL, DQ and BW).
bool wideElementLanes();

/// The eight-lane sweep (element_batch_wide.cpp); only on a CPU where wideElementLanes().
[[gnu::target("arch=x86-64-v4")]] uint32_t solveElementBatchesWide(std::span<const ElementBatch> batches,
                                                                   const ElementArrays& arrays, double invH2);

}  // namespace substep
