#pragma once
/// The element batches' projection kernel (element_batch.h), written once for four lanes (one
/// batch: AVX2 or SSE2) and eight (two batches of one wave side by side: one AVX-512 register).
///
/// Two files compile it: element_batch.cpp for x86-64-v3 and the base ISA (`target_clones`),
/// element_batch_wide.cpp for x86-64-v4 (under `#pragma GCC target`, which must enclose every
/// function that compares or selects 64-byte vectors: GCC 12 lowers those lane by lane in a
/// function compiled for a narrower target, also when it is later inlined into an AVX-512 one).
/// Hence the anonymous namespace: each file has its own copy, built for its own target, and no
/// copy built for AVX-512 can stand in for the other at link time. Every header this one
/// includes must be included before the pragma, except batch_pair_lanes.h (the pairs' loads and
/// stores, shared with the damping), which must be included under it.

#include "physics/soft/batch_pair_lanes.h"
#include "physics/soft/element_batch.h"
#include "physics/soft/lanes.h"
#include "physics/soft/shape_matching.h"

#include <cmath>
#include <cstring>

namespace substep {
namespace {

/// A lane's Newton step turned more than this (rad², 1e-3 rad): integrateRotation's series
/// takes its third term, and the quaternion's new norm its square root.
constexpr double kLaneTurn2 = 1e-6;

static_assert(sizeof(Quat) == 4 * sizeof(double), "rotations are read as packed (x, y, z, w)");

/// Four consecutive quaternions, stored (x, y, z, w) each, into lanes: a 4 x 4 transpose.
[[gnu::always_inline]] inline void loadRotations(const double* p, simd::Lanes& w, simd::Lanes& x,
                                                 simd::Lanes& y, simd::Lanes& z) {
    simd::Lanes q0, q1, q2, q3;
    simd::load(q0, p), simd::load(q1, p + 4), simd::load(q2, p + 8), simd::load(q3, p + 12);
    const simd::Lanes lo01 = __builtin_shufflevector(q0, q1, 0, 4, 1, 5);  // x0 x1 y0 y1
    const simd::Lanes lo23 = __builtin_shufflevector(q2, q3, 0, 4, 1, 5);
    const simd::Lanes hi01 = __builtin_shufflevector(q0, q1, 2, 6, 3, 7);  // z0 z1 w0 w1
    const simd::Lanes hi23 = __builtin_shufflevector(q2, q3, 2, 6, 3, 7);
    x = __builtin_shufflevector(lo01, lo23, 0, 1, 4, 5);
    y = __builtin_shufflevector(lo01, lo23, 2, 3, 6, 7);
    z = __builtin_shufflevector(hi01, hi23, 0, 1, 4, 5);
    w = __builtin_shufflevector(hi01, hi23, 2, 3, 6, 7);
}

/// Two runs of four quaternions, at a and b, into eight lanes (the transpose above on both).
[[gnu::always_inline]] inline void loadRotations(const double* a, const double* b, WideLanes& w, WideLanes& x,
                                                 WideLanes& y, WideLanes& z) {
    WideLanes q[4];
    for (int k = 0; k < 4; ++k) {
        simd::Lanes lo, hi;
        simd::load(lo, a + 4 * k), simd::load(hi, b + 4 * k);
        join(q[k], lo, hi);
    }
    const WideLanes lo01 = __builtin_shufflevector(q[0], q[1], 0, 8, 1, 9, 4, 12, 5, 13);
    const WideLanes lo23 = __builtin_shufflevector(q[2], q[3], 0, 8, 1, 9, 4, 12, 5, 13);
    const WideLanes hi01 = __builtin_shufflevector(q[0], q[1], 2, 10, 3, 11, 6, 14, 7, 15);
    const WideLanes hi23 = __builtin_shufflevector(q[2], q[3], 2, 10, 3, 11, 6, 14, 7, 15);
    x = __builtin_shufflevector(lo01, lo23, 0, 1, 8, 9, 4, 5, 12, 13);
    y = __builtin_shufflevector(lo01, lo23, 2, 3, 10, 11, 6, 7, 14, 15);
    z = __builtin_shufflevector(hi01, hi23, 0, 1, 8, 9, 4, 5, 12, 13);
    w = __builtin_shufflevector(hi01, hi23, 2, 3, 10, 11, 6, 7, 14, 15);
}

/// The inverse of loadRotations.
[[gnu::always_inline]] inline void storeRotations(double* p, const simd::Lanes& w, const simd::Lanes& x,
                                                  const simd::Lanes& y, const simd::Lanes& z) {
    const simd::Lanes xy01 = __builtin_shufflevector(x, y, 0, 4, 1, 5);  // x0 y0 x1 y1
    const simd::Lanes xy23 = __builtin_shufflevector(x, y, 2, 6, 3, 7);
    const simd::Lanes zw01 = __builtin_shufflevector(z, w, 0, 4, 1, 5);
    const simd::Lanes zw23 = __builtin_shufflevector(z, w, 2, 6, 3, 7);
    simd::store(p, __builtin_shufflevector(xy01, zw01, 0, 1, 4, 5));
    simd::store(p + 4, __builtin_shufflevector(xy01, zw01, 2, 3, 6, 7));
    simd::store(p + 8, __builtin_shufflevector(xy23, zw23, 0, 1, 4, 5));
    simd::store(p + 12, __builtin_shufflevector(xy23, zw23, 2, 3, 6, 7));
}

/// The inverse of the two runs' loadRotations, for the first `countA` and `countB` quaternions.
[[gnu::always_inline]] inline void storeRotations(double* a, double* b, const WideLanes& w, const WideLanes& x,
                                                  const WideLanes& y, const WideLanes& z, int countA = 4,
                                                  int countB = 4) {
    const WideLanes xy01 = __builtin_shufflevector(x, y, 0, 8, 1, 9, 4, 12, 5, 13);
    const WideLanes xy23 = __builtin_shufflevector(x, y, 2, 10, 3, 11, 6, 14, 7, 15);
    const WideLanes zw01 = __builtin_shufflevector(z, w, 0, 8, 1, 9, 4, 12, 5, 13);
    const WideLanes zw23 = __builtin_shufflevector(z, w, 2, 10, 3, 11, 6, 14, 7, 15);
    const WideLanes q[4] = {__builtin_shufflevector(xy01, zw01, 0, 1, 8, 9, 4, 5, 12, 13),
                            __builtin_shufflevector(xy01, zw01, 2, 3, 10, 11, 6, 7, 14, 15),
                            __builtin_shufflevector(xy23, zw23, 0, 1, 8, 9, 4, 5, 12, 13),
                            __builtin_shufflevector(xy23, zw23, 2, 3, 10, 11, 6, 7, 14, 15)};
    for (int k = 0; k < 4; ++k) {
        if (countA == 4 && countB == 4) {
            split(a + 4 * k, b + 4 * k, q[k]);
            continue;
        }
        if (k < countA) simd::store(a + 4 * k, __builtin_shufflevector(q[k], q[k], 0, 1, 2, 3));
        if (k < countB) simd::store(b + 4 * k, __builtin_shufflevector(q[k], q[k], 4, 5, 6, 7));
    }
}

/// The kernel over `Lanes` (simd::Lanes: one batch; WideLanes: two).
template <class Lanes>
struct BatchKernel {
    static constexpr int kLanes = sizeof(Lanes) / sizeof(double);
    static constexpr int kHalves = kLanes / kBatchLanes;  ///< batches side by side
    static_assert(kHalves * kBatchLanes == kLanes && (kHalves == 1 || kHalves == 2));

