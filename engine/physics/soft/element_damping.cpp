#include "physics/soft/element_damping.h"

#include "physics/soft/lanes.h"

#include <cmath>

namespace substep {
namespace {

using namespace simd;

/// One batch: the corners' positions, velocities and masses gathered into lanes (a batch whose
/// corners are consecutive particles, lane by lane, loads them as rows), the element's rigid
/// motion, and the velocities moved towards it and scattered back.
[[gnu::always_inline]] inline void dampBatch(const ElementBatch& batch, const DampingArrays& arrays,
                                             const Lanes& fraction) {
    const int lanes = static_cast<int>(batch.lanes);
    const bool rows = lanes == kLanes && batch.contiguous;
    const double* const pos = arrays.positions.data()->data();
    double* const vel = arrays.velocities.data()->data();
    Lanes rx[8], ry[8], rz[8], vx[8], vy[8], vz[8], m[8];
    for (int j = 0; j < 8; ++j) {
        const size_t first = batch.particle[j][0];
        if (rows) {
            loadPoints(pos + 3 * first, rx[j], ry[j], rz[j]);
            loadPoints(vel + 3 * first, vx[j], vy[j], vz[j]);
            load(m[j], &arrays.mass[first]);
            continue;
        }
        for (int l = 0; l < kLanes; ++l) {
            const size_t i = batch.particle[j][l];  // lanes past `lanes` repeat lane 0
            rx[j][l] = pos[3 * i], ry[j][l] = pos[3 * i + 1], rz[j][l] = pos[3 * i + 2];
            vx[j][l] = vel[3 * i], vy[j][l] = vel[3 * i + 1], vz[j][l] = vel[3 * i + 2];
            m[j][l] = arrays.mass[i];
        }
    }
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
    for (int j = 0; j < 8; ++j) {
        if (rows) {
            storePoints(vel + 3 * size_t(batch.particle[j][0]), vx[j], vy[j], vz[j]);
            continue;
        }
        for (int l = 0; l < lanes; ++l) {
            const size_t i = batch.particle[j][l];
            vel[3 * i] = vx[j][l], vel[3 * i + 1] = vy[j][l], vel[3 * i + 2] = vz[j][l];
        }
    }
}

}  // namespace

[[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]] void dampElementBatches(
    std::span<const ElementBatch> batches, const DampingArrays& arrays, double dt) {
    double lastRate = 0.0, lastFraction = 0.0;  // a body's elements share their rate: one exp
    for (const ElementBatch& batch : batches) {
        Lanes fraction = {};
        bool any = false;
        for (int l = 0; l < static_cast<int>(batch.lanes); ++l) {
            const double k = arrays.damping[batch.firstElement + static_cast<uint32_t>(l)];
            if (!(k > 0.0)) continue;  // left alone: its lane's fraction stays 0
            if (k != lastRate) lastRate = k, lastFraction = 1.0 - std::exp(-k * dt);
            fraction[l] = lastFraction;
            any = true;
        }
        if (any) dampBatch(batch, arrays, fraction);
    }
}

}  // namespace substep
