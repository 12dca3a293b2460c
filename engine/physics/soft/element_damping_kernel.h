#pragma once
/// The element damping's kernel (element_damping.h), written once for four lanes (one batch:
/// AVX2 or SSE2) and eight (two batches of one wave side by side: one AVX-512 register).
///
/// Two files compile it, as element_batch_kernel.h's: element_damping.cpp for the four lanes
/// (`target_clones`), element_damping_wide.cpp for x86-64-v4 under `#pragma GCC target`
/// (element_batch_kernel.h says why). Hence the anonymous namespace. Every header this one
/// includes must be included before the pragma, except batch_pair_lanes.h, which must be
/// included under it.

#include "physics/soft/batch_pair_lanes.h"
#include "physics/soft/element_batch.h"
#include "physics/soft/element_damping.h"
#include "physics/soft/lanes.h"

#include <cmath>

namespace substep {
namespace {

/// Each lane's fraction 1 − exp(−k dt) of the way to its element's rigid motion. A body's
/// elements share their rate k: one exp per body, remembered from the last lane (the fraction
/// depends on k and dt alone, so the order batches are damped in does not change it).
struct DampingFractions {
    double dt = 0.0;
    double lastRate = 0.0, lastFraction = 0.0;

    /// The batch's lanes' fractions, 0 past its lanes and where k ≤ 0; false where all are 0
    /// (the batch is left alone).
    [[gnu::always_inline]] bool of(const ElementBatch& batch, std::span<const double> damping, simd::Lanes& fraction) {
        // Through memory: GCC 12 fails on a vector's lane set by a variable index under x86-64-v4.
        double lanes[kBatchLanes] = {};
        bool any = false;
        for (int l = 0; l < static_cast<int>(batch.lanes); ++l) {
            const double k = damping[batch.firstElement + static_cast<uint32_t>(l)];
            if (!(k > 0.0)) continue;  // left alone: its lane's fraction stays 0
            if (k != lastRate) lastRate = k, lastFraction = 1.0 - std::exp(-k * dt);
            lanes[l] = lastFraction;
            any = true;
        }
        simd::load(fraction, lanes);
        return any;
    }
};

/// The kernel over `Lanes` (simd::Lanes: one batch; WideLanes: two side by side).
template <class Lanes>
struct DampingKernel {
    static constexpr int kLanes = sizeof(Lanes) / sizeof(double);
    static constexpr int kHalves = kLanes / kBatchLanes;  ///< batches side by side
    static_assert(kHalves * kBatchLanes == kLanes && (kHalves == 1 || kHalves == 2));

    /// Per lane, the element's rigid motion from its corners' positions r, velocities v and
    /// masses m (element_damping.h), and v moved towards it by `fraction`. r is left relative
    /// to the centre of mass. The same operations in the same order for four lanes and eight.
    [[gnu::always_inline]] static void towardsRigidMotion(Lanes (&rx)[8], Lanes (&ry)[8], Lanes (&rz)[8],
                                                          Lanes (&vx)[8], Lanes (&vy)[8], Lanes (&vz)[8],
                                                          const Lanes (&m)[8], const Lanes& fraction) {
        const Lanes zero = {};
        Lanes mass = zero, cx = zero, cy = zero, cz = zero, px = zero, py = zero, pz = zero;
        for (int j = 0; j < 8; ++j) {
            mass += m[j];
            cx += m[j] * rx[j], cy += m[j] * ry[j], cz += m[j] * rz[j];
            px += m[j] * vx[j], py += m[j] * vy[j], pz += m[j] * vz[j];
        }
        cx /= mass, cy /= mass, cz /= mass;
        const Lanes ux = px / mass, uy = py / mass, uz = pz / mass;  // mean velocity
        Lanes lx = zero, ly = zero, lz = zero;                        // L about the centre
        Lanes sxx = zero, syy = zero, szz = zero, sxy = zero, sxz = zero, syz = zero;  // Σ m r rᵀ
        for (int j = 0; j < 8; ++j) {
            rx[j] -= cx, ry[j] -= cy, rz[j] -= cz;
            const Lanes mx = m[j] * rx[j], my = m[j] * ry[j], mz = m[j] * rz[j];
            const Lanes dx = vx[j] - ux, dy = vy[j] - uy, dz = vz[j] - uz;
            lx += my * dz - mz * dy, ly += mz * dx - mx * dz, lz += mx * dy - my * dx;
            sxx += mx * rx[j], syy += my * ry[j], szz += mz * rz[j];
            sxy += mx * ry[j], sxz += mx * rz[j], syz += my * rz[j];
        }
        // I = Σ m (|r|² 1 − r rᵀ), inverted by its adjugate (symmetric).
        const Lanes spread = sxx + syy + szz;
        const Lanes i00 = spread - sxx, i11 = spread - syy, i22 = spread - szz;
        const Lanes i01 = -sxy, i02 = -sxz, i12 = -syz;
        const Lanes a00 = i11 * i22 - i12 * i12, a01 = i02 * i12 - i01 * i22, a02 = i01 * i12 - i02 * i11;
        const Lanes a11 = i00 * i22 - i02 * i02, a12 = i01 * i02 - i00 * i12, a22 = i00 * i11 - i01 * i01;
        const Lanes det = i00 * a00 + i01 * a01 + i02 * a02;
        const Lanes trace = i00 + i11 + i22;
        // A collapsed element has no well-defined spin: damped towards its mean velocity only.
        const auto spins = (det < 0 ? -det : det) > 1e-9 * trace * trace * trace;
        const Lanes wx = spins ? (a00 * lx + a01 * ly + a02 * lz) / det : zero;
        const Lanes wy = spins ? (a01 * lx + a11 * ly + a12 * lz) / det : zero;
        const Lanes wz = spins ? (a02 * lx + a12 * ly + a22 * lz) / det : zero;
        for (int j = 0; j < 8; ++j) {
            vx[j] += fraction * (ux + (wy * rz[j] - wz * ry[j]) - vx[j]);
            vy[j] += fraction * (uy + (wz * rx[j] - wx * rz[j]) - vy[j]);
            vz[j] += fraction * (uz + (wx * ry[j] - wy * rx[j]) - vz[j]);
        }
    }