    /// Per lane, all bits set or none: the result of comparing Lanes.
    using Mask = decltype(Lanes{} < Lanes{});

    [[gnu::always_inline]] static bool anyLane(const Mask& m) {
        auto bits = m[0];
        for (int l = 1; l < kLanes; ++l)
            bits |= m[l];
        return bits != 0;
    }

    /// Square roots in place, lane by lane (vectorised with -fno-math-errno).
    [[gnu::always_inline]] static void squareRoot(Lanes& v) {
        for (int l = 0; l < kLanes; ++l)
            v[l] = std::sqrt(v[l]);
    }

    /// Row `index` of the lanes' shapes (BatchShape::row): one shape's value broadcast to each
    /// batch's four lanes where its lanes have one shape (always for two batches side by side;
    /// `OneShape`: both batches have the same), else lane by lane.
    template <bool OneShape>
    [[gnu::always_inline]] static void loadShapeRow(Lanes& v, const ElementBatch* const* batches,
                                                    const BatchShape* shapes, int index) {
        if constexpr (kHalves == 1) {
            const ElementBatch& batch = *batches[0];
            if (OneShape || batch.oneShape) {
                const double x = *shapes[batch.shape[0]].row(index);
                v = Lanes{x, x, x, x};
                return;
            }
            v = Lanes{*shapes[batch.shape[0]].row(index), *shapes[batch.shape[1]].row(index),
                      *shapes[batch.shape[2]].row(index), *shapes[batch.shape[3]].row(index)};
        } else {
            const double lo = *shapes[batches[0]->shape[0]].row(index);
            if constexpr (OneShape) {
                v = Lanes{lo, lo, lo, lo, lo, lo, lo, lo};
                return;
            }
            const double hi = *shapes[batches[1]->shape[0]].row(index);
            const simd::Lanes a = {lo, lo, lo, lo}, b = {hi, hi, hi, hi};
            join(v, a, b);
        }
    }

