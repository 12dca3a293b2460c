#pragma once
/// The rigid mode's passes (rigid_mode.h) on lanes of particles, written once for four lanes
/// (one block of four consecutive particles: AVX2 or SSE2) and eight (two blocks side by side:
/// one AVX-512 register).
///
/// Two files compile it: rigid_mode.cpp for x86-64-v4, -v3 and the base ISA four lanes at a time
/// (`target_clones`), rigid_mode_wide.cpp eight at a time for x86-64-v4 (included under
/// `#pragma GCC target` there, as element_batch_kernel.h is). Hence the anonymous namespace: each
/// file has its own copy, built for its own target. Vectors go in and out of these functions by
/// reference only: a 256- or 512-bit vector passed by value has another ABI without AVX, which
/// clang rejects in a call between functions of different targets, inlined or not.
///
/// The same bits on either width: each lane runs the same operations (GCC fuses a multiply into
/// an add, FMA, by the expression's shape, not its width), and the sums add block by block on
/// four lanes, the products that fuse into them formed there.

#include "physics/soft/lanes.h"
#include "physics/soft/rigid_mode.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace substep {

namespace {

using simd::kLanes;
using simd::Lanes;

/// The `count` (at most four) points at p into lanes; lanes past `count` get `pad`.
[[gnu::always_inline]] inline void loadBlock(const Vec3* p, uint32_t count, const Vec3& pad, Lanes& x, Lanes& y,
                                             Lanes& z) {
    if (count == kLanes) return simd::loadPoints(p->data(), x, y, z);
    Vec3 padded[kLanes];
    for (uint32_t l = 0; l < kLanes; ++l)
        padded[l] = l < count ? p[l] : pad;
    simd::loadPoints(padded[0].data(), x, y, z);
}

/// The first `count` (at most four) lanes' points to p.
[[gnu::always_inline]] inline void storeBlock(Vec3* p, uint32_t count, const Lanes& x, const Lanes& y,
                                              const Lanes& z) {
    if (count == kLanes) return simd::storePoints(p->data(), x, y, z);
    Vec3 padded[kLanes];
    simd::storePoints(padded[0].data(), x, y, z);
    for (uint32_t l = 0; l < count; ++l)
        p[l] = padded[l];
}

/// The `count` (at most four) masses at m into lanes; lanes past `count` get 0.
[[gnu::always_inline]] inline void loadMasses(const double* m, uint32_t count, Lanes& out) {
    if (count == kLanes) return simd::load(out, m);
    double padded[kLanes] = {};
    for (uint32_t l = 0; l < count; ++l)
        padded[l] = m[l];
    simd::load(out, padded);
}

/// rigidModeMoments' sums over blocks of four particles, relative to `origin`: each block's
/// positions (relative), velocities and masses (0 past the end) added lane by lane.
struct MomentSums {
    Lanes mass = {}, fx = {}, fy = {}, fz = {}, px = {}, py = {}, pz = {};
    Lanes lx = {}, ly = {}, lz = {};
    Lanes sxx = {}, syy = {}, szz = {}, sxy = {}, sxz = {}, syz = {};

    [[gnu::always_inline]] void add(const Lanes& rx, const Lanes& ry, const Lanes& rz, const Lanes& vx,
                                    const Lanes& vy, const Lanes& vz, const Lanes& mi) {
        const Lanes mx = mi * rx, my = mi * ry, mz = mi * rz;
        mass += mi, fx += mx, fy += my, fz += mz;
        px += mi * vx, py += mi * vy, pz += mi * vz;
        lx += my * vz - mz * vy, ly += mz * vx - mx * vz, lz += mx * vy - my * vx;
        sxx += mx * rx, syy += my * ry, szz += mz * rz;
        sxy += mx * ry, sxz += mx * rz, syz += my * rz;
    }

    /// The lanes added in a fixed order and moved to the centre of mass.
    [[gnu::always_inline]] RigidModeMoments moments(const Vec3& origin) const {
        using simd::sum;
        RigidModeMoments out;
        out.mass = sum(mass);
        if (!(out.mass > 0.0)) return out;
        const Vec3 first(sum(fx), sum(fy), sum(fz));
        const Vec3 momentum(sum(px), sum(py), sum(pz));
        const Vec3 angular(sum(lx), sum(ly), sum(lz));
        Mat3 second;
        second << sum(sxx), sum(sxy), sum(sxz), sum(sxy), sum(syy), sum(syz), sum(sxz), sum(syz), sum(szz);
        const Vec3 d = first / out.mass;  // centre − origin
        out.centre = origin + d;
        out.velocity = momentum / out.mass;
        out.angularMomentum = angular - d.cross(momentum);
        const Mat3 centred = second - out.mass * d * d.transpose();  // Σ m r rᵀ about the centre
        out.inertia = centred.trace() * Mat3::Identity() - centred;
        return out;
    }
};

/// turnSums' sums over blocks of four particles, lane by lane: q = x_prev − origin, mp = m p
/// (p = x − origin), qq = |q|² (formed by the caller, on four lanes or eight).
struct TurnLanes {
    Lanes mass = {}, spread = {}, f[3] = {}, g[3] = {}, c[3][3] = {};

