#pragma once
/// The two correction operations of paper 3.3 (positional, Eqs. 2-9; angular, Eqs. 11-16) and
/// their block forms for attachments, orientation locks and welds: every joint moves bodies
/// through these, and only these, at the position level. Plus the velocity-level counterpart
/// (Eq. 33).

#include "physics/body.h"
#include "physics/math.h"

#include <cstdint>
#include <limits>
#include <vector>

namespace substep {

enum class SolverType : uint8_t {
    GaussSeidel,  ///< non-linear Gauss-Seidel: each correction moves the bodies at once (default)
    Jacobi,       ///< corrections of one iteration are gathered and applied together, summed
};

/// Where a joint correction takes its directions (the Jacobian: lever arms, axes, the inverse
/// inertia in world coordinates) from. The violation is always measured on the current state.
enum class JointProjection : uint8_t {
    /// The paper's form (3.3): directions on the current, predicted state. Like implicit Euler
    /// it removes energy in proportion to the substep (pendulum3 at 40 substeps: 0.68 m g L in
    /// 10 s).
    Paper,
    /// Directions on the substep's start poses (Body::xPrev, qPrev), the SHAKE/RATTLE form,
    /// which is symplectic for holonomic constraints: pendulum3 at 40 substeps keeps its energy
    /// to 1e-4 m g L (docs/fidelity/README.md). Contacts keep the current normals.
    Start,
};

/// Corrections gathered for one body during a Jacobi iteration.
struct JacobiDelta {
    Vec3 position = Vec3::Zero();
    Vec3 rotation = Vec3::Zero();
    uint32_t count = 0;
};

/// No bound on a correction's multiplier.
inline constexpr double kUnlimited = std::numeric_limits<double>::infinity();

/// What a correction needs to know about the current solve.
struct SolverContext {
    Body* bodies = nullptr;
    double h = 0.0;       ///< substep length
    double invH2 = 0.0;   ///< 1/h², turns compliance α into α̃ = α/h²
    SolverType solver = SolverType::GaussSeidel;
    JacobiDelta* deltas = nullptr;  ///< one per body, Jacobi only
    /// Repair pass (World::repairLargeViolations): only hard corrections at least this large
    /// act (distance in m, angle in rad); 0 outside the pass, where every correction acts.
    double repairDistance = 0.0;
    double repairAngle = 0.0;
    int repairs = 0;  ///< corrections the repair pass made
    /// Contacts push out overlaps their bodies' approach does not explain at a capped speed
    /// (contact.cpp, pushOut); false pushes them out whole, as plain PBD does.
    bool capPushOut = true;
    /// Directions of the block joint corrections (attachments, orientation locks and axis
    /// alignments, welds); the scalar ones (limits, drives, distances) keep the paper's.
    JointProjection projection = JointProjection::Paper;
};

/// The orientation a joint correction takes its directions from: the substep's start (qPrev) for
/// a dynamic body under JointProjection::Start, the current one otherwise (static bodies do not
/// keep a start pose).
inline const Quat& directionOrientation(const SolverContext& ctx, const Body& body) {
    return ctx.projection == JointProjection::Start && body.rotates() && body.invMass > 0.0 ? body.qPrev
                                                                                             : body.q;
}

/// The rotation matrix of the orientation directionOrientation names, given the matrix of the
/// body's current orientation: a joint that measured its frames with `current` passes it on
/// rather than converting the quaternion again.
inline Mat3 directionRotation(const SolverContext& ctx, const Body& body, const Mat3& current) {
    return ctx.projection == JointProjection::Start && body.rotates() && body.invMass > 0.0
               ? body.qPrev.toRotationMatrix()
               : current;
}

/// Eqs. 2-9: moves the point at world offset r0 of body i0 by `delta` relative to the point at
/// offset r1 of body i1 (|delta| is the constraint value c, its direction n), sharing the
/// motion by generalised inverse mass. XPBD with compliance α: Δλ = (c − α̃λ)/(w0 + w1 + α̃).
/// Returns the impulse p = Δλ n given to body 0 (body 1 receives −p). With `lambdaLimit` the
/// correction is made only if the new λ stays at or below it (static friction, paper 3.5:
/// "only if λ_t < μ_s λ_n"); otherwise nothing moves and zero is returned.
Vec3 applyPositionalCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& delta,
                               const Vec3& r0, const Vec3& r1, double compliance, double& lambda,
                               double lambdaLimit = kUnlimited);

/// The attachment form of Eqs. 2-9: makes the point at r0 on body i0 coincide with the point at
/// r1 on body i1 (delta = p1 − p0) with a vector multiplier and the 3 x 3 generalised inverse
/// mass K = Σ (1/m) 1 − [r]× I⁻¹ [r]×, instead of one scalar correction along delta/|delta|.
/// The scalar form weighs the whole gap by the inverse mass along the gap's direction; under
/// gravity that direction is the sag's, and a sideways part of the gap is then corrected with
/// the wrong inverse mass and overshoots by m r²/I: a box hung from its top face (m r²/I = 1.5)
/// grows a sideways nudge 1.7-fold every substep into a lasting flutter. With compliance α this
/// is XPBD's Δλ = (K + α̃ 1)⁻¹ (Δr − α̃ λ). Returns the impulse given to body 0.
Vec3 applyPointCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& delta,
                          const Vec3& r0, const Vec3& r1, double compliance, Vec3& lambda);

