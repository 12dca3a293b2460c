// The element damping eight lanes at a time, for CPUs with x86-64-v4 (element_damping_kernel.h):
// the pairs of the projection sweep (ElementBatch::partnerAhead: contiguous or rows batches of
// one wave) side by side in one AVX-512 register; the other batches, and a pair of which one
// batch is not damped, four lanes at a time as in element_damping.cpp, compiled for the same
// target.
#include "physics/soft/element_batch.h"
#include "physics/soft/element_damping.h"
#include "physics/soft/lanes.h"

#include <cmath>

// GCC: everything the kernel compares or selects in 64-byte vectors is defined under the pragma
// (element_batch_kernel.h says why); its other headers are included above, outside it.
#if !defined(__clang__)
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v4")
#endif
#include "physics/soft/element_damping_kernel.h"
#if !defined(__clang__)
#pragma GCC pop_options
#endif

namespace substep {

[[gnu::target("arch=x86-64-v4")]] void dampElementBatchesWide(std::span<const ElementBatch> batches,
                                                              const DampingArrays& arrays, double dt) {
    using Four = DampingKernel<simd::Lanes>;
    using Eight = DampingKernel<WideLanes>;
    DampingFractions fractions{.dt = dt};
    for (size_t b = 0; b < batches.size(); ++b) {
        const ElementBatch& batch = batches[b];
        if (batch.partnerBehind != 0) continue;  // damped with the partner behind it
        simd::Lanes fraction;
        const bool damped = fractions.of(batch, arrays.damping, fraction);
        if (batch.partnerAhead == 0) {
            if (damped) Four::dampOne(batch, arrays, fraction);
            continue;
        }
        // A lane with fraction 0 is not left bit for bit (−0 + 0 is +0): a batch the four
        // lanes would skip is skipped here too.
        const ElementBatch& partner = batches[b + batch.partnerAhead];
        simd::Lanes partnerFraction;
        const bool partnerDamped = fractions.of(partner, arrays.damping, partnerFraction);
        if (damped && partnerDamped) {
            const ElementBatch* const pair[2] = {&batch, &partner};
            WideLanes both;
            join(both, fraction, partnerFraction);
            if (batch.rowsPair) Eight::dampPair<true>(pair, arrays, both);
            else Eight::dampPair<false>(pair, arrays, both);
        } else if (damped) {
            Four::dampOne(batch, arrays, fraction);
        } else if (partnerDamped) {
            Four::dampOne(partner, arrays, partnerFraction);
        }
    }
}

}  // namespace substep
