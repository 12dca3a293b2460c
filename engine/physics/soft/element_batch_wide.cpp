// The element sweep eight lanes at a time, for CPUs with x86-64-v4 (element_batch_kernel.h):
// pairs of contiguous batches of one wave side by side, in one AVX-512 register, and pairs with
// a rows batch (a tyre's ring ends: ElementBatch::rows) likewise; the other batches (gathered,
// held, with the volume constraint or unpaired) four lanes at a time as in element_batch.cpp,
// compiled for the same target.
#include "physics/soft/element_batch.h"
#include "physics/soft/lanes.h"
#include "physics/soft/shape_matching.h"

#include <cmath>
#include <cstring>

// GCC: everything the kernel compares or selects in 64-byte vectors is defined under the pragma
// (element_batch_kernel.h says why); its headers are included above, outside it. Clang lowers
// vectors after inlining, for the function they end up in: the attribute below is enough.
#if !defined(__clang__)
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v4")
#endif
#include "physics/soft/element_batch_kernel.h"
#if !defined(__clang__)
#pragma GCC pop_options
#endif

namespace substep {

[[gnu::target("arch=x86-64-v4")]] uint32_t solveElementBatchesWide(std::span<const ElementBatch> batches,
                                                                   const ElementArrays& arrays, double invH2) {
    using Four = BatchKernel<simd::Lanes>;
    using Eight = BatchKernel<WideLanes>;
    uint32_t handedOver = 0;
    const bool anyHeld = !arrays.heldBatches.empty();
    const auto held = [&](size_t b) { return anyHeld && arrays.heldBatches[b] != 0; };
    for (size_t b = 0; b < batches.size(); ++b) {
        const ElementBatch& batch = batches[b];
        // Projected with the partner behind it already (neither held).
        if (batch.partnerBehind != 0 && !held(b) && !held(b - batch.partnerBehind)) continue;
        const size_t ahead = b + batch.partnerAhead;
        const ElementBatch* const pair[2] = {&batch, &batches[ahead]};
        const bool oneShape = batch.shape[0] == batches[ahead].shape[0];
        if (!held(b) && batch.partnerAhead != 0 && !held(ahead) && batch.rowsPair)
            handedOver += oneShape ? Eight::solve<true, false, true, true>(pair, arrays, invH2)
                                   : Eight::solve<true, false, false, true>(pair, arrays, invH2);
        else if (!held(b) && batch.partnerAhead != 0 && !held(ahead))
            handedOver += oneShape ? Eight::solve<true, false, true>(pair, arrays, invH2)
                                   : Eight::solve<true, false>(pair, arrays, invH2);
        else
            handedOver += Four::solveOne(batch, held(b), arrays, invH2);
    }
    return handedOver;
}

}  // namespace substep
