#pragma once
/// The world's soft bodies: particles in structure-of-arrays storage, hexahedral elements held
/// by shape matching, attachments to rigid bodies and particle contacts, stepped inside the
/// world's substep loop (Algorithm 2 without rotation: integrate, solve, derive velocities,
/// velocity pass). The world owns one only once a soft body is created, so a world without
/// soft bodies pays nothing.
///
/// Particles stand in for bodies in the paper's correction operations ("each body can be
/// replaced with a single particle by setting w = 1/m and omitting the update of the
/// orientation", section 4): attachments use Eqs. 2-9, contacts Eqs. 26-30 and 34.

#include "physics/body.h"
#include "physics/collision/contact_manifold.h"
#include "physics/collision/heightfield_sphere.h"
#include "physics/correction.h"
#include "physics/handles.h"
#include "physics/math.h"
#include "physics/soft/attachment_run.h"
#include "physics/soft/candidate_skips.h"
#include "physics/soft/element_batch.h"
#include "physics/soft/lattice.h"
#include "physics/soft/particle_contact.h"
#include "physics/soft/rigid_mode.h"
#include "physics/soft/soft_body.h"
#include "physics/soft/still_contacts.h"

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <vector>

namespace substep {

class WorkerPool;

/// The soft bodies' share of the world's energies (J).
struct SoftEnergies {
    double kinetic = 0.0;    ///< Σ ½ m v² over particles
    double potential = 0.0;  ///< Σ −m g·x over particles
    double elastic = 0.0;    ///< Σ C²/(2 α_e) over shape-matching and volume constraints
};

class SoftSystem {
public:
    /// Creates a soft body; attachments refer to `bodies` (the world's storage).
    SoftBodyId create(const SoftBodyDef& def, std::span<const Body> bodies, uint32_t generation);
    /// Removes a soft body's particles, elements and attachments (storage stays contiguous).
    void destroy(SoftBodyId id);
    bool isValid(SoftBodyId id) const;
    /// No live soft body: the world skips every stage.
    bool empty() const { return liveBodies_ == 0; }
    /// Drops attachments to a rigid body that is being destroyed.
    void forgetBody(uint32_t bodyIndex);

    // The stages of World::step, in order.
    /// Once per frame: the (particle, rigid body) pairs that may touch during the frame (with a
    /// pool, each soft body's on a thread of their own).
    void collectCandidates(std::span<const Body> bodies, double dt, double margin, const Vec3& gravity,
                           WorkerPool* pool = nullptr);
    /// Every substep: the prediction (with a pool, body by body on its threads).
    void integrate(double h, const Vec3& gravity, WorkerPool* pool = nullptr);
    /// Every substep: the candidates' contact points on the current poses (with a pool, each
    /// soft body's candidates on a thread of their own, their points joined in the bodies'
    /// order: the same list as one after the other).
    void findContacts(std::span<const Body> bodies, double margin, WorkerPool* pool = nullptr);
    /// Every substep, after findContacts, with setHeldContacts on: the particles a contact
    /// holds (every contact found, touching or within the margin) and their contact normals,
    /// along which the element projection does not push them (element_batch.h;
    /// docs/SOFT_BODIES.md, "Loaded particles sink into the ground"). Off: none.
    void holdContactParticles();
    /// Elements, then attachments, then contacts (hard inequalities last). With a pool, each
    /// soft body's elements on a thread of their own (the bodies share no particle: the same
    /// bits as one after the other); where the soft bodies are apart (bodiesApart), each body's
    /// elements, attachments and contacts together on one.
    void solvePositions(SolverContext& ctx, WorkerPool* pool = nullptr);
    /// solvePositions' last two stages alone (what the world calls while recording each
    /// stage's corrections, substep_corrections.h).
    void solveAttachments(SolverContext& ctx);
    void solveContacts(SolverContext& ctx);
    /// Static friction per contact patch (WorldSettings::softPatchFriction) or per particle.
    void setPatchFriction(bool on) { patchFriction_ = on; }
    /// Particles held by their contacts in the element projection (holdContactParticles); off
    /// by default: loaded particles then rest on the surface, but the sag moves into the
    /// elements above them (1-iteration XPBD through light particles), a 2 kg rim on a test
    /// tyre keeps bouncing at 20 substeps and rc_car's coasting and wheel-spin tests fail
    /// (docs/SOFT_BODIES.md, "Loaded particles sink into the ground"). The world sets it every
    /// frame from WorldSettings::softHeldContacts.
    void setHeldContacts(bool on) { heldContacts_ = on; }
    /// Every substep, after the solve: the velocities (with a pool, body by body on its threads).
    void deriveVelocities(double h, WorkerPool* pool = nullptr);
    /// The contacts' restitution and dynamic friction (with a pool and the bodies apart, each
    /// soft body's contacts on a thread of their own).
    void solveVelocities(Body* bodies, double h, double gravity, WorkerPool* pool = nullptr);
    /// Whether this substep's soft bodies are apart: no moving rigid body is touched (held or
    /// in contact) by two of them, so each one's attachments and contacts change state no
    /// other one's read, and the bodies' solves may run in any order, or at once, with the same
    /// bits. Decided by findContacts.
    bool bodiesApart() const { return bodiesApart_; }