    /// One batch: the corners' positions, velocities and masses gathered into lanes (a batch
    /// whose corners are consecutive particles, lane by lane, loads them as rows), damped, and
    /// the velocities scattered back.
    [[gnu::always_inline]] static void dampOne(const ElementBatch& batch, const DampingArrays& arrays,
                                               const Lanes& fraction) {
        static_assert(kHalves == 1, "one batch: four lanes");
        const int lanes = static_cast<int>(batch.lanes);
        const bool rows = lanes == kLanes && batch.contiguous;
        const double* const pos = arrays.positions.data()->data();
        double* const vel = arrays.velocities.data()->data();
        Lanes rx[8], ry[8], rz[8], vx[8], vy[8], vz[8], m[8];
        for (int j = 0; j < 8; ++j) {
            const size_t first = batch.particle[j][0];
            if (rows) {
                simd::loadPoints(pos + 3 * first, rx[j], ry[j], rz[j]);
                simd::loadPoints(vel + 3 * first, vx[j], vy[j], vz[j]);
                simd::load(m[j], &arrays.mass[first]);
                continue;
            }
            for (int l = 0; l < kLanes; ++l) {
                const size_t i = batch.particle[j][l];  // lanes past `lanes` repeat lane 0
                rx[j][l] = pos[3 * i], ry[j][l] = pos[3 * i + 1], rz[j][l] = pos[3 * i + 2];
                vx[j][l] = vel[3 * i], vy[j][l] = vel[3 * i + 1], vz[j][l] = vel[3 * i + 2];
                m[j][l] = arrays.mass[i];
            }
        }
        towardsRigidMotion(rx, ry, rz, vx, vy, vz, m, fraction);
        for (int j = 0; j < 8; ++j) {
            if (rows) {
                simd::storePoints(vel + 3 * size_t(batch.particle[j][0]), vx[j], vy[j], vz[j]);
                continue;
            }
            for (int l = 0; l < lanes; ++l) {
                const size_t i = batch.particle[j][l];
                vel[3 * i] = vx[j][l], vel[3 * i + 1] = vy[j][l], vel[3 * i + 2] = vz[j][l];
            }
        }
    }

    /// Two batches of one wave side by side, each contiguous or (`Rows`) rows (ElementBatch::
    /// rows): each batch's corners loaded as rows from its lane 0, strays put in by a select;
    /// only each batch's own velocities written back. Elements of one wave share no particle,
    /// so damping the later batch early gives the bits of damping it in its turn.
    template <bool Rows>
    [[gnu::always_inline]] static void dampPair(const ElementBatch* const* batches, const DampingArrays& arrays,
                                                const Lanes& fraction) {
        static_assert(kHalves == 2, "two batches side by side: eight lanes");
        const double* const pos = arrays.positions.data()->data();
        double* const vel = arrays.velocities.data()->data();
        const double* const mass = arrays.mass.data();
        const unsigned strayCorners = Rows ? batches[0]->strayCorners | batches[1]->strayCorners : 0;
        Lanes rx[8], ry[8], rz[8], vx[8], vy[8], vz[8], m[8];
        for (int j = 0; j < 8; ++j) {
            WideMask stray = {};
            if (Rows && (strayCorners >> j & 1) != 0) strayMask(batches, j, stray);
            loadCornerPoints<Rows>(batches, j, pos, strayCorners, stray, rx[j], ry[j], rz[j]);
            loadCornerPoints<Rows>(batches, j, vel, strayCorners, stray, vx[j], vy[j], vz[j]);
            simd::Lanes lo, hi;
            simd::load(lo, mass + batches[0]->particle[j][0]), simd::load(hi, mass + batches[1]->particle[j][0]);
            join(m[j], lo, hi);
            if (Rows && (strayCorners >> j & 1) != 0) {
                Lanes strayMass;
                strayValues(batches, j, mass, 1, 0, strayMass);
                m[j] = stray ? strayMass : m[j];
            }
        }
        towardsRigidMotion(rx, ry, rz, vx, vy, vz, m, fraction);
        for (int j = 0; j < 8; ++j)
            storeCornerPoints<Rows>(batches, j, vel, strayCorners, vx[j], vy[j], vz[j]);
    }
};

}  // namespace
}  // namespace substep
