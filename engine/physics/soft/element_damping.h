#pragma once
/// Each element's deformation rate damped once per frame (SoftSystem::damp), four elements at a
/// time (eight with AVX-512): the batches of the shape-matching projection (element_batch.h)
/// hold elements that share no particle, so their lanes damp side by side what the elements one
/// after the other would.
///
/// Per element, each corner's velocity moves towards the element's rigid motion
/// v̄ + ω × (x − c) (mass-weighted with the particles' masses: c the centre of mass, v̄ the mean
/// velocity, ω = I⁻¹ L from the corners' angular momentum L and inertia I about c) by
/// 1 − exp(−k dt): deformation rates decay at k whatever their direction, rigid motion is
/// untouched, and each element's momentum and angular momentum are kept. A collapsed element
/// (I not invertible) is damped towards its mean velocity only.

#include "physics/math.h"
#include "physics/soft/element_batch.h"

#include <span>

namespace substep {

/// What the damping reads and writes, the SoftSystem's arrays.
struct DampingArrays {
    std::span<const Vec3> positions;
    std::span<Vec3> velocities;
    std::span<const double> mass;       ///< per particle
    std::span<const double> damping;    ///< per element: k (1/s); ≤ 0 leaves it alone
};

/// Damps every batch's elements over a frame of length dt: eight lanes (the sweep's pairs of
/// batches, ElementBatch::partnerAhead) where the CPU has x86-64-v4 and `lanes` is Widest,
/// else four; the same bits either way (each lane's arithmetic is the same, and a pair's
/// batches, of one wave, share no particle).
void dampElementBatches(std::span<const ElementBatch> batches, const DampingArrays& arrays, double dt,
                        ElementLanes lanes = ElementLanes::Widest);

/// The eight lanes (element_damping_wide.cpp); only on a CPU where wideElementLanes().
[[gnu::target("arch=x86-64-v4")]] void dampElementBatchesWide(std::span<const ElementBatch> batches,
                                                              const DampingArrays& arrays, double dt);

}  // namespace substep