    [[gnu::always_inline]] void add(const Lanes (&q)[3], const Lanes (&mp)[3], const Lanes& qq, const Lanes& mi) {
        mass += mi;
        f[0] += mp[0], f[1] += mp[1], f[2] += mp[2];
        g[0] += mi * q[0], g[1] += mi * q[1], g[2] += mi * q[2];
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k)
                c[r][k] += mp[r] * q[k];
        spread += mi * qq;
    }

    /// The lanes added in a fixed order.
    [[gnu::always_inline]] TurnSums sums() const {
        using simd::sum;
        TurnSums out;
        out.mass = sum(mass);
        out.first = Vec3(sum(f[0]), sum(f[1]), sum(f[2]));
        out.firstPrev = Vec3(sum(g[0]), sum(g[1]), sum(g[2]));
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k)
                out.cross(r, k) = sum(c[r][k]);
        out.spread = sum(spread);
        return out;
    }
};

/// predictOnArc's formula on lanes of either width (Algorithm 2's prediction on the arc):
/// x = x_prev + h (v + gravityStep) + arc r, r = x_prev − centre (p holds x_prev and receives x).
template <class L>
[[gnu::always_inline]] inline void predictLanes(L& px, L& py, L& pz, L& vx, L& vy, L& vz, const Vec3& gravityStep,
                                                double h, const Mat3& arc, const Vec3& centre) {
    vx += gravityStep.x(), vy += gravityStep.y(), vz += gravityStep.z();
    const L rx = px - centre.x(), ry = py - centre.y(), rz = pz - centre.z();
    px += h * vx + (arc(0, 0) * rx + arc(0, 1) * ry + arc(0, 2) * rz);
    py += h * vy + (arc(1, 0) * rx + arc(1, 1) * ry + arc(1, 2) * rz);
    pz += h * vz + (arc(2, 0) * rx + arc(2, 1) * ry + arc(2, 2) * rz);
}

/// |q|² on lanes of either width.
template <class L>
[[gnu::always_inline]] inline void squaredNorms(const L (&q)[3], L& out) {
    out = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
}

/// deriveOnArc's formula on lanes of either width:
/// v = (x − x_prev) invH + spin (x − centre) − turnBack (x_prev − centrePrev).
template <class L>
[[gnu::always_inline]] inline void deriveLanes(const L& px, const L& py, const L& pz, const L& qx, const L& qy,
                                               const L& qz, L& vx, L& vy, L& vz, double invH, const Mat3& spin,
                                               const Vec3& centre, const Mat3& turnBack, const Vec3& centrePrev) {
    const L rx = px - centre.x(), ry = py - centre.y(), rz = pz - centre.z();
    const L sx = qx - centrePrev.x(), sy = qy - centrePrev.y(), sz = qz - centrePrev.z();
    vx = ((px - qx) * invH + (spin(0, 0) * rx + spin(0, 1) * ry + spin(0, 2) * rz)) -
         (turnBack(0, 0) * sx + turnBack(0, 1) * sy + turnBack(0, 2) * sz);
    vy = ((py - qy) * invH + (spin(1, 0) * rx + spin(1, 1) * ry + spin(1, 2) * rz)) -
         (turnBack(1, 0) * sx + turnBack(1, 1) * sy + turnBack(1, 2) * sz);
    vz = ((pz - qz) * invH + (spin(2, 0) * rx + spin(2, 1) * ry + spin(2, 2) * rz)) -
         (turnBack(2, 0) * sx + turnBack(2, 1) * sy + turnBack(2, 2) * sz);
}

