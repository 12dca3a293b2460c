// The rigid mode's passes over a soft body's particles (rigid_mode.h), four particles at a time:
// each block of four consecutive particles is loaded as rows and transposed into x, y and z
// lanes (simd::loadPoints), a block of fewer at the end through a padded copy. Sums are kept per
// lane and added in a fixed order at the end, so a pass gives the same bytes on every run.
//
// On AVX-512 (x86-64-v4) the per-particle arithmetic runs on eight particles at a time (two
// blocks in one 512-bit vector, EightLanes), written once as templates over the lane type: the
// same operations on each lane, and GCC fuses a multiply into an add (FMA) by the expression's
// shape, not its width, so the same bits. The sums still add block by block, each block's four
// lanes in turn, and their products are formed on those four lanes, where they fuse into the
// sums as before. Other machines (and valgrind) run the four-lane code; the tests compare both.
#include "physics/soft/rigid_mode.h"

#include "physics/soft/lanes.h"

#include <algorithm>
#include <cstring>

#pragma GCC diagnostic ignored "-Wpsabi"  // 512-bit vectors, only inside always-inline code

namespace substep {
namespace {

using namespace simd;

/// Eight doubles: two blocks of four particles side by side (AVX-512's width).
using EightLanes = double __attribute__((vector_size(8 * sizeof(double))));

/// The eight-lane paths need x86-64-v4 (what the four-lane paths' AVX-512 clones need too).
bool eightLanes(PassLanes lanes) { return lanes == PassLanes::Widest && __builtin_cpu_supports("x86-64-v4"); }

/// Eight consecutive points' 24 coordinates into x, y and z lanes (loadPoints, twice as wide).
[[gnu::always_inline]] inline void loadEightPoints(const double* p, EightLanes& x, EightLanes& y, EightLanes& z) {
    EightLanes v0, v1, v2;  // x0 y0 z0 x1 y1 z1 x2 y2 | z2 x3 y3 z3 x4 y4 z4 x5 | y5 z5 x6 y6 z6 x7 y7 z7
    std::memcpy(&v0, p, sizeof v0), std::memcpy(&v1, p + 8, sizeof v1), std::memcpy(&v2, p + 16, sizeof v2);
    x = __builtin_shufflevector(__builtin_shufflevector(v0, v1, 0, 3, 6, 9, 12, 15, 0, 0), v2, 0, 1, 2, 3, 4, 5, 10, 13);
    y = __builtin_shufflevector(__builtin_shufflevector(v0, v1, 1, 4, 7, 10, 13, 0, 0, 0), v2, 0, 1, 2, 3, 4, 8, 11, 14);
    z = __builtin_shufflevector(__builtin_shufflevector(v0, v1, 2, 5, 8, 11, 14, 0, 0, 0), v2, 0, 1, 2, 3, 4, 9, 12, 15);
}

/// The inverse of loadEightPoints.
[[gnu::always_inline]] inline void storeEightPoints(double* p, const EightLanes& x, const EightLanes& y,
                                                    const EightLanes& z) {
    const EightLanes v0 = __builtin_shufflevector(__builtin_shufflevector(x, y, 0, 8, 0, 1, 9, 0, 2, 10), z, 0, 1, 8, 3, 4, 9, 6, 7);
    const EightLanes v1 = __builtin_shufflevector(__builtin_shufflevector(x, y, 0, 3, 11, 0, 4, 12, 0, 5), z, 10, 1, 2, 11, 4, 5, 12, 7);
    const EightLanes v2 = __builtin_shufflevector(__builtin_shufflevector(x, y, 0, 13, 6, 14, 0, 7, 15, 0), z, 1, 13, 2, 3, 14, 5, 6, 15);
    std::memcpy(p, &v0, sizeof v0), std::memcpy(p + 8, &v1, sizeof v1), std::memcpy(p + 16, &v2, sizeof v2);
}

/// The first (half 0) or second (half 1) block of four of eight lanes.
template <int Half>
[[gnu::always_inline]] inline Lanes halfOf(const EightLanes& v) {
    if constexpr (Half == 0) return __builtin_shufflevector(v, v, 0, 1, 2, 3);
    else return __builtin_shufflevector(v, v, 4, 5, 6, 7);
}

/// The `count` (at most four) points at p into lanes; lanes past `count` get `pad`.
[[gnu::always_inline]] inline void loadBlock(const Vec3* p, uint32_t count, const Vec3& pad,
                                             Lanes& x, Lanes& y, Lanes& z) {
    if (count == kLanes) return loadPoints(p->data(), x, y, z);
    Vec3 padded[kLanes];
    for (uint32_t l = 0; l < kLanes; ++l)
        padded[l] = l < count ? p[l] : pad;
    loadPoints(padded[0].data(), x, y, z);
}

/// The first `count` (at most four) lanes' points to p.
[[gnu::always_inline]] inline void storeBlock(Vec3* p, uint32_t count, const Lanes& x,
                                              const Lanes& y, const Lanes& z) {
    if (count == kLanes) return storePoints(p->data(), x, y, z);
    Vec3 padded[kLanes];
    storePoints(padded[0].data(), x, y, z);
    for (uint32_t l = 0; l < count; ++l)
        p[l] = padded[l];
}

/// The `count` (at most four) masses at m into lanes; lanes past `count` get 0.
[[gnu::always_inline]] inline void loadMasses(const double* m, uint32_t count, Lanes& out) {
    if (count == kLanes) return load(out, m);
    double padded[kLanes] = {};
    for (uint32_t l = 0; l < count; ++l)
        padded[l] = m[l];
    load(out, padded);
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

}  // namespace

[[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]] RigidModeMoments
rigidModeMoments(const Vec3* x, const Vec3* v, const double* m, uint32_t count) {
    if (count == 0) return {};
    const Vec3 origin = x[0];
    MomentSums sums;
    for (uint32_t i = 0; i < count; i += kLanes) {
        const uint32_t n = std::min<uint32_t>(kLanes, count - i);
        Lanes rx, ry, rz, vx, vy, vz, mi;
        loadBlock(x + i, n, origin, rx, ry, rz);
        loadBlock(v + i, n, Vec3::Zero(), vx, vy, vz);
        loadMasses(m + i, n, mi);
        rx -= origin.x(), ry -= origin.y(), rz -= origin.z();
        sums.add(rx, ry, rz, vx, vy, vz, mi);
    }
    return sums.moments(origin);
}

namespace {

/// predictOnArc's formula on lanes of either width: x = x_prev + h (v + gravityStep) + arc r,
/// r = x_prev − centre (p holds x_prev and receives x).
template <class L>
[[gnu::always_inline]] inline void predictLanes(L& px, L& py, L& pz, L& vx, L& vy, L& vz, const Vec3& gravityStep,
                                                double h, const Mat3& arc, const Vec3& centre) {
    vx += gravityStep.x(), vy += gravityStep.y(), vz += gravityStep.z();
    const L rx = px - centre.x(), ry = py - centre.y(), rz = pz - centre.z();
    px += h * vx + (arc(0, 0) * rx + arc(0, 1) * ry + arc(0, 2) * rz);
    py += h * vy + (arc(1, 0) * rx + arc(1, 1) * ry + arc(1, 2) * rz);
    pz += h * vz + (arc(2, 0) * rx + arc(2, 1) * ry + arc(2, 2) * rz);
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

[[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]] void predictInFours(
    Vec3* x, const Vec3* xPrev, const Vec3* v, uint32_t count, const Vec3& gravityStep, double h,
    const Mat3& arc, const Vec3& centre) {
    // Copies the stores to x cannot alias: kept in registers, not loaded again for each block.
    const Vec3 g = gravityStep, c = centre;
    const Mat3 a = arc;
    predictFourAtATime(x, xPrev, v, 0, count, g, h, a, c);
}

[[gnu::target("arch=x86-64-v4")]] void predictInEights(
    Vec3* x, const Vec3* xPrev, const Vec3* v, uint32_t count, const Vec3& gravityStep, double h,
    const Mat3& arc, const Vec3& centre) {
    const Vec3 g = gravityStep, c = centre;  // (predictInFours)
    const Mat3 a = arc;
    uint32_t i = 0;
    for (; i + 8 <= count; i += 8) {
        EightLanes px, py, pz, vx, vy, vz;
        loadEightPoints(xPrev[i].data(), px, py, pz);
        loadEightPoints(v[i].data(), vx, vy, vz);
        predictLanes(px, py, pz, vx, vy, vz, g, h, a, c);
        storeEightPoints(x[i].data(), px, py, pz);
    }
    predictFourAtATime(x, xPrev, v, i, count, g, h, a, c);
}

}  // namespace

void predictOnArc(Vec3* x, const Vec3* xPrev, const Vec3* v, uint32_t count, const Vec3& gravityStep, double h,
                  const Mat3& arc, const Vec3& centre, PassLanes lanes) {
    if (eightLanes(lanes)) return predictInEights(x, xPrev, v, count, gravityStep, h, arc, centre);
    predictInFours(x, xPrev, v, count, gravityStep, h, arc, centre);
}

namespace {

/// turnSums' sums over blocks of four particles, lane by lane: p = x − origin, q = x_prev −
/// origin, mp = m p, qq = |q|² (computed by the caller, on four lanes or eight).
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

/// |q|² on lanes of either width.
template <class L>
[[gnu::always_inline]] inline L squaredNorms(const L (&q)[3]) {
    return q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
}

/// turnSums from particle `i` on, four at a time (the last block padded with the origin and
/// no mass).
[[gnu::always_inline]] inline void turnSumsFourAtATime(const Vec3* x, const Vec3* xPrev, const double* m,
                                                       uint32_t i, uint32_t count, const Vec3& origin,
                                                       TurnLanes& lanes) {
    for (; i < count; i += kLanes) {
        const uint32_t n = std::min<uint32_t>(kLanes, count - i);
        Lanes p[3], q[3], mi;
        loadBlock(x + i, n, origin, p[0], p[1], p[2]);
        loadBlock(xPrev + i, n, origin, q[0], q[1], q[2]);
        loadMasses(m + i, n, mi);
        for (int k = 0; k < 3; ++k)
            p[k] -= origin[k], q[k] -= origin[k];
        const Lanes mp[3] = {mi * p[0], mi * p[1], mi * p[2]};
        lanes.add(q, mp, squaredNorms(q), mi);
    }
}

[[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]] TurnSums turnSumsInFours(
    const Vec3* x, const Vec3* xPrev, const double* m, uint32_t count, const Vec3& origin) {
    TurnLanes lanes;
    turnSumsFourAtATime(x, xPrev, m, 0, count, origin, lanes);
    return lanes.sums();
}

/// The block of four in `half` of eight lanes, for the sums.
template <int Half>
[[gnu::always_inline]] inline void addTurnHalf(TurnLanes& lanes, const EightLanes (&q)[3], const EightLanes (&mp)[3],
                                               const EightLanes& qq, const EightLanes& mi) {
    const Lanes qh[3] = {halfOf<Half>(q[0]), halfOf<Half>(q[1]), halfOf<Half>(q[2])};
    const Lanes mph[3] = {halfOf<Half>(mp[0]), halfOf<Half>(mp[1]), halfOf<Half>(mp[2])};
    lanes.add(qh, mph, halfOf<Half>(qq), halfOf<Half>(mi));
}

[[gnu::target("arch=x86-64-v4")]] TurnSums turnSumsInEights(
    const Vec3* x, const Vec3* xPrev, const double* m, uint32_t count, const Vec3& origin) {
    TurnLanes lanes;
    uint32_t i = 0;
    for (; i + 8 <= count; i += 8) {
        EightLanes p[3], q[3], mi;
        loadEightPoints(x[i].data(), p[0], p[1], p[2]);
        loadEightPoints(xPrev[i].data(), q[0], q[1], q[2]);
        std::memcpy(&mi, m + i, sizeof mi);
        for (int k = 0; k < 3; ++k)
            p[k] -= origin[k], q[k] -= origin[k];
        const EightLanes mp[3] = {mi * p[0], mi * p[1], mi * p[2]};
        const EightLanes qq = squaredNorms(q);
        addTurnHalf<0>(lanes, q, mp, qq, mi);
        addTurnHalf<1>(lanes, q, mp, qq, mi);
    }
    turnSumsFourAtATime(x, xPrev, m, i, count, origin, lanes);
    return lanes.sums();
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

/// deriveOnArc from particle `i` on, four at a time (v is only written).
[[gnu::always_inline]] inline void deriveFourAtATime(const Vec3* x, const Vec3* xPrev, Vec3* v, uint32_t i,
                                                     uint32_t count, double invH, const Mat3& spin,
                                                     const Vec3& centre, const Mat3& turnBack,
                                                     const Vec3& centrePrev, const double* m, const Vec3& origin,
                                                     MomentSums& sums) {
    for (; i < count; i += kLanes) {
        const uint32_t n = std::min<uint32_t>(kLanes, count - i);
        Lanes px, py, pz, qx, qy, qz, vx, vy, vz;
        loadBlock(x + i, n, Vec3::Zero(), px, py, pz);
        loadBlock(xPrev + i, n, Vec3::Zero(), qx, qy, qz);
        deriveLanes(px, py, pz, qx, qy, qz, vx, vy, vz, invH, spin, centre, turnBack, centrePrev);
        storeBlock(v + i, n, vx, vy, vz);
        Lanes mi;
        loadMasses(m + i, n, mi);  // 0 past the end: those lanes add nothing
        sums.add(px - origin.x(), py - origin.y(), pz - origin.z(), vx, vy, vz, mi);
    }
}

[[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]] RigidModeMoments deriveInFours(
    const Vec3* x, const Vec3* xPrev, Vec3* v, uint32_t count, double invH, const Mat3& spin,
    const Vec3& centre, const Mat3& turnBack, const Vec3& centrePrev, const double* m) {
    const Vec3 origin = x[0];
    // Copies the stores to v cannot alias: not loaded again for each block.
    const Mat3 s = spin, t = turnBack;
    const Vec3 c = centre, cp = centrePrev;
    MomentSums sums;
    deriveFourAtATime(x, xPrev, v, 0, count, invH, s, c, t, cp, m, origin, sums);
    return sums.moments(origin);
}

[[gnu::target("arch=x86-64-v4")]] RigidModeMoments deriveInEights(
    const Vec3* x, const Vec3* xPrev, Vec3* v, uint32_t count, double invH, const Mat3& spin,
    const Vec3& centre, const Mat3& turnBack, const Vec3& centrePrev, const double* m) {
    const Vec3 origin = x[0];
    const Mat3 s = spin, t = turnBack;  // (deriveInFours)
    const Vec3 c = centre, cp = centrePrev;
    MomentSums sums;
    uint32_t i = 0;
    for (; i + 8 <= count; i += 8) {
        EightLanes px, py, pz, qx, qy, qz, vx, vy, vz, mi;
        loadEightPoints(x[i].data(), px, py, pz);
        loadEightPoints(xPrev[i].data(), qx, qy, qz);
        deriveLanes(px, py, pz, qx, qy, qz, vx, vy, vz, invH, s, c, t, cp);
        storeEightPoints(v[i].data(), vx, vy, vz);
        std::memcpy(&mi, m + i, sizeof mi);
        const EightLanes ox = px - origin.x(), oy = py - origin.y(), oz = pz - origin.z();
        sums.add(halfOf<0>(ox), halfOf<0>(oy), halfOf<0>(oz), halfOf<0>(vx), halfOf<0>(vy), halfOf<0>(vz), halfOf<0>(mi));
        sums.add(halfOf<1>(ox), halfOf<1>(oy), halfOf<1>(oz), halfOf<1>(vx), halfOf<1>(vy), halfOf<1>(vz), halfOf<1>(mi));
    }
    deriveFourAtATime(x, xPrev, v, i, count, invH, s, c, t, cp, m, origin, sums);
    return sums.moments(origin);
}

}  // namespace

TurnSums turnSums(const Vec3* x, const Vec3* xPrev, const double* m, uint32_t count, const Vec3& origin,
                  PassLanes lanes) {
    if (eightLanes(lanes)) return turnSumsInEights(x, xPrev, m, count, origin);
    return turnSumsInFours(x, xPrev, m, count, origin);
}

RigidModeMoments deriveOnArc(const Vec3* x, const Vec3* xPrev, Vec3* v, uint32_t count, double invH,
                             const Mat3& spin, const Vec3& centre, const Mat3& turnBack, const Vec3& centrePrev,
                             const double* m, PassLanes lanes) {
    if (count == 0) return {};
    if (eightLanes(lanes)) return deriveInEights(x, xPrev, v, count, invH, spin, centre, turnBack, centrePrev, m);
    return deriveInFours(x, xPrev, v, count, invH, spin, centre, turnBack, centrePrev, m);
}

static_assert(sizeof(Quat) == 4 * sizeof(double), "rotations are read as packed (x, y, z, w)");

namespace {

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
    load(v, q);
    const Lanes wwwx = __builtin_shufflevector(v, v, 3, 3, 3, 0);
    const Lanes zxyy = __builtin_shufflevector(v, v, 2, 0, 1, 1);
    const Lanes yzxz = __builtin_shufflevector(v, v, 1, 2, 0, 2);
    store(q, t.a * v + t.b * wwwx + t.c * zxyy + t.d * yzxz);
}

[[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]] void turnRotationsOneByOne(
    double* q, uint32_t count, const Quat& turn) {
    const TurnTerms terms(turn);
    for (uint32_t i = 0; i < count; ++i, q += 4)
        turnOne(q, terms);
}

[[gnu::target("arch=x86-64-v4")]] void turnRotationsInPairs(double* q, uint32_t count, const Quat& turn) {
    const TurnTerms terms(turn);
    const auto twice = [](const Lanes& v) -> EightLanes { return __builtin_shufflevector(v, v, 0, 1, 2, 3, 0, 1, 2, 3); };
    const EightLanes a = twice(terms.a), b = twice(terms.b), c = twice(terms.c), d = twice(terms.d);
    uint32_t i = 0;
    for (; i + 2 <= count; i += 2, q += 8) {
        EightLanes v;
        std::memcpy(&v, q, sizeof v);
        const EightLanes wwwx = __builtin_shufflevector(v, v, 3, 3, 3, 0, 7, 7, 7, 4);
        const EightLanes zxyy = __builtin_shufflevector(v, v, 2, 0, 1, 1, 6, 4, 5, 5);
        const EightLanes yzxz = __builtin_shufflevector(v, v, 1, 2, 0, 2, 5, 6, 4, 6);
        const EightLanes turned = a * v + b * wwwx + c * zxyy + d * yzxz;
        std::memcpy(q, &turned, sizeof turned);
    }
    if (i < count) turnOne(q, terms);
}

}  // namespace

void turnRotations(Quat* rotations, uint32_t count, const Quat& turn, PassLanes lanes) {
    if (eightLanes(lanes)) return turnRotationsInPairs(rotations->coeffs().data(), count, turn);
    turnRotationsOneByOne(rotations->coeffs().data(), count, turn);
}

}  // namespace substep
