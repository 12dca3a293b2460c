// The rigid mode's passes over a soft body's particles (rigid_mode.h), four particles at a time
// (rigid_mode_kernel.h): each block of four consecutive particles is loaded as rows and
// transposed into x, y and z lanes (simd::loadPoints), a block of fewer at the end through a
// padded copy. Sums are kept per lane and added in a fixed order at the end, so a pass gives the
// same bytes on every run. Where the CPU has x86-64-v4 (AVX-512), the passes run eight particles
// at a time instead (rigid_mode_wide.cpp), with the same bits.
#include "physics/soft/rigid_mode.h"

#include "physics/soft/element_batch.h"
#include "physics/soft/rigid_mode_kernel.h"

namespace substep {
namespace {

/// The eight-lane paths need x86-64-v4 (what the four-lane paths' AVX-512 clones need too).
bool eightLanes(PassLanes lanes) { return lanes == PassLanes::Widest && wideElementLanes(); }

[[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]] void predictInFours(
    Vec3* x, const Vec3* xPrev, const Vec3* v, uint32_t count, const Vec3& gravityStep, double h,
    const Mat3& arc, const Vec3& centre) {
    // Copies the stores to x cannot alias: kept in registers, not loaded again for each block.
    const Vec3 g = gravityStep, c = centre;
    const Mat3 a = arc;
    predictFourAtATime(x, xPrev, v, 0, count, g, h, a, c);
}

[[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]] TurnSums turnSumsInFours(
    const Vec3* x, const Vec3* xPrev, const double* m, uint32_t count, const Vec3& origin) {
    TurnLanes lanes;
    turnSumsFourAtATime(x, xPrev, m, 0, count, origin, lanes);
    return lanes.sums();
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

[[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]] void turnRotationsOneByOne(
    double* q, uint32_t count, const Quat& turn) {
    const TurnTerms terms(turn);
    for (uint32_t i = 0; i < count; ++i, q += 4)
        turnOne(q, terms);
}

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

void predictOnArc(Vec3* x, const Vec3* xPrev, const Vec3* v, uint32_t count, const Vec3& gravityStep, double h,
                  const Mat3& arc, const Vec3& centre, PassLanes lanes) {
    if (eightLanes(lanes)) return predictInEights(x, xPrev, v, count, gravityStep, h, arc, centre);
    predictInFours(x, xPrev, v, count, gravityStep, h, arc, centre);
}

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

void turnRotations(Quat* rotations, uint32_t count, const Quat& turn, PassLanes lanes) {
    if (eightLanes(lanes)) return turnRotationsInPairs(rotations->coeffs().data(), count, turn);
    turnRotationsOneByOne(rotations->coeffs().data(), count, turn);
}

}  // namespace substep