/// predictOnArc from particle `i` on, four at a time.
[[gnu::always_inline]] inline void predictFourAtATime(Vec3* x, const Vec3* xPrev, const Vec3* v, uint32_t i,
                                                      uint32_t count, const Vec3& gravityStep, double h,
                                                      const Mat3& arc, const Vec3& centre) {
    for (; i < count; i += kLanes) {
        const uint32_t n = std::min<uint32_t>(kLanes, count - i);
        Lanes px, py, pz, vx, vy, vz;
        loadBlock(xPrev + i, n, Vec3::Zero(), px, py, pz);
        loadBlock(v + i, n, Vec3::Zero(), vx, vy, vz);
        predictLanes(px, py, pz, vx, vy, vz, gravityStep, h, arc, centre);
        storeBlock(x + i, n, px, py, pz);
    }
}

/// turnSums from particle `i` on, four at a time (the last block padded with the origin and
/// no mass).
[[gnu::always_inline]] inline void turnSumsFourAtATime(const Vec3* x, const Vec3* xPrev, const double* m, uint32_t i,
                                                       uint32_t count, const Vec3& origin, TurnLanes& lanes) {
    for (; i < count; i += kLanes) {
        const uint32_t n = std::min<uint32_t>(kLanes, count - i);
        Lanes p[3], q[3], mi, qq;
        loadBlock(x + i, n, origin, p[0], p[1], p[2]);
        loadBlock(xPrev + i, n, origin, q[0], q[1], q[2]);
        loadMasses(m + i, n, mi);
        for (int k = 0; k < 3; ++k)
            p[k] -= origin[k], q[k] -= origin[k];
        const Lanes mp[3] = {mi * p[0], mi * p[1], mi * p[2]};
        squaredNorms(q, qq);
        lanes.add(q, mp, qq, mi);
    }
}

/// deriveOnArc from particle `i` on, four at a time (v is only written).
[[gnu::always_inline]] inline void deriveFourAtATime(const Vec3* x, const Vec3* xPrev, Vec3* v, uint32_t i,
                                                     uint32_t count, double invH, const Mat3& spin, const Vec3& centre,
                                                     const Mat3& turnBack, const Vec3& centrePrev, const double* m,
                                                     const Vec3& origin, MomentSums& sums) {
    for (; i < count; i += kLanes) {
        const uint32_t n = std::min<uint32_t>(kLanes, count - i);
        Lanes px, py, pz, qx, qy, qz, vx, vy, vz, mi;
        loadBlock(x + i, n, Vec3::Zero(), px, py, pz);
        loadBlock(xPrev + i, n, Vec3::Zero(), qx, qy, qz);
        deriveLanes(px, py, pz, qx, qy, qz, vx, vy, vz, invH, spin, centre, turnBack, centrePrev);
        storeBlock(v + i, n, vx, vy, vz);
        loadMasses(m + i, n, mi);  // 0 past the end: those lanes add nothing
        sums.add(px - origin.x(), py - origin.y(), pz - origin.z(), vx, vy, vz, mi);
    }
}

static_assert(sizeof(Quat) == 4 * sizeof(double), "rotations are read as packed (x, y, z, w)");

// turn q with q = (x, y, z, w) in one vector: the product's four terms are the turn's
// coefficients (signed, broadcast or permuted) times q, q's lanes permuted:
// x' = tw qx + tx qw + ty qz − tz qy, y' = tw qy + ty qw + tz qx − tx qz,
// z' = tw qz + tz qw + tx qy − ty qx, w' = tw qw − tx qx − ty qy − tz qz.
// On eight lanes two quaternions at a time, the same permutation in each half.

/// The turn's coefficients for turnOne.
struct TurnTerms {
    Lanes a, b, c, d;
    explicit TurnTerms(const Quat& turn) {
        const double tx = turn.x(), ty = turn.y(), tz = turn.z(), tw = turn.w();
        a = Lanes{tw, tw, tw, tw}, b = Lanes{tx, ty, tz, -tx}, c = Lanes{ty, tz, tx, -ty}, d = Lanes{-tz, -tx, -ty, -tz};
    }
};

/// One quaternion at q turned.
[[gnu::always_inline]] inline void turnOne(double* q, const TurnTerms& t) {
    Lanes v;
    simd::load(v, q);
    const Lanes wwwx = __builtin_shufflevector(v, v, 3, 3, 3, 0);
    const Lanes zxyy = __builtin_shufflevector(v, v, 2, 0, 1, 1);
    const Lanes yzxz = __builtin_shufflevector(v, v, 1, 2, 0, 2);
    const Lanes turned = t.a * v + t.b * wwwx + t.c * zxyy + t.d * yzxz;
    simd::store(q, turned);
}

}  // namespace
}  // namespace substep
