#pragma once
/// Soft particles held to points of rigid bodies (Eqs. 2-9, body 0 the particle with w = 1/m and
/// no rotation, body 1 the rigid body), solved Gauss-Seidel in runs: the attachments to one body
/// one after the other with the body's pose in local variables (SoftSystem::solveAttachments).
/// A run is one dependent chain (each correction moves the body the next one starts from), so
/// runs that share no body and no particle are stepped side by side, link by link: one after
/// the other in turn (attachment_run.cpp), or one per lane of a vector where the CPU has AVX2
/// (attachment_lanes.cpp), with the same operations in the same order per run and so the same
/// bits.

#include "physics/body.h"
#include "physics/math.h"

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace substep {

/// A particle held to a point of a rigid body (principal frame).
struct Attachment {
    uint32_t particle = 0;
    uint32_t body = 0;
    Vec3 local = Vec3::Zero();
    double compliance = 0.0;
    double lambda = 0.0;
};

/// The Gauss-Seidel state of a run of attachments to one body: the body's pose in local
/// variables (its rotation matrix and world inverse inertia from the run's start, its position
/// and the run's accumulated turn), and the particles it holds.
struct AttachmentRun {
    size_t next = 0, end = 0;  ///< the attachments still to solve
    uint32_t bodyIndex = 0;
    uint32_t lowParticle = 0, highParticle = 0;
    bool moves = false, turns = false;
    double inverseMass = 0.0;
    Mat3 rotation = Mat3::Identity();
    Mat3 inverseInertia = Mat3::Zero();
    Vec3 position = Vec3::Zero(), turned = Vec3::Zero();
    void begin(const Body& b);
    /// Writes the position and the turn back to the body.
    void finish(Body& b) const;
};

/// The run of attachments to one body that starts at `first` and ends by `end` (not begun):
/// the longest such stretch, with the range of the particles it holds.
AttachmentRun attachmentRunAt(std::span<const Attachment> attachments, size_t first, size_t end);

/// Every run of `attachments` (attachmentRunAt one after the other, to the list's end) into
/// `runs` (replaced). The solve steps them every substep; they change only with the
/// attachments (SoftSystem keeps them).
void listAttachmentRuns(std::span<const Attachment> attachments, std::vector<AttachmentRun>& runs);

/// Runs stepped side by side (rc_car's four rims; four doubles in an AVX2 register).
inline constexpr int kAttachmentLanes = 4;

/// How solveAttachmentRuns steps its runs (the same bits whichever): one after the other in
/// turn; in the lanes of an AVX2 register where the CPU has AVX2; or as widest the CPU has
/// (x86-64-v4's 32 registers where wideElementLanes(), element_batch.h, else AVX2's).
enum class AttachmentLanes { OneByOne, Avx2, Widest };

/// Eq. 4 for an attachment whose particle is `delta` short of the body's point (c = |delta|,
/// c2 = c²), multiplier lambda (updated) and compliance term α̃ = α / h², between generalised
/// inverse masses w + w_body = wLinear + angular / c² (Eqs. 2-3: `angular` is
/// (r × delta)ᵀ I⁻¹ (r × delta), 0 when wLinear holds the whole sum). Returns the factor f of
/// the impulse Δλ n = Δλ delta / c = f delta. Written over c² (Δλ = c² (c − α̃ λ) /
/// ((wLinear + α̃) c² + angular)), a hard attachment's impulse waits for one division and no
/// square root: the rim's run of attachments is a chain, each correction moving the body the
/// next one starts from. A hard attachment (α̃ = 0) leaves λ alone: with no α̃ λ term and no
/// force readout nothing reads it, so its link costs one division, not two and a square root.
inline double attachmentImpulse(double& lambda, double alphaTilde, double c2, double wLinear, double angular) {
    const double denominator = (wLinear + alphaTilde) * c2 + angular;
    if (alphaTilde == 0.0) return c2 / denominator;  // Eq. 4 with α̃ = 0: Δλ = c / (w + w_body)
    const double c = std::sqrt(c2);
    const double deltaLambda = c2 * (c - alphaTilde * lambda) / denominator;  // Eq. 4
    const double factor = (c2 - alphaTilde * lambda * c) / denominator;
    lambda += deltaLambda;
    return factor;
}

/// Steps `runs` (begun, sharing no body and no particle) to their ends, link by link: each
/// attachment's particle in `x` (inverse masses `invMass`) and its run's body move (Eqs. 6-8),
/// soft attachments' λ sum Δλ; invH2 = 1 / h².
void solveAttachmentRuns(std::span<AttachmentRun> runs, Attachment* attachments, Vec3* x, const double* invMass,
                         double invH2, AttachmentLanes lanes = AttachmentLanes::Widest);

/// Whether the CPU runs solveAttachmentRuns' lanes (AVX2).
bool attachmentVectorLanes();

/// The runs in lanes, the last one's rest one by one: compiled for AVX2 (attachment_lanes.cpp;
/// only where attachmentVectorLanes()) and for x86-64-v4 (attachment_lanes_wide.cpp; only where
/// wideElementLanes()).
void solveAttachmentRunsInLanes(std::span<AttachmentRun> runs, Attachment* attachments, Vec3* x,
                                const double* invMass, double invH2);
void solveAttachmentRunsInWideLanes(std::span<AttachmentRun> runs, Attachment* attachments, Vec3* x,
                                    const double* invMass, double invH2);

}  // namespace substep