    /// The rotation matrices of the lanes' unit quaternions.
    [[gnu::always_inline]] static void rotationMatrix(const Lanes& w, const Lanes& qx, const Lanes& qy,
                                                      const Lanes& qz, Lanes& r00, Lanes& r01, Lanes& r02,
                                                      Lanes& r10, Lanes& r11, Lanes& r12, Lanes& r20,
                                                      Lanes& r21, Lanes& r22) {
        r00 = 1 - 2 * (qy * qy + qz * qz), r01 = 2 * (qx * qy - w * qz), r02 = 2 * (qx * qz + w * qy);
        r10 = 2 * (qx * qy + w * qz), r11 = 1 - 2 * (qx * qx + qz * qz), r12 = 2 * (qy * qz - w * qx);
        r20 = 2 * (qx * qz - w * qy), r21 = 2 * (qy * qz + w * qx), r22 = 1 - 2 * (qx * qx + qy * qy);
    }

    /// One Newton step of extractRotation (shape_matching.h) for the lanes' A and rotation R:
    /// with B = Rᵀ A = S + [u]×, the turn t (in R's frame) solving (tr S 1 − S) t = 2u, and
    /// where tr S 1 − S is positive definite (t is 0 where it is not).
    [[gnu::always_inline]] static void newtonTurn(const Lanes (&am)[3][3], const Lanes& spread, const Lanes& r00,
                                                  const Lanes& r01, const Lanes& r02, const Lanes& r10,
                                                  const Lanes& r11, const Lanes& r12, const Lanes& r20,
                                                  const Lanes& r21, const Lanes& r22, Lanes& tx, Lanes& ty,
                                                  Lanes& tz, Mask& definite) {
        const Lanes zero = {}, one = zero + 1.0;
        const Lanes b00 = r00 * am[0][0] + r10 * am[1][0] + r20 * am[2][0];
        const Lanes b01 = r00 * am[0][1] + r10 * am[1][1] + r20 * am[2][1];
        const Lanes b02 = r00 * am[0][2] + r10 * am[1][2] + r20 * am[2][2];
        const Lanes b10 = r01 * am[0][0] + r11 * am[1][0] + r21 * am[2][0];
        const Lanes b11 = r01 * am[0][1] + r11 * am[1][1] + r21 * am[2][1];
        const Lanes b12 = r01 * am[0][2] + r11 * am[1][2] + r21 * am[2][2];
        const Lanes b20 = r02 * am[0][0] + r12 * am[1][0] + r22 * am[2][0];
        const Lanes b21 = r02 * am[0][1] + r12 * am[1][1] + r22 * am[2][1];
        const Lanes b22 = r02 * am[0][2] + r12 * am[1][2] + r22 * am[2][2];
        const Lanes ux = b21 - b12, uy = b02 - b20, uz = b10 - b01;  // 2u
        const Lanes trace = b00 + b11 + b22;
        const Lanes m00 = trace - b00, m11 = trace - b11, m22 = trace - b22;
        const Lanes m01 = -0.5 * (b01 + b10), m02 = -0.5 * (b02 + b20), m12 = -0.5 * (b12 + b21);
        const Lanes c00 = m11 * m22 - m12 * m12, c01 = m02 * m12 - m01 * m22, c02 = m01 * m12 - m02 * m11;
        const Lanes c11 = m00 * m22 - m02 * m02, c12 = m01 * m02 - m00 * m12, c22 = m00 * m11 - m01 * m01;
        const Lanes det = m00 * c00 + m01 * c01 + m02 * c02;
        const Lanes floor = 1e-6 * (trace < 0 ? -trace : trace) + 1e-9 * spread;
        definite = (m00 > floor) & (c22 > floor * floor) & (det > floor * floor * floor);
        const Lanes inverse = definite ? one / det : zero;
        tx = (c00 * ux + c01 * uy + c02 * uz) * inverse;
        ty = (c01 * ux + c11 * uy + c12 * uz) * inverse;
        tz = (c02 * ux + c12 * uy + c22 * uz) * inverse;
    }