/// A weld: the attachment of applyPointCorrection and a hard orientation lock (`rotation`, the
/// rotation body 0 must make relative to body 1) solved together with the 6 x 6 generalised
/// inverse mass. Solved one after the other, the two parts fight over the body's rotation (the
/// attachment turns the body about its centre, the lock turns it back and reopens the gap), and
/// a cantilever with one iteration sags four times more and reports twice its torque.
/// r0 and r1 are the lever arms the correction acts through (on the poses directionOrientation
/// names); `delta` is measured on the current state. Adds the impulses given to body 0 to
/// `impulse` and `angularImpulse`.
void applyWeldCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& delta,
                         const Vec3& r0, const Vec3& r1, const Vec3& rotation, double compliance,
                         Vec3& lambdaPoint, Vec3& lambdaAngle, Vec3& impulse, Vec3& angularImpulse);

/// applyPointCorrection for a joint's attachment: anchors in the bodies' principal frames,
/// delta = p1 − p0 computed here on the current state, the lever arms and inverse inertias on
/// the poses directionOrientation names.
Vec3 applyAttachmentCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1,
                               const Vec3& anchor0, const Vec3& anchor1, double compliance,
                               Vec3& lambda);

/// The block form of Eqs. 11-16: turns body i0 by the world rotation vector `rotation` relative
/// to body i1 with a vector multiplier and K = I0⁻¹ + I1⁻¹ (world). The scalar form turns a body
/// with uneven inertia by I⁻¹ n θ / (nᵀ I⁻¹ n), which is not θ n: the error along n goes, one
/// across it appears, and the next correction swings back (a bar held by a prismatic lock read
/// 1.9 times its static torque and never came to rest). With `freeAxis` only the two directions
/// normal to it are constrained (a hinge's axis alignment). K is taken on the orientations
/// directionOrientation names. Returns the angular impulse given to body 0.
Vec3 applyRotationCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& rotation,
                             double compliance, Vec3& lambda, const Vec3* freeAxis = nullptr);

/// Eqs. 11-16: turns body i0 by the world rotation vector `rotation` relative to body i1 (its
/// length is the angle θ), shared by inverse inertia about the axis. Returns the angular
/// impulse given to body 0 (body 1 receives the opposite). `lambdaLimit` as for
/// applyPositionalCorrection.
Vec3 applyAngularCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& rotation,
                            double compliance, double& lambda, double lambdaLimit = kUnlimited);

// The same operations with the bodies' rotation matrices at hand (`rotation0`, `rotation1`: the
// matrices of the orientations the directions are taken on, whose columns are the principal axes
// the inverse inertia I⁻¹ = R diag(I⁻¹) Rᵀ is built from). A joint computes each body's matrix
// once per part and shares it between its geometry (axes, lever arms) and its correction; the
// forms above convert the quaternions themselves and call these.

/// applyPointCorrection with the matrices the lever arms r0, r1 were taken on.
Vec3 applyPointCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Mat3& rotation0,
                          const Mat3& rotation1, const Vec3& delta, const Vec3& r0, const Vec3& r1,
                          double compliance, Vec3& lambda);

/// applyRotationCorrection with the matrices of the orientations directionOrientation names.
Vec3 applyRotationCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Mat3& rotation0,
                             const Mat3& rotation1, const Vec3& rotation, double compliance,
                             Vec3& lambda, const Vec3* freeAxis = nullptr);

/// applyAngularCorrection with the matrices of the bodies' current orientations.
Vec3 applyAngularCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Mat3& rotation0,
                            const Mat3& rotation1, const Vec3& rotation, double compliance,
                            double& lambda, double lambdaLimit = kUnlimited);

/// Moves two bodies by a positional impulse gathered elsewhere (a contact patch's block solve):
/// body 0 by `linear` / m0 and turned by I0⁻¹ `angular0`, body 1 by −`linear` / m1 and turned
/// by −I1⁻¹ `angular1` (the angular impulses are Σ r × p about each body's centre).
void applyImpulse(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& linear,
                  const Vec3& angular0, const Vec3& angular1);

/// Eq. 33: changes the relative velocity of the points at r0, r1 (body 0's minus body 1's) by
/// `deltaVelocity`. Returns the impulse given to body 0.
Vec3 applyVelocityCorrection(Body& b0, Body& b1, const Vec3& deltaVelocity, const Vec3& r0,
                             const Vec3& r1);

/// Angular counterpart of Eq. 33: changes ω0 − ω1 by `deltaOmega`.
Vec3 applyAngularVelocityCorrection(Body& b0, Body& b1, const Vec3& deltaOmega);

/// Applies the Jacobi deltas gathered in one iteration (their plain sum: see SolverType).
void applyJacobiDeltas(Body* bodies, JacobiDelta* deltas, size_t count);

}  // namespace substep
