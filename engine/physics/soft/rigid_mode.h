#pragma once
/// A soft body's rigid mode: the translation and rotation of its particles as a whole, which
/// the substep integrates on arcs rather than on straight lines.
///
/// Moving each particle by h v and projecting the elements back onto their rest shapes turns a
/// spinning body by atan(ω h) instead of ω h, and the chord velocity (x − x_prev) / h that
/// follows is shorter than the arc's: the spin loses about (ω h)² of its angular momentum per
/// substep (12 % over 5 s at 5.5 rad/s and 20 substeps). So the prediction turns each particle
/// about the body's centre of mass by the body's spin, and the velocity derivation puts the
/// spin back from the best-fit rotation between the start and the end of the substep
/// (rigid_mode.h's functions; SoftSystem::integrate and ::deriveVelocities use them; the
/// passes over the particles run four or eight particles at a time in vector lanes,
/// rigid_mode.cpp). A rigid motion is then integrated exactly, as the paper integrates a rigid
/// body's rotation (Algorithm 2), and the deformation on top of it as before.

#include "physics/math.h"

#include <cstdint>

namespace substep {

/// Mass, centre of mass, momentum, angular momentum and inertia (both about the centre of mass)
/// of a set of particles.
struct RigidModeMoments {
    double mass = 0.0;
    Vec3 centre = Vec3::Zero();
    Vec3 velocity = Vec3::Zero();         ///< momentum / mass
    Vec3 angularMomentum = Vec3::Zero();  ///< Σ m (x − c) × v
    Mat3 inertia = Mat3::Zero();          ///< Σ m (|r|² 1 − r rᵀ), r = x − c
};

/// The width of the passes below: eight particles at a time where the machine has AVX-512
/// (x86-64-v4), four otherwise; the same bits either way (rigid_mode.cpp). Four can be asked
/// for, so that the tests compare the two.
enum class PassLanes { Widest, Four };

/// The moments of `count` particles, summed about the first particle's position (so the sums
/// do not cancel far from the origin) and moved to the centre of mass.
RigidModeMoments rigidModeMoments(const Vec3* x, const Vec3* v, const double* m, uint32_t count);

/// The prediction of Algorithm 2 for `count` particles with the rigid mode's arc
/// (SoftSystem::integrate), from the positions `xPrev` into `x`:
/// x = x_prev + h (v + gravityStep) + arc (x_prev − centre). arc = 0 moves them on straight
/// lines. `x` is only written (the system swaps its position arrays, so that the substep's
/// x_prev is the last one's x without a copy). v + gravityStep is not stored: the velocity
/// derivation overwrites v, and only the contacts read it before (they add gravityStep
/// themselves).
void predictOnArc(Vec3* x, const Vec3* xPrev, const Vec3* v, uint32_t count, const Vec3& gravityStep,
                  double h, const Mat3& arc, const Vec3& centre, PassLanes lanes = PassLanes::Widest);

/// The sums the best-fit turn from x_prev to x needs (SoftSystem::deriveVelocities), over
/// positions relative to `origin`: p = x − origin, q = x_prev − origin.
struct TurnSums {
    double mass = 0.0;
    Vec3 first = Vec3::Zero();      ///< Σ m p
    Vec3 firstPrev = Vec3::Zero();  ///< Σ m q
    Mat3 cross = Mat3::Zero();      ///< Σ m p qᵀ
    double spread = 0.0;            ///< Σ m |q|²
};
TurnSums turnSums(const Vec3* x, const Vec3* xPrev, const double* m, uint32_t count,
                  const Vec3& origin, PassLanes lanes = PassLanes::Widest);

/// The velocity derivation with the rigid turn on its arc (SoftSystem::deriveVelocities):
/// v = (x − x_prev) invH + spin (x − centre) − turnBack (x_prev − centrePrev).
/// Returns the moments of x and the new v (rigidModeMoments' sums, in the same pass): the next
/// substep's prediction needs them, and x does not move before it.
RigidModeMoments deriveOnArc(const Vec3* x, const Vec3* xPrev, Vec3* v, uint32_t count,
                             double invH, const Mat3& spin, const Vec3& centre, const Mat3& turnBack,
                             const Vec3& centrePrev, const double* m, PassLanes lanes = PassLanes::Widest);

/// Turns `count` rotations by `turn` (q = turn q): the elements' warm starts follow their body's
/// predicted turn (SoftSystem::integrate). Each quaternion in one vector of four lanes, two at a
/// time on AVX-512.
void turnRotations(Quat* rotations, uint32_t count, const Quat& turn, PassLanes lanes = PassLanes::Widest);

/// The passes eight particles at a time (rigid_mode_wide.cpp), which the functions above call
/// on a CPU where wideElementLanes() (element_batch.h).
[[gnu::target("arch=x86-64-v4")]] void predictInEights(Vec3* x, const Vec3* xPrev, const Vec3* v, uint32_t count,
                                                       const Vec3& gravityStep, double h, const Mat3& arc,
                                                       const Vec3& centre);
[[gnu::target("arch=x86-64-v4")]] TurnSums turnSumsInEights(const Vec3* x, const Vec3* xPrev, const double* m,
                                                            uint32_t count, const Vec3& origin);
[[gnu::target("arch=x86-64-v4")]] RigidModeMoments deriveInEights(const Vec3* x, const Vec3* xPrev, Vec3* v,
                                                                  uint32_t count, double invH, const Mat3& spin,
                                                                  const Vec3& centre, const Mat3& turnBack,
                                                                  const Vec3& centrePrev, const double* m);
[[gnu::target("arch=x86-64-v4")]] void turnRotationsInPairs(double* q, uint32_t count, const Quat& turn);

/// The spin ω whose turn by h ω keeps the angular momentum L of a body of inertia I: the
/// inertia turns with the body, so L after the turn is Rot(h ω) I ω, and ω solves
/// I ω = Rot(−h ω) L (a fixed point, contracting by about h |ω| per iteration: two or three
/// iterations at the substeps in use, at most 16). Returns 0 for
/// an inertia without a well-defined inverse (particles on a line or a point).
inline Vec3 momentumKeepingSpin(const Mat3& inertia, const Vec3& angularMomentum, double h) {
    const double trace = inertia.trace();
    const double det = inertia.determinant();
    if (!(trace > 0.0) || !(det > 1e-9 * trace * trace * trace)) return Vec3::Zero();
    const Mat3 inverse = inertia.inverse();
    Vec3 omega = inverse * angularMomentum;
    for (int iteration = 0; iteration < 16; ++iteration) {
        Quat back = Quat::Identity();
        integrateRotation(back, -h * omega);
        const Vec3 next = inverse * (back * angularMomentum);
        const double change = h * (next - omega).norm();
        omega = next;
        if (!(change > 1e-15)) break;  // converged (or NaN: the caller's finite check)
    }
    return omega;
}

}  // namespace substep