    /// Once per frame, after the substeps: damps each element's deformation rate (elementDamping_;
    /// with a pool, body by body on its threads; `lanes`: element_damping.h, the same bits).
    void damp(double dt, WorkerPool* pool = nullptr, ElementLanes lanes = ElementLanes::Widest);

    SoftEnergies energies(const Vec3& gravity) const;
    bool isFinite() const;
    /// `withVolume` false leaves `volume` at 0 and skips its sum over every element (the engine
    /// layer's per-step readout, ecs::PhysicsSystem::writeBack).
    SoftBodyReadout readout(SoftBodyId id, bool withVolume = true) const;
    /// Current particle positions of one soft body.
    std::span<const Vec3> positions(SoftBodyId id) const;
    std::span<const Vec3> velocities(SoftBodyId id) const;
    /// Per particle of one soft body: mass (kg).
    std::span<const double> masses(SoftBodyId id) const;
    SoftSurface surface(SoftBodyId id) const;
    /// Contact points that pushed in the last substep.
    int activeContactCount() const;
    /// Contact points the last findContacts found (touching or within the margin).
    size_t foundContactCount() const { return contacts_.size(); }
    /// The particle contacts' total force on the particles in the last substep of length h (N):
    /// Σ (λ_n n + the static friction's impulse) / h² (Eq. 10 for contacts).
    Vec3 contactForce(double h) const;
    /// Deepest current overlap of a particle contact (m).
    double maxPenetration(std::span<const Body> bodies) const;
    /// Every particle's position and velocity, the soft bodies' particles one after the other
    /// (positions(id) is a part of it).
    std::span<const Vec3> particlePositions() const { return x_; }
    std::span<const Vec3> particleVelocities() const { return v_; }
    /// Element count over all soft bodies.
    size_t elementCount() const { return elements_.size(); }
    /// The attachments, and their runs as the solve steps them (attachment_run.h; for tests).
    std::span<const Attachment> attachments() const { return attachments_; }
    std::span<const AttachmentRun> attachmentRuns() const { return attachmentRuns_; }

