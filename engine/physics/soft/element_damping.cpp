// The element damping four lanes at a time (AVX-512VL, AVX2 or SSE2: `target_clones`), and the
// choice of lanes: eight (element_damping_wide.cpp) where the CPU has x86-64-v4.
#include "physics/soft/element_damping.h"

#include "physics/soft/element_damping_kernel.h"

namespace substep {
namespace {

[[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]] void dampFourLanes(
    std::span<const ElementBatch> batches, const DampingArrays& arrays, double dt) {
    DampingFractions fractions{.dt = dt};
    for (const ElementBatch& batch : batches) {
        simd::Lanes fraction;
        if (fractions.of(batch, arrays.damping, fraction)) DampingKernel<simd::Lanes>::dampOne(batch, arrays, fraction);
    }
}

}  // namespace

void dampElementBatches(std::span<const ElementBatch> batches, const DampingArrays& arrays, double dt,
                        ElementLanes lanes) {
    if (lanes == ElementLanes::Widest && wideElementLanes()) return dampElementBatchesWide(batches, arrays, dt);
    dampFourLanes(batches, arrays, dt);
}

}  // namespace substep
