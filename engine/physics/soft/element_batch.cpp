#include "physics/soft/element_batch.h"

#include "physics/soft/element_batch_kernel.h"

#include <algorithm>
#include <bit>
#include <map>

namespace substep {
namespace {

/// One sweep four lanes at a time (AVX2, or SSE2 on the base ISA).
[[gnu::target_clones("arch=x86-64-v3", "default")]] uint32_t sweepFourLanes(std::span<const ElementBatch> batches,
                                                                          const ElementArrays& arrays,
                                                                          double invH2) {
    using Kernel = BatchKernel<simd::Lanes>;
    uint32_t handedOver = 0;
    const bool anyHeld = !arrays.heldBatches.empty();
    for (size_t b = 0; b < batches.size(); ++b)
        handedOver += Kernel::solveOne(batches[b], anyHeld && arrays.heldBatches[b] != 0, arrays, invH2);
    return handedOver;
}

}  // namespace

std::vector<uint32_t> elementWaves(std::span<const HexElement> elements, size_t particleCount) {
    std::vector<uint32_t> next(particleCount, 0);  // per particle: the first wave free of it
    std::vector<uint32_t> wave(elements.size(), 0);
    for (size_t e = 0; e < elements.size(); ++e) {
        uint32_t w = 0;
        for (uint32_t p : elements[e])
            w = std::max(w, next[p]);
        wave[e] = w;
        for (uint32_t p : elements[e])
            next[p] = w + 1;
    }
    return wave;
}

void appendBatches(const ElementArrays& arrays, std::span<const uint32_t> wave, uint32_t first,
                   uint32_t count, std::vector<ElementBatch>& batches, std::vector<BatchShape>& shapes) {
    const uint32_t end = first + count;
    const size_t start = batches.size();  // this body's first batch
    const auto shares = [&](uint32_t e, uint32_t from, uint32_t to) {
        for (uint32_t other = from; other < to; ++other)
            for (uint32_t p : arrays.elements[e])
                for (uint32_t o : arrays.elements[other])
                    if (p == o) return true;
        return false;
    };
    // This body's shapes, found by their bits (a tyre's 1104 elements have 24).
    std::map<std::array<uint64_t, 26>, uint32_t> shapeIndex;
    const auto shapeOf = [&](uint32_t element) {
        BatchShape shape;
        for (int j = 0; j < 8; ++j)
            for (int r = 0; r < 3; ++r) shape.rest[r][j] = arrays.restOffsets[element][j][r];
        shape.scale2 = arrays.scale2[element];
        shape.compliance = arrays.compliance[element];
        std::array<uint64_t, 26> bits;
        for (int i = 0; i < 26; ++i) bits[i] = std::bit_cast<uint64_t>(*shape.row(i));
        const auto [at, added] = shapeIndex.try_emplace(bits, static_cast<uint32_t>(shapes.size()));
        if (added) shapes.push_back(shape);
        return at->second;
    };
    // The body's particles end here: rows never reach past it (nor past its elements), whose
    // particles another thread may be solving meanwhile.
    uint32_t particleEnd = 0;
    for (uint32_t e = first; e < end; ++e)
        for (const uint32_t p : arrays.elements[e]) particleEnd = std::max(particleEnd, p + 1);
    std::vector<uint32_t> shapeOfElement(count);
    for (uint32_t e = first; e < end; ++e) shapeOfElement[e - first] = shapeOf(e);
    for (uint32_t e = first; e < end;) {
        ElementBatch batch{};
        batch.firstElement = e;
        batch.lanes = 1;
        // A batch whose first two elements have one shape stays within it: a tyre's batch ends
        // with its ring, so that the ring's last cells load as rows too (`rows`) instead of
        // being gathered together with the next ring's first.
        const uint32_t shape = shapeOfElement[e - first];
        const bool oneShapeStart = e + 1 < end && shapeOfElement[e + 1 - first] == shape;
        while (batch.lanes < kBatchLanes && e + batch.lanes < end &&
               wave[e + batch.lanes - first] == wave[e - first] &&
               !(oneShapeStart && shapeOfElement[e + batch.lanes - first] != shape) &&
               !shares(e + batch.lanes, e, e + batch.lanes))
            ++batch.lanes;
        for (int l = 0; l < kBatchLanes; ++l) {
            const uint32_t element =
                e + static_cast<uint32_t>(l < static_cast<int>(batch.lanes) ? l : 0);
            for (int j = 0; j < 8; ++j) batch.particle[j][l] = arrays.elements[element][j];
            batch.shape[l] = shapeOfElement[element - first];
            batch.volume = batch.volume || arrays.volumeCompliance[element] >= 0.0;
        }
        batch.oneShape = true;
        for (int l = 1; l < kBatchLanes; ++l) batch.oneShape = batch.oneShape && batch.shape[l] == batch.shape[0];
        batch.contiguous = batch.lanes == kBatchLanes && !batch.volume && batch.oneShape;
        for (int j = 0; j < 8; ++j)
            for (int l = 1; l < kBatchLanes; ++l)
                batch.contiguous = batch.contiguous && batch.particle[j][l] == batch.particle[j][0] + l;
        // Rows: four rows from lane 0's particles and element must lie inside the body, and each
        // corner has at most one lane outside its run.
        batch.rows = !batch.contiguous && batch.lanes >= 2 && !batch.volume && batch.oneShape && e + kBatchLanes <= end;
        for (int j = 0; j < 8; ++j) {
            uint32_t run = 1;
            while (run < batch.lanes && batch.particle[j][run] == batch.particle[j][0] + run) ++run;
            batch.run[j] = static_cast<uint8_t>(run);
            batch.strayLane[j] = run < batch.lanes ? static_cast<uint8_t>(run) : 0;
            batch.strayParticle[j] = batch.particle[j][batch.strayLane[j]];
            batch.strayCorners |= static_cast<uint8_t>(run < batch.lanes ? 1 << j : 0);
            batch.rows = batch.rows && batch.lanes - run <= 1 && batch.particle[j][0] + kBatchLanes <= particleEnd;
        }
        batches.push_back(batch);
        e += batch.lanes;
    }
    // Each contiguous batch paired with the next unpaired contiguous one of its wave, of its own
    // shape where there is one (the kernel then broadcasts one shape to all eight lanes); then
    // the rows batches and the contiguous ones left, among themselves.
    const auto pairUp = [&](auto&& free, bool rowsPair) {
        for (size_t b = start; b < batches.size(); ++b) {
            if (!free(b)) continue;
            const uint32_t ownWave = wave[batches[b].firstElement - first];
            size_t partner = 0, sameShape = 0;
            for (size_t next = b + 1; next < batches.size() && wave[batches[next].firstElement - first] == ownWave;
                 ++next) {
                if (!free(next)) continue;
                if (partner == 0) partner = next;
                if (batches[next].shape[0] == batches[b].shape[0]) {
                    sameShape = next;
                    break;
                }
            }
            if (sameShape != 0) partner = sameShape;
            if (partner == 0) continue;
            batches[b].partnerAhead = batches[partner].partnerBehind = static_cast<uint32_t>(partner - b);
            batches[b].rowsPair = batches[partner].rowsPair = rowsPair;
        }
    };
    const auto unpaired = [&](size_t b) { return batches[b].partnerAhead == 0 && batches[b].partnerBehind == 0; };
    pairUp([&](size_t b) { return batches[b].contiguous && unpaired(b); }, false);
    pairUp([&](size_t b) { return (batches[b].contiguous || batches[b].rows) && unpaired(b); }, true);
}

bool wideElementLanes() {
    // x86-64-v4's AVX-512 subsets (every CPU with them has the rest of x86-64-v4 and -v3).
    static const bool wide = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                             __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw");
    return wide;
}

uint32_t solveElementBatches(std::span<const ElementBatch> batches, const ElementArrays& arrays, double invH2,
                             ElementLanes lanes) {
    if (lanes == ElementLanes::Widest && wideElementLanes()) return solveElementBatchesWide(batches, arrays, invH2);
    return sweepFourLanes(batches, arrays, invH2);
}

}  // namespace substep