    /// Turns the lanes' quaternions q by ω = R t (world) as integrateRotation does,
    /// q + ½ (0, s ω) q renormalised, with `halfScale` = ½ s (s its tan(|θ|/2)/(|θ|/2) series).
    /// The new norm is 1 + ε, ε ≤ |½ s ω|² plus the rounding of |q|: lanes in `exact` divide by
    /// its square root, the others (ε below 1e-6) take 1/sqrt(1 + ε) by its series, whose ε³
    /// terms are under 1e-18. Lanes in `still` keep their quaternion bit for bit.
    [[gnu::always_inline]] static void turnLanes(const Lanes& r00, const Lanes& r01, const Lanes& r02,
                                                 const Lanes& r10, const Lanes& r11, const Lanes& r12,
                                                 const Lanes& r20, const Lanes& r21, const Lanes& r22,
                                                 const Lanes& tx, const Lanes& ty, const Lanes& tz,
                                                 const Lanes& halfScale, const Mask& still, const Mask& exact,
                                                 Lanes& w, Lanes& qx, Lanes& qy, Lanes& qz) {
        const Lanes ox = (r00 * tx + r01 * ty + r02 * tz) * halfScale;  // ½ s ω
        const Lanes oy = (r10 * tx + r11 * ty + r12 * tz) * halfScale;
        const Lanes oz = (r20 * tx + r21 * ty + r22 * tz) * halfScale;
        const Lanes nw = w - ox * qx - oy * qy - oz * qz;
        const Lanes nx = qx + ox * w + oy * qz - oz * qy;
        const Lanes ny = qy - ox * qz + oy * w + oz * qx;
        const Lanes nz = qz + ox * qy - oy * qx + oz * w;
        const Lanes squared = nw * nw + nx * nx + ny * ny + nz * nz;
        const Lanes epsilon = squared - 1.0;
        Lanes norm = 1.0 - epsilon * (0.5 - 0.375 * epsilon);
        if (anyLane(exact)) {
            Lanes root = squared;
            squareRoot(root);
            norm = exact ? 1.0 / root : norm;
        }
        w = still ? w : nw * norm, qx = still ? qx : nx * norm;
        qy = still ? qy : ny * norm, qz = still ? qz : nz * norm;
    }

    /// Projects `batches` (one, or two of one wave whose corners are consecutive particles and
    /// that have no volume constraint and no held corner), every lane's arithmetic in vector
    /// registers: the corners gathered once from the particle array into lanes (the batch holds
    /// their indices; a contiguous batch loads them as rows and transposes them), the rest
    /// offsets, ℓ² and α_e broadcast from the batches' shapes (`OneShape`: both batches side by
    /// side have one), the inverse masses from the particles', one warm-started Newton step of
    /// the rotation extraction, the deviations and the XPBD update (Eq. 4), and the corners
    /// scattered back.
    ///
    /// `Rows` (two batches side by side, contiguous or rows, ElementBatch::rows): each batch's
    /// rows are loaded from its lane 0 as a contiguous batch's and its strays put in by a
    /// select; only its own lanes' doubles, rotations and multipliers are written back.
    template <bool Contiguous, bool Held, bool OneShape = false, bool Rows = false>
    [[gnu::always_inline]] static uint32_t solve(const ElementBatch* const* batches, const ElementArrays& arrays,
                                                 double invH2);

