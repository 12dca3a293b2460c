// The rigid mode's passes eight particles at a time, for CPUs with x86-64-v4 (rigid_mode_kernel.h):
// two blocks of four consecutive particles side by side in one AVX-512 register (one transpose
// of eight points costs what one of four does), the rotations two at a time; the last particles
// four at a time as in rigid_mode.cpp, compiled for the same target. The sums add each block's
// four lanes in turn, as the four-lane passes do, so both give the same bits
// (rigid_mode_test.cpp compares them).
#include "physics/soft/lanes.h"
#include "physics/soft/rigid_mode.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

// GCC: the kernel and the eight-lane helpers are compiled for AVX-512 where they are defined,
// under the pragma (their headers are included above, outside it); clang lowers vectors after
// inlining, for the function they end up in: the attribute on each pass is enough
// (element_batch_wide.cpp does the same).
#if !defined(__clang__)
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v4")
#endif
#include "physics/soft/rigid_mode_kernel.h"

namespace substep {
namespace {

/// Eight doubles: two blocks of four particles side by side (AVX-512's width).
using EightLanes = double __attribute__((vector_size(8 * sizeof(double))));

/// Eight consecutive points' 24 coordinates into x, y and z lanes (simd::loadPoints, twice as wide).
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
[[gnu::always_inline]] inline void halfOf(const EightLanes& v, Lanes& out) {
    if constexpr (Half == 0) out = __builtin_shufflevector(v, v, 0, 1, 2, 3);
    else out = __builtin_shufflevector(v, v, 4, 5, 6, 7);
}

/// Each of `count` eight-lane vectors' block of four in `half`.
template <int Half, int Count>
[[gnu::always_inline]] inline void halvesOf(const EightLanes (&v)[Count], Lanes (&out)[Count]) {
    for (int k = 0; k < Count; ++k) halfOf<Half>(v[k], out[k]);
}

/// The block of four in `half` of eight lanes added to turnSums' sums.
template <int Half>
[[gnu::always_inline]] inline void addTurnHalf(TurnLanes& lanes, const EightLanes (&q)[3], const EightLanes (&mp)[3],
                                               const EightLanes& qq, const EightLanes& mi) {
    Lanes qh[3], mph[3], qqh, mih;
    halvesOf<Half>(q, qh), halvesOf<Half>(mp, mph);
    halfOf<Half>(qq, qqh), halfOf<Half>(mi, mih);
    lanes.add(qh, mph, qqh, mih);
}

/// The block of four in `half` of eight lanes added to deriveOnArc's moment sums: r = x − origin
/// and the new v.
template <int Half>
[[gnu::always_inline]] inline void addMomentHalf(MomentSums& sums, const EightLanes (&r)[3], const EightLanes (&v)[3],
                                                 const EightLanes& mi) {
    Lanes rh[3], vh[3], mih;
    halvesOf<Half>(r, rh), halvesOf<Half>(v, vh), halfOf<Half>(mi, mih);
    sums.add(rh[0], rh[1], rh[2], vh[0], vh[1], vh[2], mih);
}

}  // namespace
}  // namespace substep

#if !defined(__clang__)
#pragma GCC pop_options
#endif

namespace substep {

[[gnu::target("arch=x86-64-v4")]] void predictInEights(Vec3* x, const Vec3* xPrev, const Vec3* v, uint32_t count,
                                                       const Vec3& gravityStep, double h, const Mat3& arc,
                                                       const Vec3& centre) {
    // Copies the stores to x cannot alias (rigid_mode.cpp's predictInFours).
    const Vec3 g = gravityStep, c = centre;
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

[[gnu::target("arch=x86-64-v4")]] TurnSums turnSumsInEights(const Vec3* x, const Vec3* xPrev, const double* m,
                                                            uint32_t count, const Vec3& origin) {
    TurnLanes lanes;
    uint32_t i = 0;
    for (; i + 8 <= count; i += 8) {
        EightLanes p[3], q[3], mi, qq;
        loadEightPoints(x[i].data(), p[0], p[1], p[2]);
        loadEightPoints(xPrev[i].data(), q[0], q[1], q[2]);
        std::memcpy(&mi, m + i, sizeof mi);
        for (int k = 0; k < 3; ++k)
            p[k] -= origin[k], q[k] -= origin[k];
        const EightLanes mp[3] = {mi * p[0], mi * p[1], mi * p[2]};
        squaredNorms(q, qq);
        addTurnHalf<0>(lanes, q, mp, qq, mi);
        addTurnHalf<1>(lanes, q, mp, qq, mi);
    }
    turnSumsFourAtATime(x, xPrev, m, i, count, origin, lanes);
    return lanes.sums();
}

[[gnu::target("arch=x86-64-v4")]] RigidModeMoments deriveInEights(const Vec3* x, const Vec3* xPrev, Vec3* v,
                                                                  uint32_t count, double invH, const Mat3& spin,
                                                                  const Vec3& centre, const Mat3& turnBack,
                                                                  const Vec3& centrePrev, const double* m) {
    const Vec3 origin = x[0];
    const Mat3 s = spin, t = turnBack;  // (rigid_mode.cpp's deriveInFours)
    const Vec3 c = centre, cp = centrePrev;
    MomentSums sums;
    uint32_t i = 0;
    for (; i + 8 <= count; i += 8) {
        EightLanes p[3], q[3], w[3], mi;
        loadEightPoints(x[i].data(), p[0], p[1], p[2]);
        loadEightPoints(xPrev[i].data(), q[0], q[1], q[2]);
        deriveLanes(p[0], p[1], p[2], q[0], q[1], q[2], w[0], w[1], w[2], invH, s, c, t, cp);
        storeEightPoints(v[i].data(), w[0], w[1], w[2]);
        std::memcpy(&mi, m + i, sizeof mi);
        const EightLanes r[3] = {p[0] - origin.x(), p[1] - origin.y(), p[2] - origin.z()};
        addMomentHalf<0>(sums, r, w, mi);
        addMomentHalf<1>(sums, r, w, mi);
    }
    deriveFourAtATime(x, xPrev, v, i, count, invH, s, c, t, cp, m, origin, sums);
    return sums.moments(origin);
}

[[gnu::target("arch=x86-64-v4")]] void turnRotationsInPairs(double* q, uint32_t count, const Quat& turn) {
    const TurnTerms terms(turn);
    EightLanes a, b, c, d;  // each of the turn's coefficients for both quaternions
    a = __builtin_shufflevector(terms.a, terms.a, 0, 1, 2, 3, 0, 1, 2, 3);
    b = __builtin_shufflevector(terms.b, terms.b, 0, 1, 2, 3, 0, 1, 2, 3);
    c = __builtin_shufflevector(terms.c, terms.c, 0, 1, 2, 3, 0, 1, 2, 3);
    d = __builtin_shufflevector(terms.d, terms.d, 0, 1, 2, 3, 0, 1, 2, 3);
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

}  // namespace substep
