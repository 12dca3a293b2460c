#pragma once
/// Two element batches of one wave side by side in eight lanes (one AVX-512 register), their
/// corners loaded as rows: what the projection sweep (element_batch_kernel.h) and the damping
/// (element_damping_kernel.h) read and write of a pair of contiguous or rows batches
/// (ElementBatch::contiguous, ElementBatch::rows: a tyre's ring ends, rows from lane 0 and a
/// "stray" lane put in by a select).
///
/// GCC: a file that uses these for x86-64-v4 includes this header under `#pragma GCC target`
/// (element_batch_kernel.h says why: 64-byte compares and selects defined for a narrower target
/// are lowered lane by lane), with the headers below included before the pragma. Hence the
/// anonymous namespace: each file its own copy, built for its own target.

#include "physics/soft/element_batch.h"
#include "physics/soft/lanes.h"

#include <cstddef>

namespace substep {
namespace {

/// Eight doubles: the lanes of two batches, the first's in 0-3.
using WideLanes = double __attribute__((vector_size(8 * sizeof(double))));

/// Two halves' four lanes as eight.
[[gnu::always_inline]] inline void join(WideLanes& v, const simd::Lanes& lo, const simd::Lanes& hi) {
    v = __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
}

/// Eight lanes' halves stored at lo and hi.
[[gnu::always_inline]] inline void split(double* lo, double* hi, const WideLanes& v) {
    const simd::Lanes a = __builtin_shufflevector(v, v, 0, 1, 2, 3), b = __builtin_shufflevector(v, v, 4, 5, 6, 7);
    simd::store(lo, a), simd::store(hi, b);
}

/// simd::loadPoints for two runs of four points at once: lanes 0-3 from a, 4-7 from b. Each
/// shuffle is loadPoints' on both halves (an index i of its first vector is i and i + 4 here,
/// an index 4 + i of its second 8 + i and 12 + i).
[[gnu::always_inline]] inline void loadPoints(const double* a, const double* b, WideLanes& x, WideLanes& y,
                                              WideLanes& z) {
    simd::Lanes a0, a1, a2, b0, b1, b2;
    simd::load(a0, a), simd::load(a1, a + 4), simd::load(a2, a + 8);
    simd::load(b0, b), simd::load(b1, b + 4), simd::load(b2, b + 8);
    WideLanes v0, v1, v2;
    join(v0, a0, b0), join(v1, a1, b1), join(v2, a2, b2);
    x = __builtin_shufflevector(__builtin_shufflevector(v0, v1, 0, 3, 10, 0, 4, 7, 14, 4), v2, 0, 1, 2, 9, 4, 5, 6, 13);
    y = __builtin_shufflevector(__builtin_shufflevector(v0, v1, 1, 8, 11, 0, 5, 12, 15, 4), v2, 0, 1, 2, 10, 4, 5, 6, 14);
    z = __builtin_shufflevector(__builtin_shufflevector(v0, v1, 2, 9, 0, 0, 6, 13, 4, 4), v2, 0, 1, 8, 11, 4, 5, 12, 15);
}

/// The inverse of the above, as rows: row k holds doubles 4k to 4k + 3 of the first run's 12 in
/// lanes 0-3 and of the second's in lanes 4-7 (simd::storePoints' on both halves).
[[gnu::always_inline]] inline void pointRows(const WideLanes& x, const WideLanes& y, const WideLanes& z,
                                             WideLanes (&rows)[3]) {
    const WideLanes xy01 = __builtin_shufflevector(x, y, 0, 8, 1, 9, 4, 12, 5, 13);
    const WideLanes xy23 = __builtin_shufflevector(x, y, 2, 10, 3, 11, 6, 14, 7, 15);
    const WideLanes yz12 = __builtin_shufflevector(y, z, 1, 9, 2, 10, 5, 13, 6, 14);
    rows[0] = __builtin_shufflevector(xy01, z, 0, 1, 8, 2, 4, 5, 12, 6);
    rows[1] = __builtin_shufflevector(yz12, xy23, 0, 1, 8, 9, 4, 5, 12, 13);
    const WideLanes xyz23 = __builtin_shufflevector(xy23, z, 2, 3, 10, 11, 6, 7, 14, 15);
    rows[2] = __builtin_shufflevector(xyz23, xyz23, 2, 0, 1, 3, 6, 4, 5, 7);
}

/// The inverse of the two runs' loadPoints.
[[gnu::always_inline]] inline void storePoints(double* a, double* b, const WideLanes& x, const WideLanes& y,
                                               const WideLanes& z) {
    WideLanes rows[3];
    pointRows(x, y, z, rows);
    for (int k = 0; k < 3; ++k) split(a + 4 * k, b + 4 * k, rows[k]);
}

/// The first `count` doubles of v at p (all four, or none), the others left alone: written back
/// as read, they would make the next wave's loads of them wait for this store (a load that
/// spans two stores is not forwarded from them).
[[gnu::always_inline]] inline void storeFirst(double* p, const simd::Lanes& v, int count) {
    if (count >= 4) {
        simd::store(p, v);
    } else if (count > 0) {
        p[0] = v[0];
        if (count > 1) p[1] = v[1];
        if (count > 2) p[2] = v[2];
    }
}

/// storePoints for two runs, of their first `countA` and `countB` points only (ElementBatch::rows).
[[gnu::always_inline]] inline void storePoints(double* a, double* b, const WideLanes& x, const WideLanes& y,
                                               const WideLanes& z, int countA, int countB) {
    WideLanes rows[3];
    pointRows(x, y, z, rows);
    for (int k = 0; k < 3; ++k) {
        storeFirst(a + 4 * k, __builtin_shufflevector(rows[k], rows[k], 0, 1, 2, 3), 3 * countA - 4 * k);
        storeFirst(b + 4 * k, __builtin_shufflevector(rows[k], rows[k], 4, 5, 6, 7), 3 * countB - 4 * k);
    }
}

/// Per lane, all bits set or none: the result of comparing WideLanes.
using WideMask = decltype(WideLanes{} < WideLanes{});

/// Rows: the lanes of corner j's strays, one lane of each batch at most (a corner without one
/// names lane 0 and its own particle, which the select and the write-back leave as they are).
/// The strays go in by a select: a lane picked at run time would take the vector through memory.
[[gnu::always_inline]] inline void strayMask(const ElementBatch* const* batches, int j, WideMask& stray) {
    const double lo = batches[0]->strayLane[j], hi = batches[1]->strayLane[j];
    const simd::Lanes a = {lo, lo, lo, lo}, b = {hi, hi, hi, hi};
    WideLanes lane;
    join(lane, a, b);
    const WideLanes index = {0, 1, 2, 3, 0, 1, 2, 3};
    stray = index == lane;
}

/// Rows: corner j's strays' values, base[stride p + offset] for each batch's stray p, in that
/// batch's lanes.
[[gnu::always_inline]] inline void strayValues(const ElementBatch* const* batches, int j, const double* base,
                                               int stride, int offset, WideLanes& v) {
    const double lo = base[stride * size_t(batches[0]->strayParticle[j]) + offset];
    const double hi = base[stride * size_t(batches[1]->strayParticle[j]) + offset];
    const simd::Lanes a = {lo, lo, lo, lo}, b = {hi, hi, hi, hi};
    join(v, a, b);
}

/// Corner j's points of two batches side by side (contiguous or rows), each batch's four rows
/// from `points` (packed Vec3s) at its lane 0's particle; with `Rows`, each batch's stray put in
/// by the select `stray` (strayMask) where strayCorners has bit j.
template <bool Rows>
[[gnu::always_inline]] inline void loadCornerPoints(const ElementBatch* const* batches, int j, const double* points,
                                                    unsigned strayCorners, const WideMask& stray, WideLanes& x,
                                                    WideLanes& y, WideLanes& z) {
    loadPoints(points + 3 * size_t(batches[0]->particle[j][0]), points + 3 * size_t(batches[1]->particle[j][0]), x, y,
               z);
    if (Rows && (strayCorners >> j & 1) != 0) {
        WideLanes sx, sy, sz;
        strayValues(batches, j, points, 3, 0, sx), strayValues(batches, j, points, 3, 1, sy);
        strayValues(batches, j, points, 3, 2, sz);
        x = stray ? sx : x, y = stray ? sy : y, z = stray ? sz : z;
    }
}

/// The inverse of loadCornerPoints: with `Rows`, each batch's own points only (its run's rows,
/// then its stray), else all eight.
template <bool Rows>
[[gnu::always_inline]] inline void storeCornerPoints(const ElementBatch* const* batches, int j, double* points,
                                                     unsigned strayCorners, const WideLanes& x, const WideLanes& y,
                                                     const WideLanes& z) {
    double* const a = points + 3 * size_t(batches[0]->particle[j][0]);
    double* const b = points + 3 * size_t(batches[1]->particle[j][0]);
    if constexpr (!Rows) {
        storePoints(a, b, x, y, z);
    } else {
        storePoints(a, b, x, y, z, batches[0]->run[j], batches[1]->run[j]);
        if ((strayCorners >> j & 1) == 0) return;
        for (int h = 0; h < 2; ++h) {
            const int lane = h * kBatchLanes + batches[h]->strayLane[j];
            double* p = points + 3 * size_t(batches[h]->strayParticle[j]);
            p[0] = x[lane], p[1] = y[lane], p[2] = z[lane];
        }
    }
}

}  // namespace
}  // namespace substep
