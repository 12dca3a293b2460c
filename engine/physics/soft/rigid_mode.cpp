// The rigid mode's passes over a soft body's particles (rigid_mode.h), four particles at a time:
// each block of four consecutive particles is loaded as rows and transposed into x, y and z
// lanes (simd::loadPoints), a block of fewer at the end through a padded copy. Sums are kept per
// lane and added in a fixed order at the end, so a pass gives the same bytes on every run.
#include "physics/soft/rigid_mode.h"

#include "physics/soft/lanes.h"

#include <algorithm>

namespace substep {
namespace {

using namespace simd;

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

[[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]] void predictOnArc(
    Vec3* x, const Vec3* xPrev, const Vec3* v, uint32_t count, const Vec3& gravityStep, double h,
    const Mat3& arc, const Vec3& centre) {
    for (uint32_t i = 0; i < count; i += kLanes) {
        const uint32_t n = std::min<uint32_t>(kLanes, count - i);
        Lanes px, py, pz, vx, vy, vz;
        loadBlock(xPrev + i, n, Vec3::Zero(), px, py, pz);
        loadBlock(v + i, n, Vec3::Zero(), vx, vy, vz);
        vx += gravityStep.x(), vy += gravityStep.y(), vz += gravityStep.z();
        const Lanes rx = px - centre.x(), ry = py - centre.y(), rz = pz - centre.z();
        px += h * vx + (arc(0, 0) * rx + arc(0, 1) * ry + arc(0, 2) * rz);
        py += h * vy + (arc(1, 0) * rx + arc(1, 1) * ry + arc(1, 2) * rz);
        pz += h * vz + (arc(2, 0) * rx + arc(2, 1) * ry + arc(2, 2) * rz);
        storeBlock(x + i, n, px, py, pz);
    }
}

[[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]] TurnSums turnSums(
    const Vec3* x, const Vec3* xPrev, const double* m, uint32_t count, const Vec3& origin) {
    const Lanes zero = {};
    Lanes mass = zero, spread = zero, fx = zero, fy = zero, fz = zero, gx = zero, gy = zero, gz = zero;
    Lanes c[3][3] = {};
    for (uint32_t i = 0; i < count; i += kLanes) {
        const uint32_t n = std::min<uint32_t>(kLanes, count - i);
        Lanes p[3], q[3], mi;
        loadBlock(x + i, n, origin, p[0], p[1], p[2]);
        loadBlock(xPrev + i, n, origin, q[0], q[1], q[2]);
        loadMasses(m + i, n, mi);
        for (int k = 0; k < 3; ++k)
            p[k] -= origin[k], q[k] -= origin[k];
        const Lanes mp[3] = {mi * p[0], mi * p[1], mi * p[2]};
        mass += mi;
        fx += mp[0], fy += mp[1], fz += mp[2];
        gx += mi * q[0], gy += mi * q[1], gz += mi * q[2];
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k)
                c[r][k] += mp[r] * q[k];
        spread += mi * (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    }
    TurnSums out;
    out.mass = sum(mass);
    out.first = Vec3(sum(fx), sum(fy), sum(fz));
    out.firstPrev = Vec3(sum(gx), sum(gy), sum(gz));
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k)
            out.cross(r, k) = sum(c[r][k]);
    out.spread = sum(spread);
    return out;
}

[[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]] RigidModeMoments deriveOnArc(
    const Vec3* x, const Vec3* xPrev, Vec3* v, uint32_t count, double invH,
    const Mat3& spin, const Vec3& centre, const Mat3& turnBack, const Vec3& centrePrev, const double* m) {
    if (count == 0) return {};
    const Vec3 origin = x[0];
    MomentSums sums;
    for (uint32_t i = 0; i < count; i += kLanes) {
        const uint32_t n = std::min<uint32_t>(kLanes, count - i);
        Lanes px, py, pz, qx, qy, qz, vx, vy, vz;
        loadBlock(x + i, n, Vec3::Zero(), px, py, pz);
        loadBlock(xPrev + i, n, Vec3::Zero(), qx, qy, qz);
        loadBlock(v + i, n, Vec3::Zero(), vx, vy, vz);
        const Lanes rx = px - centre.x(), ry = py - centre.y(), rz = pz - centre.z();
        const Lanes sx = qx - centrePrev.x(), sy = qy - centrePrev.y(), sz = qz - centrePrev.z();
        vx = ((px - qx) * invH + (spin(0, 0) * rx + spin(0, 1) * ry + spin(0, 2) * rz)) -
             (turnBack(0, 0) * sx + turnBack(0, 1) * sy + turnBack(0, 2) * sz);
        vy = ((py - qy) * invH + (spin(1, 0) * rx + spin(1, 1) * ry + spin(1, 2) * rz)) -
             (turnBack(1, 0) * sx + turnBack(1, 1) * sy + turnBack(1, 2) * sz);
        vz = ((pz - qz) * invH + (spin(2, 0) * rx + spin(2, 1) * ry + spin(2, 2) * rz)) -
             (turnBack(2, 0) * sx + turnBack(2, 1) * sy + turnBack(2, 2) * sz);
        storeBlock(v + i, n, vx, vy, vz);
        Lanes mi;
        loadMasses(m + i, n, mi);  // 0 past the end: those lanes add nothing
        sums.add(px - origin.x(), py - origin.y(), pz - origin.z(), vx, vy, vz, mi);
    }
    return sums.moments(origin);
}

static_assert(sizeof(Quat) == 4 * sizeof(double), "rotations are read as packed (x, y, z, w)");

[[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]] void turnRotations(Quat* rotations,
                                                                                       uint32_t count,
                                                                                       const Quat& turn) {
    // turn q with q = (x, y, z, w) in one vector: the product's four terms are the turn's
    // coefficients (signed, broadcast or permuted) times q, q's lanes permuted:
    // x' = tw qx + tx qw + ty qz − tz qy, y' = tw qy + ty qw + tz qx − tx qz,
    // z' = tw qz + tz qw + tx qy − ty qx, w' = tw qw − tx qx − ty qy − tz qz.
    const double tx = turn.x(), ty = turn.y(), tz = turn.z(), tw = turn.w();
    const Lanes a = {tw, tw, tw, tw}, b = {tx, ty, tz, -tx}, c = {ty, tz, tx, -ty}, d = {-tz, -tx, -ty, -tz};
    double* q = rotations->coeffs().data();
    for (uint32_t i = 0; i < count; ++i, q += 4) {
        Lanes v;
        load(v, q);
        const Lanes wwwx = __builtin_shufflevector(v, v, 3, 3, 3, 0);
        const Lanes zxyy = __builtin_shufflevector(v, v, 2, 0, 1, 1);
        const Lanes yzxz = __builtin_shufflevector(v, v, 1, 2, 0, 2);
        store(q, a * v + b * wwwx + c * zxyy + d * yzxz);
    }
}

}  // namespace substep