    /// One batch, by its kind: gathered or contiguous corners, with a held corner or without.
    [[gnu::always_inline]] static uint32_t solveOne(const ElementBatch& batch, bool held, const ElementArrays& arrays,
                                                    double invH2) {
        const ElementBatch* const one[1] = {&batch};
        if (held) [[unlikely]]
            return batch.contiguous ? solve<true, true, true>(one, arrays, invH2) : solve<false, true>(one, arrays, invH2);
        return batch.contiguous ? solve<true, false, true>(one, arrays, invH2) : solve<false, false>(one, arrays, invH2);
    }
};

template <class Lanes>
template <bool Contiguous, bool Held, bool OneShape, bool Rows>
[[gnu::always_inline]] inline uint32_t BatchKernel<Lanes>::solve(const ElementBatch* const* batches, const ElementArrays& arrays, double invH2) {
    static_assert(kHalves == 1 || (Contiguous && !Held), "two batches side by side: the common path only");
    static_assert(!Rows || kHalves == 2, "rows: two batches side by side");
    const ElementBatch& batch = *batches[0];  // the one batch of the gathers and held corners
    uint32_t handedOver = 0;
    const uint32_t first = batch.firstElement;
    const int lanes = kHalves == 1 ? static_cast<int>(batch.lanes) : kLanes;
    double* const pos = arrays.positions.data()->data();
    // Lane l's element, and batch h's corner j of its first lane.
    const auto elementOf = [&](int l) {
        return batches[l / kBatchLanes]->firstElement + static_cast<uint32_t>(l % kBatchLanes);
    };
    const auto corner = [&](int h, int j) { return pos + 3 * size_t(batches[h]->particle[j][0]); };
    const auto rotationsOf = [&](int h) { return arrays.rotations[batches[h]->firstElement].coeffs().data(); };
    const auto lambdaOf = [&](int h) { return &arrays.lambda[batches[h]->firstElement]; };
    // Rows: each batch's lanes, and whether lane l is one of them.
    const int lanesOf[2] = {static_cast<int>(batches[0]->lanes), static_cast<int>(batches[kHalves - 1]->lanes)};
    const auto own = [&](int l) { return !Rows || l % kBatchLanes < lanesOf[l / kBatchLanes]; };

    Lanes px[8], py[8], pz[8];
    Lanes w, qx, qy, qz, lambda, spread, alpha;
    Mask strays[8];  // rows: each corner's stray lanes (strayMask)
    // Rows: the corners with a stray in either batch (the odd cells' at a tyre's ring end).
    const unsigned strayCorners = Rows ? batches[0]->strayCorners | batches[kHalves - 1]->strayCorners : 0;
    if constexpr (Contiguous && kHalves == 1) {
        for (int j = 0; j < 8; ++j)
            simd::loadPoints(corner(0, j), px[j], py[j], pz[j]);
        loadRotations(rotationsOf(0), w, qx, qy, qz);
        simd::load(lambda, lambdaOf(0));
    } else if constexpr (Contiguous) {
        for (int j = 0; j < 8; ++j) {
            if (Rows && (strayCorners >> j & 1) != 0) strayMask(batches, j, strays[j]);
            loadCornerPoints<Rows>(batches, j, pos, strayCorners, strays[j], px[j], py[j], pz[j]);
        }
        loadRotations(rotationsOf(0), rotationsOf(1), w, qx, qy, qz);
        simd::Lanes lo, hi;
        simd::load(lo, lambdaOf(0)), simd::load(hi, lambdaOf(1));
        join(lambda, lo, hi);
    } else {
        int lane[kLanes];  // the element of each lane; lanes past `lanes` repeat lane 0
        for (int l = 0; l < kLanes; ++l)
            lane[l] = l < lanes ? l : 0;
        for (int j = 0; j < 8; ++j)
            for (int l = 0; l < kLanes; ++l) {
                const double* p = pos + 3 * size_t(batch.particle[j][l]);
                px[j][l] = p[0], py[j][l] = p[1], pz[j][l] = p[2];
            }
        const Quat* rotations = arrays.rotations.data() + first;
        for (int l = 0; l < kLanes; ++l) {
            const Quat& rotation = rotations[lane[l]];
            w[l] = rotation.w(), qx[l] = rotation.x(), qy[l] = rotation.y(), qz[l] = rotation.z();
            lambda[l] = arrays.lambda[first + static_cast<uint32_t>(lane[l])];
        }
    }
    const BatchShape* const shapes = arrays.shapes.data();
    loadShapeRow<OneShape>(spread, batches, shapes, BatchShape::kScale2);
    loadShapeRow<OneShape>(alpha, batches, shapes, BatchShape::kCompliance);
    alpha *= invH2;
    const auto loadRest = [&](int j, Lanes& rx, Lanes& ry, Lanes& rz) {
        loadShapeRow<OneShape>(rx, batches, shapes, j);
        loadShapeRow<OneShape>(ry, batches, shapes, 8 + j);
        loadShapeRow<OneShape>(rz, batches, shapes, 16 + j);
    };
    // w_j: rows of the particles' inverse masses where the corners are consecutive.
    const double* const invMass = arrays.invMass.data();
    const auto loadInvMass = [&](int j, Lanes& wj) {
        if constexpr (Contiguous && kHalves == 1) {
            simd::load(wj, invMass + batch.particle[j][0]);
        } else if constexpr (Contiguous) {
            simd::Lanes lo, hi;
            simd::load(lo, invMass + batches[0]->particle[j][0]), simd::load(hi, invMass + batches[1]->particle[j][0]);
            join(wj, lo, hi);
            if (Rows && (strayCorners >> j & 1) != 0) {
                Lanes sw;
                strayValues(batches, j, invMass, 1, 0, sw);
                wj = strays[j] ? sw : wj;
            }
        } else {
            for (int l = 0; l < kLanes; ++l) wj[l] = invMass[batch.particle[j][l]];
        }
    };

    // A = Σ ⅛ x_j q_jᵀ (Σ q_j = 0 removes the centroid).
    Lanes am[3][3] = {};
    for (int j = 0; j < 8; ++j) {
        Lanes rx, ry, rz;
        loadRest(j, rx, ry, rz);
        am[0][0] += px[j] * rx, am[0][1] += px[j] * ry, am[0][2] += px[j] * rz;
        am[1][0] += py[j] * rx, am[1][1] += py[j] * ry, am[1][2] += py[j] * rz;
        am[2][0] += pz[j] * rx, am[2][1] += pz[j] * ry, am[2][2] += pz[j] * rz;
    }
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            am[r][c] *= 0.125;

    // projectionRotation's Newton step from the warm start (selects instead of branches); the
    // lanes it hands over (a turn over 0.1 rad, an inverted or collapsed shape, NaN) go to
    // extractRotation itself.
    const Lanes zero = {}, one = zero + 1.0;
    Lanes r00, r01, r02, r10, r11, r12, r20, r21, r22;
    rotationMatrix(w, qx, qy, qz, r00, r01, r02, r10, r11, r12, r20, r21, r22);
    Lanes tx, ty, tz;
    Mask definite;
    newtonTurn(am, spread, r00, r01, r02, r10, r11, r12, r20, r21, r22, tx, ty, tz, definite);
    const Lanes angle2 = tx * tx + ty * ty + tz * tz;
    const Mask handOver = ~definite | (angle2 > kFarTurn2) | (angle2 != angle2);
    {
        // integrateRotation's small-angle series: its first two terms are exact to rounding for
        // |θ|/2 up to 5e-4 (a turn of 1e-3 rad); up to 0.05 it takes the third, and the new
        // norm then needs its square root. A converged lane (angle2 ≤ 1e-24) stays put, as in
        // projectionRotation.
        const Mask large = ~handOver & (angle2 > kLaneTurn2);
        const Lanes half2 = 0.25 * angle2;
        const Lanes series = 0.5 * (1.0 + half2 * (1.0 / 3.0 + half2 * (2.0 / 15.0)));
        const Lanes longSeries = 0.5 * (1.0 + half2 * (1.0 / 3.0 + half2 * (2.0 / 15.0 + half2 * (17.0 / 315.0))));
        const Mask still = handOver | (angle2 <= 1e-24);
        const Lanes scale = still ? zero : large ? longSeries : series;
        turnLanes(r00, r01, r02, r10, r11, r12, r20, r21, r22, tx, ty, tz, scale, still, large, w, qx, qy, qz);
        rotationMatrix(w, qx, qy, qz, r00, r01, r02, r10, r11, r12, r20, r21, r22);
    }
    // A lane handed over kept its warm start in (w, qx, qy, qz): extractRotation starts from it.
    if constexpr (Contiguous && kHalves == 1) storeRotations(rotationsOf(0), w, qx, qy, qz);
    if constexpr (Contiguous && kHalves == 2)
        storeRotations(rotationsOf(0), rotationsOf(1), w, qx, qy, qz, Rows ? lanesOf[0] : 4, Rows ? lanesOf[1] : 4);
    for (int l = 0; l < lanes; ++l) {
        if (!own(l)) continue;  // rows: a lane past its batch's
        const uint32_t e = elementOf(l);
        if (handOver[l] == 0) {
            if constexpr (!Contiguous) arrays.rotations[e] = Quat(w[l], qx[l], qy[l], qz[l]);
            continue;
        }
        // The rare lane: the extraction from there, as the scalar sweep does it.
        if constexpr (!Contiguous) arrays.rotations[e] = Quat(w[l], qx[l], qy[l], qz[l]);
        ++handedOver;
        Mat3 matrix;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                matrix(r, c) = am[r][c][l];
        const Mat3 r = extractRotation(matrix, spread[l], arrays.rotations[e]);
        r00[l] = r(0, 0), r01[l] = r(0, 1), r02[l] = r(0, 2);
        r10[l] = r(1, 0), r11[l] = r(1, 1), r12[l] = r(1, 2);
        r20[l] = r(2, 0), r21[l] = r(2, 1), r22[l] = r(2, 2);
    }

    // Deviations d_j = x_j − c − R q_j, C and the update (Eq. 4, shape_matching.h).
    Lanes cx = zero, cy = zero, cz = zero;
    for (int j = 0; j < 8; ++j)
        cx += px[j], cy += py[j], cz += pz[j];
    cx *= 0.125, cy *= 0.125, cz *= 0.125;
    Lanes dx[8], dy[8], dz[8];
    Lanes sum = zero, weighted = zero;  // Σ |d_j|², Σ w_j |d_j|²
    for (int j = 0; j < 8; ++j) {
        Lanes rx, ry, rz, wj;
        loadRest(j, rx, ry, rz);
        dx[j] = px[j] - cx - (r00 * rx + r01 * ry + r02 * rz);
        dy[j] = py[j] - cy - (r10 * rx + r11 * ry + r12 * rz);
        dz[j] = pz[j] - cz - (r20 * rx + r21 * ry + r22 * rz);
        const Lanes squared = dx[j] * dx[j] + dy[j] * dy[j] + dz[j] * dz[j];
        sum += squared;
        if constexpr (!Held) {
            loadInvMass(j, wj);
            weighted += wj * squared;  // Σ w_j |∇_j C|² = weighted / (64 C²)
        }
    }
    Lanes c = 0.125 * sum;
    squareRoot(c);
    // Held corners (a contact holds them, element_batch.h): where the correction
    // Δx_j = w_j ∇_j C Δλ would push one into its contact (Δλ (n·d_j) < 0; Δλ has the sign of
    // −C − α̃ λ), its inverse mass along n is 0: d_j loses its normal part, both in the update
    // and in Σ w_j |∇_j C|² (W_j = w_j (1 − n nᵀ)). The part taken out, Δλ (n·d_j) / (8 C),
    // goes to the contact (heldImpulse).
    Lanes blocked[8];
    if constexpr (Held) {
        const Lanes numerator = -c - alpha * lambda;
        for (int j = 0; j < 8; ++j) {
            Lanes nx, ny, nz, wj;
            for (int l = 0; l < kLanes; ++l) {
                const Vec3& n = arrays.holdNormals[batch.particle[j][l]];
                nx[l] = n.x(), ny[l] = n.y(), nz[l] = n.z();
            }
            const Lanes along = nx * dx[j] + ny * dy[j] + nz * dz[j];
            blocked[j] = numerator * along < 0.0 ? along : zero;
            dx[j] -= blocked[j] * nx, dy[j] -= blocked[j] * ny, dz[j] -= blocked[j] * nz;
            loadInvMass(j, wj);
            weighted += wj * (dx[j] * dx[j] + dy[j] * dy[j] + dz[j] * dz[j]);
        }
    }
    Lanes step;
    {
        // C ≤ 1e-12 ℓ (C² ≤ 1e-24 ℓ²): already at the goal.
        const auto active = (sum > 8e-24 * spread) & (weighted > 0.0);
        // Δλ = (−C − α̃ λ) / (weighted / (64 C²) + α̃) and the step Δλ / (8 C): with
        // 64 C² = 8 Σ|d_j|², the step is (−Σ|d_j|² − 8 α̃ λ C) / (weighted + 8 α̃ Σ|d_j|²), one
        // division that does not wait for the square root (C only meets λ, 0 in a substep's
        // first iteration).
        const Lanes cc = active ? c : one;
        const Lanes inverse = one / (weighted + 8.0 * alpha * sum);  // inf or NaN when inactive
        const Lanes solved = (-sum - 8.0 * alpha * lambda * cc) * inverse;
        step = active ? solved : zero;
        lambda += step * (8.0 * cc);
    }
    for (int j = 0; j < 8; ++j) {
        Lanes wj;
        loadInvMass(j, wj);
        const Lanes move = step * wj;
        px[j] += move * dx[j], py[j] += move * dy[j], pz[j] += move * dz[j];
    }
    if constexpr (Held) {
        for (int j = 0; j < 8; ++j) {
            const Lanes pushed = step * blocked[j];  // ≤ 0: the impulse along n it did not take
            for (int l = 0; l < lanes; ++l)
                if (pushed[l] != 0.0) arrays.heldImpulse[batch.particle[j][l]] -= pushed[l];
        }
    }

    if constexpr (Contiguous && kHalves == 1) {
        simd::store(lambdaOf(0), lambda);
        for (int j = 0; j < 8; ++j)
            simd::storePoints(corner(0, j), px[j], py[j], pz[j]);
        return handedOver;
    } else if constexpr (Rows) {
        for (int l = 0; l < kLanes; ++l)
            if (own(l)) lambdaOf(l / kBatchLanes)[l % kBatchLanes] = lambda[l];
        for (int j = 0; j < 8; ++j)
            storeCornerPoints<true>(batches, j, pos, strayCorners, px[j], py[j], pz[j]);
        return handedOver;
    } else if constexpr (Contiguous) {
        split(lambdaOf(0), lambdaOf(1), lambda);
        for (int j = 0; j < 8; ++j)
            storePoints(corner(0, j), corner(1, j), px[j], py[j], pz[j]);
        return handedOver;
    }
    for (int l = 0; l < lanes; ++l)
        arrays.lambda[first + static_cast<uint32_t>(l)] = lambda[l];
    if (!batch.volume) {
        for (int l = 0; l < lanes; ++l)
            for (int j = 0; j < 8; ++j) {
                double* p = pos + 3 * size_t(batch.particle[j][l]);
                p[0] = px[j][l], p[1] = py[j][l], p[2] = pz[j][l];
            }
        return handedOver;
    }
    for (int l = 0; l < lanes; ++l) {
        const uint32_t e = first + static_cast<uint32_t>(l);
        const HexElement& element = arrays.elements[e];
        std::array<Vec3, 8> corners;
        for (int j = 0; j < 8; ++j)
            corners[j] = Vec3(px[j][l], py[j][l], pz[j][l]);
        if (arrays.volumeCompliance[e] >= 0.0) {
            // The optional volume constraint, after the element's shape matching.
            std::array<Vec3, 8> gradient;
            const double cv = volumeError(corners, arrays.volumeGradients[e], gradient);
            const double alphaV = arrays.volumeCompliance[e] * invH2;
            std::array<double, 8> volumeBlocked{};  // held corners: as the shape matching's, above
            if constexpr (Held) {
                const double numerator = -cv - alphaV * arrays.volumeLambda[e];
                for (int j = 0; j < 8; ++j) {
                    const Vec3& n = arrays.holdNormals[element[j]];
                    const double along = n.dot(gradient[j]);
                    if (numerator * along < 0.0) volumeBlocked[j] = along, gradient[j] -= along * n;
                }
            }
            double wv = 0.0;
            for (int j = 0; j < 8; ++j)
                wv += arrays.invMass[element[j]] * gradient[j].squaredNorm();
            if (wv + alphaV > 1e-30 && std::isfinite(cv)) {
                const double deltaLambda = (-cv - alphaV * arrays.volumeLambda[e]) / (wv + alphaV);
                arrays.volumeLambda[e] += deltaLambda;
                for (int j = 0; j < 8; ++j)
                    corners[j] += (arrays.invMass[element[j]] * deltaLambda) * gradient[j];
                if constexpr (Held)
                    for (int j = 0; j < 8; ++j)
                        if (volumeBlocked[j] != 0.0) arrays.heldImpulse[element[j]] -= deltaLambda * volumeBlocked[j];
            }
        }
        for (int j = 0; j < 8; ++j)
            arrays.positions[element[j]] = corners[j];
    }
    return handedOver;
}

}  // namespace
}  // namespace substep