    /// One Gauss-Seidel sweep over every element's shape-matching (and volume) constraint;
    /// public for the benchmarks of the projection cost (`lanes`: element_batch.h).
    void solveElements(double invH2, ElementLanes lanes = ElementLanes::Widest, WorkerPool* pool = nullptr);

private:
    struct SoftBodyData {
        uint32_t firstParticle = 0, particleCount = 0;
        uint32_t firstElement = 0, elementCount = 0;
        double staticFriction = 0.5, dynamicFriction = 0.3, restitution = 0.0;
        double radius = 0.01, mass = 0.0;
        bool collide = true, preserveVolume = false, alive = false;
        uint32_t collisionGroup = 1, collisionMask = ~0u;  ///< SoftBodyDef's filter
        uint32_t generation = 0;
        std::vector<std::array<uint32_t, 4>> quads;  ///< boundary faces, body-local indices
        /// Rigid bodies it is attached to: its particles do not collide with them.
        std::vector<uint32_t> attachedBodies;
        /// The rigid mode's turn in this substep (rigid_mode.h): predicted by integrate, the
        /// warm start of the best-fit rotation in deriveVelocities.
        Quat turn = Quat::Identity();
        /// The moments of the particles' positions and velocities, summed by the velocity
        /// derivation (deriveOnArc) and kept up to date through the velocity pass, for the next
        /// substep's prediction; `momentsKept` false (after damping, at creation) makes
        /// integrate sum them afresh.
        RigidModeMoments moments;
        bool momentsKept = false;
    };
    /// Lists attachmentRuns_ and the ranges again: every edit of attachments_ calls it.
    void attachmentsChanged();
    /// The Gauss-Seidel attachments [first, end) of attachments_.
    void solveAttachmentRange(SolverContext& ctx, size_t first, size_t end);
    /// A particle and a rigid body that may touch this frame (its skip data, which every substep
    /// reads, apart in BodyCandidates::skips: candidate_skips.h).
    struct Candidate {
        uint32_t particle = 0;
        uint32_t body = 0;
        uint32_t softBody = 0;
        /// A heightfield in the world's axes (HeightfieldClearance, in world coordinates): the
        /// substeps also skip the pair while the particle is above `clearAbove` inside the x–z
        /// box (clearLowX, clearHighX) x (clearLowZ, clearHighZ), wherever it came from. NaN
        /// until the first substep the gap does not skip it computes them, with `roam` (m, the
        /// frame's reach); +∞ for every other pair (never skipped by it).
        double clearAbove = std::numeric_limits<double>::infinity();
        double clearLowX = 0.0, clearHighX = 0.0, clearLowZ = 0.0, clearHighZ = 0.0;
        double roam = 0.0;
    };
    /// One soft body's contacts with one rigid body in a substep: their static friction holds
    /// or lets go together (solveContacts).
    struct ContactPatch {
        uint32_t softBody = 0;
        uint32_t body = 0;
        double staticFriction = 0.0;
        double dynamicFriction = 0.0;
        double normal = 0.0;             ///< Σ λ_n
        Vec3 centre = Vec3::Zero();      ///< λ_n-weighted centre of the particles
        Vec3 direction = Vec3::Zero();   ///< λ_n-weighted mean normal, unit
        double reach = 0.0;              ///< Σ λ_n ρ, ρ a particle's distance from the centre across the normal
        Vec3 force = Vec3::Zero();       ///< Σ static friction impulse on the particles
        double twist = 0.0;              ///< its moment about the centre along `direction`
        double kept = 0.0;               ///< the share of this iteration's static friction kept
    };

    /// Sorts this substep's contacts into patches (patches_, contactPatch_).
    void groupContactPatches();
    /// solveContacts with static friction judged contact by contact (the paper's), or over
    /// each patch.
    /// (Per particle: the contacts [first, end) of contacts_.)
    void solveContactsPerParticle(SolverContext& ctx, size_t first, size_t end);
    void solveContactsPerPatch(SolverContext& ctx);
    void solveContactVelocities(Body* bodies, double h, double gravity, size_t first, size_t end);
    /// The particles' arrays as the contacts' solves read them (still_contacts.h).
    ContactParticles contactParticles();
    /// The velocity pass's changes to the particles passedVelocities_[first, end), all of one
    /// soft body or of several in runs, added to their bodies' kept moments.
    void keepPassedMoments(size_t first, size_t end);
    /// (These two are defined in soft_body_loops.h.)
    /// visit(body) for every live body; with a pool, each on a thread of its own (the bodies'
    /// particles, elements and moments are their own: the same bits in any order).
    template <class Visit>
    void forEachBody(WorkerPool* pool, Visit&& visit);
    /// visit(first, end) for each live body's batches, [first, end) in batches_; with a pool,
    /// each on a thread of their own; without, once for all of them.
    template <class Visit>
    void forEachBodyBatches(WorkerPool* pool, Visit&& visit);
    /// The element arrays as the batch kernel reads them.
    ElementArrays elementArrays();
    /// Rebuilds batches_ from every live body's elements.
    void rebuildBatches();
    /// Sizes the held particles' arrays to the particles and batches and indexes each
    /// particle's batches (particleBatchStart_, particleBatches_); nothing is held after it.
    void indexParticleBatches();
    /// Hands the elements' push a held particle did not take (heldImpulse_) to its contact c:
    /// λ_n grows by it and a moving body receives it (the element and the contact solved
    /// together). Returns it (0 when the particle has none, or it went to an earlier contact).
    double takeHeldImpulse(SolverContext& ctx, ParticleContact& c);
    void addAttachments(const SoftBodyDef& def, SoftBodyData& data, const Lattice& lattice,
                        std::span<const Body> bodies);

    // Particles (structure of arrays). Between integrate and deriveVelocities v_ holds the
    // velocities the substep started from: the prediction's v + g h (gravityStep_ added) is
    // formed where it is read, by the contacts, not stored for every particle.
    std::vector<Vec3> x_, xPrev_, v_;
    Vec3 gravityStep_ = Vec3::Zero();  ///< g h of the substep (integrate)
    /// Per particle: its velocity before the substep's derivation, written for the contacts'
    /// particles only (deriveVelocities; the velocity pass's Eq. 34 reads no other).
    std::vector<Vec3> vPrev_;
    std::vector<double> mass_, invMass_;
    // Elements.
    std::vector<HexElement> elements_;
    /// q_j: the element's rest shape (lattice.h), the same bits for every element of a shape, in
    /// that shape's own frame; rotations_ map it to the world.
    std::vector<std::array<Vec3, 8>> restOffsets_;
    /// b_j = ⅛ A_qq⁻¹ r_j, r_j the corners' offsets from their centroid in the world at creation.
    std::vector<std::array<Vec3, 8>> volumeGradients_;
    /// The rotation extracted last (the next extraction's warm start), from the element's rest
    /// frame to the world; at creation the body's orientation times the shape's turn.
    std::vector<Quat> rotations_;
    std::vector<double> scale2_;                       ///< ℓ² = Σ ⅛ |q_j|²
    std::vector<double> compliance_;                   ///< α_e = α ℓ² / V (m/N)
    std::vector<double> volumeCompliance_;             ///< α_V / V; negative: no volume constraint
    std::vector<double> elementDamping_;               ///< k (1/s): deformation rates decay as exp(−k t)
    std::vector<double> lambda_, volumeLambda_;
    /// Per element: its wave (element_batch.h); each body's elements are stored wave by wave.
    std::vector<uint32_t> elementWave_;
    std::vector<ElementBatch> batches_;     ///< the projection's batches (element_batch.h)
    std::vector<BatchShape> batchShapes_;  ///< their rest shapes
    /// Each live body's batches, [first, end) in batches_ (bodies in batches_' order).
    std::vector<std::pair<uint32_t, uint32_t>> bodyBatches_;
    // Bodies, couplings, contacts.
    std::vector<SoftBodyData> bodies_;
    std::vector<uint32_t> freeBodies_;
    int liveBodies_ = 0;
    std::vector<Attachment> attachments_;
    /// attachments_' runs (listAttachmentRuns), listed when they change (attachmentsChanged), not
    /// every substep.
    std::vector<AttachmentRun> attachmentRuns_;
    /// A soft body and a static heightfield it has candidates on this frame: the field's grid
    /// with the normals of the cells under the soft body kept (heightfield_sphere.h), for the
    /// candidates' gap bounds and every substep's contacts.
    struct FieldGrid {
        uint32_t softBody = 0, body = 0;
        std::shared_ptr<const HeightfieldData> field;  ///< kept alive while the grid points at it
        HeightfieldGrid grid;
    };
    /// One soft body's candidates this frame (collectCandidates) with their skip data, in the
    /// same order, and the heightfield grids they use; every substep, the candidates the gaps
    /// keep, the contacts found (with a pool, before the bodies' lists are joined) and where they
    /// are in contacts_. One per soft body slot, its storage reused frame after frame.
    struct BodyCandidates {
        std::vector<Candidate> candidates;
        CandidateSkips skips;
        std::vector<uint32_t> kept;
        std::vector<FieldGrid> fieldGrids;  ///< the first fieldGridCount are this frame's
        size_t fieldGridCount = 0;
        std::vector<ParticleContact> contacts;
        size_t firstContact = 0, endContact = 0;
        /// Appends a candidate and its skip data.
        Candidate& add(const Candidate& candidate, double gap, const Vec3& origin);
        /// Forgets the frame's candidates and grids (their storage stays).
        void clear();
    };
    std::vector<BodyCandidates> bodyCandidates_;
    /// Soft body s's candidates (collectCandidates); `fall`: g dt², the frame's fall.
    void collectBodyCandidates(uint32_t s, std::span<const Body> bodies, double dt, double margin, double fall);
    /// The contact points of one soft body's candidates, appended to `out`.
    void findBodyContacts(BodyCandidates& own, std::span<const Body> bodies, double margin,
                          std::vector<ParticleContact>& out);
    /// Fills a heightfield candidate's clearance (Candidate::clearAbove) from where its
    /// particle is now; `field` is its body, `own` its soft body's candidates.
    void clearanceOf(const BodyCandidates& own, Candidate& candidate, const Body& field, double margin) const;
    /// One live soft body's share of a substep's solve: its element batches, attachments,
    /// contacts and velocity pass particles (ranges of batches_, attachments_, contacts_,
    /// passedVelocities_).
    struct BodyShare {
        uint32_t body = 0;
        uint32_t firstBatch = 0, endBatch = 0;
        size_t firstAttachment = 0, endAttachment = 0;
        size_t firstContact = 0, endContact = 0;
        size_t firstPassed = 0, endPassed = 0;
    };
    std::vector<BodyShare> shares_;
    bool bodiesApart_ = false;
    /// Lists shares_ and decides bodiesApart_ (findContacts, with this substep's contacts).
    void planShares(std::span<const Body> bodies);
    /// Per soft body slot: its attachments' range in attachments_ ({0, 0} for none), and whether
    /// every body's are consecutive; listed again after attachments change.
    std::vector<std::pair<size_t, size_t>> attachmentRanges_;
    bool attachmentRangesListed_ = false, attachmentsGrouped_ = false;
    void listAttachmentRanges();
    std::vector<uint32_t> rigidOwner_;  ///< planShares': per rigid body, the soft body touching it
    std::vector<uint32_t> ownedBodies_;  ///< the rigid bodies rigidOwner_ names
    std::vector<ParticleContact> contacts_;
    bool patchFriction_ = false;
    bool heldContacts_ = false;
    std::vector<ContactPatch> patches_;
    std::vector<uint32_t> contactPatch_;  ///< per contact: its patch
    std::vector<Vec3> frictionStep_;      ///< per contact: this iteration's static friction impulse
    // Particles held by contacts (holdContactParticles).
    std::vector<Vec3> holdNormal_;         ///< per particle: its contacts' unit normal, zero when free
    std::vector<double> heldImpulse_;      ///< per particle: the elements' push its normal did not take
    std::vector<uint32_t> heldParticles_;  ///< the particles with a non-zero holdNormal_
    std::vector<uint8_t> heldBatches_;     ///< per batch: 1 where a corner is held
    std::vector<uint32_t> particleBatchStart_, particleBatches_;  ///< each particle's batches
    /// The velocity pass's particles (solveVelocities): index and velocity before it, and a
    /// flag per particle while it is listed.
    std::vector<std::pair<uint32_t, Vec3>> passedVelocities_;
    std::vector<uint8_t> passed_;
};

}  // namespace substep
