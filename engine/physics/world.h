#pragma once
/// The XPBD world: bodies, particles and joints in contiguous storage, stepped by the paper's
/// Algorithm 2 (substeps, integration with the gyroscopic term, position solve by the two
/// correction operations, velocity derivation, velocity pass).

#include "physics/body.h"
#include "physics/collision/broadphase.h"
#include "physics/contact.h"
#include "physics/contact_schedule.h"
#include "physics/contact_restitution.h"
#include "physics/correction.h"
#include "physics/handles.h"
#include "physics/joints/joint.h"
#include "physics/math.h"
#include "physics/sleep_islands.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <span>
#include <vector>

namespace substep {

struct ColouredSolve;
class JointBlockSolver;
class SoftSystem;
class SubstepCorrections;
class WorkerPool;
class WorldSnapshot;
struct SoftBodyDef;
struct SoftBodyReadout;
struct SoftSurface;

/// At most this many candidate contact pairs per frame (each holds at most kMaxContactPoints
/// points), or kMaxContactPairsPerBody per colliding body where that is more
/// (World::contactPairCap): the bound on one frame's narrowphase work and memory for
/// pathological scenes, linear in the bodies. Bodies piled at one point pair with every other;
/// a crowd falling together pairs each body with its neighbours within the frame's motion
/// (16000 spheres falling in ten layers: up to 255000 pairs, 16 a body).
inline constexpr std::size_t kMaxContactPairs = std::size_t{1} << 17;
inline constexpr std::size_t kMaxContactPairsPerBody = 32;

struct WorldSettings {
    Vec3 gravity = Vec3(0.0, -9.81, 0.0);
    int substeps = 20;
    int iterations = 1;
    SolverType solver = SolverType::GaussSeidel;
    /// Hard joint parts violated by more than these when a step follows the creation of joints
    /// (a scene built far from its constraints), or after requestRepair() (a teleported body),
    /// are repaired before the step, moving positions without touching velocities. Projected
    /// inside a substep instead, such a violation becomes a velocity of violation / h: a hinge
    /// started 90° off its axis turned 100 J into 640 J in the first frame, a swing-limited
    /// ball joint 135° outside its cone into 115 kJ. The errors a running simulation makes
    /// itself are left to the substeps, so the repair never acts as hidden extra iterations.
    /// 0 switches it off.
    double repairDistance = 0.05;  ///< m
    double repairAngle = 0.25;     ///< rad
    /// The narrowphase also reports points this far apart (m), so that a point that a
    /// correction elsewhere pushes into contact later in the substep is still held.
    double contactMargin = 0.002;
    /// Time the stages of every step (World::stepTimes): a clock read per stage and substep,
    /// so off unless something shows the breakdown (the viewer does).
    bool measureTime = false;
    /// The velocity pass (paper 3.6: damping, dynamic friction, restitution) after each
    /// substep's velocity derivation. Off gives plain PBD velocities v = Δx/h, with overlaps
    /// pushed out whole: the comparison the paper's Figs. 12 and 13 draw.
    bool velocityPass = true;
    /// Sleeping (sleep_islands.h): islands of touching or jointed bodies that have rested for
    /// `sleep.time` stop being simulated until a body, an edit or a moved static body wakes
    /// them. Off by default, so every scene behaves as before; a world with soft bodies never
    /// sleeps (their coupling to rigid bodies is not part of the islands).
    bool sleeping = false;
    SleepSettings sleep;
    /// Threads the step uses (the caller's among them; 1: no other thread). The narrowphase,
    /// integration and velocity derivation run in parallel, each item written to its own slot,
    /// so they give the same bytes for every thread count. With more than one thread the
    /// position solve and the velocity pass take their constraints by colour
    /// (constraint_colouring.h): that order differs from the serial one, so 1 thread gives other
    /// bytes than 2, while 2, 3, 4 ... give the same bytes as `colouredSolve` at 1 thread.
    int threads = 1;
    /// Solve contacts and joints in the coloured order at 1 thread too (always on with more
    /// threads): the reference the parallel runs are compared with. Gauss-Seidel only.
    bool colouredSolve = false;
    /// Where joint corrections take their directions from (correction.h): the paper's current
    /// state, or the substep's start, which keeps the energy of jointed bodies.
    JointProjection jointProjection = JointProjection::Paper;
    /// Restitution by sweeps of two-body collisions before the velocity pass
    /// (contact_restitution.h), so that an impact passes through a row of touching bodies
    /// whatever order they are listed in. The default; false (the scene file's
    /// `"restitution": "paper"`) keeps the paper's Eq. 34 alone. Piles settle and sleep under it
    /// (spheres1000 at 21.9 s, 24.2 s under Eq. 34); spheres1000's fall costs 9.5 % more CPU. A
    /// substep in which no contact with restitution collided lately runs the paper's velocity
    /// pass either way.
    bool sweptRestitution = true;
    /// Joints around light bodies (a dynamic body jointed to one at least 20 times heavier)
    /// solved together by a direct block solve each substep (joint_block_solve.h), so that a
    /// light link passes corrections on whole: a 1 g box holding a 1 kg box keeps its hard
    /// joints closed within 0.1 mm instead of 6.8 mm. Worlds without light links are
    /// unaffected. Gauss-Seidel only (the Jacobi solver ignores it).
    bool blockSolve = true;
    /// Soft bodies' static friction judged over each soft body's contact patch on a rigid body
    /// (soft_coupling.cpp): the patch holds while its friction stays within μ_s Σλ_n and slides
    /// at μ_d at the position level, so a soft box holds on a slope up to atan(μ_s) and the
    /// braked RC car on 25°. Off by default: in rc_car's coasting test it stops the car more
    /// abruptly, and the energy readout at rest flickers by 1.5 % of the kinetic energy it had
    /// (1 % is the bound).
    bool softPatchFriction = false;
    /// Soft bodies' particles held by their contacts in the element projection: the shape
    /// matching does not push a particle with a contact into it (its inverse mass is zero along
    /// the contact normal for that push), and the contact takes that push as load. Loaded
    /// particles then rest on the surface rather than 3 to 26 mm in it. Off by default: the sag
    /// moves into the elements above the contact, which one iteration leaves softer by h² w̃, so
    /// the rest shape still depends on the substeps and a heavy rim rings (docs/SOFT_BODIES.md).
    bool softHeldContacts = false;
};

/// Where the last step's time went (ms), when WorldSettings::measureTime is on.
struct StepTimes {
    double broadphase = 0.0;   ///< collecting the frame's pairs
    double narrowphase = 0.0;  ///< the contacts of every substep
    double solve = 0.0;        ///< position solve: joints and contacts
    double velocities = 0.0;   ///< the velocity pass: damping, friction, restitution
    double integrate = 0.0;    ///< integration and velocity derivation
    double total() const { return broadphase + narrowphase + solve + velocities + integrate; }
};

/// Energies as DESIGN.md defines them (J).
struct Energies {
    double kinetic = 0.0;    ///< Σ ½ m v² + ½ ωᵀ I ω
    double potential = 0.0;  ///< Σ −m g·x
    double elastic = 0.0;    ///< Σ C²/(2α) over compliant joint parts
    double total() const { return kinetic + potential + elastic; }
};

class World {
public:
    explicit World(const WorldSettings& settings = {});
    ~World();
    World(World&&) noexcept;
    World& operator=(World&&) noexcept;

    /// Creates a body from its definition; mass properties come from the shape unless the
    /// definition gives a mass. Inputs are assumed valid (the scene loader validates files).
    BodyId createBody(const BodyDef& def);
    /// Destroys a body and every joint attached to it.
    void destroyBody(BodyId id);
    JointId createJoint(const JointDef& def);
    void destroyJoint(JointId id);

    /// Whether the handle names a live body (joint) of this world.
    bool isValid(BodyId id) const {
        return !id.isNull() && id.index < bodies_.size() && bodies_[id.index].alive &&
               bodies_[id.index].generation == id.generation;
    }
    bool isValid(JointId id) const {
        return !id.isNull() && id.index < joints_.size() && joints_[id.index].alive &&
               joints_[id.index].generation == id.generation;
    }
    /// The body or joint a handle names. A null, destroyed (stale generation) or foreign handle
    /// is an error: it asserts in a debug build and throws std::invalid_argument otherwise,
    /// naming the handle. The solver indexes storage directly and pays nothing for the check.
    /// A body is read only: its pose, velocity and surface change through setBodyPose,
    /// setBodyVelocity and setBodySurface, which wake its island, as Box2D's and Jolt's body
    /// interfaces do (a body written in place stayed asleep).
    const Body& body(BodyId id) const { return bodies_[checked(id)]; }
    const Joint& joint(JointId id) const { return joints_[checked(id)]; }
    /// A live joint's parameters may be set in place (damping, a drive's target); that does not
    /// wake a sleeping island, which updateJoint does.
    Joint& joint(JointId id) { return joints_[checked(id)]; }

    /// Gives a live joint the parameters of `def` (anchors, frames, compliances, limits, drives,
    /// damping, collide; not its bodies or type), keeping its running state: a motor keeps the
    /// angle it has reached. Parameters set to the values they have change nothing.
    void updateJoint(JointId id, const JointDef& def);
    /// Moves a body's user frame to a pose (a static mount carried, a body placed); it keeps its
    /// velocity. An orientation within rounding of the current one leaves the rotation alone.
    void setBodyPose(BodyId id, const Vec3& position, const Quat& orientation);
    /// Sets a dynamic body's velocity (of its centre of mass) and angular velocity; static bodies
    /// ignore it.
    void setBodyVelocity(BodyId id, const Vec3& velocity, const Vec3& angularVelocity);
    /// Sets a body's friction, restitution and whether it collides.
    void setBodySurface(BodyId id, double staticFriction, double dynamicFriction,
                        double restitution, bool collide);
    /// Creates a soft body (engine/physics/soft/soft_body.h): its lattice, elements and
    /// attachments to the bodies it names. Inputs are assumed valid.
    SoftBodyId createSoftBody(const SoftBodyDef& def);
    void destroySoftBody(SoftBodyId id);
    bool isValid(SoftBodyId id) const;
    /// Centre of mass, mean velocity, extent, volume of a soft body (zeros for a dead id).
    SoftBodyReadout softBodyReadout(SoftBodyId id) const;
    /// A soft body's current surface for drawing (positions, quads, triangles).
    SoftSurface softBodySurface(SoftBodyId id) const;
    /// A soft body's current particle positions (empty for a dead id).
    std::span<const Vec3> softBodyPositions(SoftBodyId id) const;
    /// The soft bodies' storage, or null while the world has never had one.
    const SoftSystem* softBodies() const { return soft_.get(); }

    /// Advances one frame of length dt in `settings().substeps` substeps: beginFrame(dt), every
    /// substep, endFrame().
    void step(double dt);
    /// The frame split (the viewer steps one substep at a time): beginFrame does Algorithm 2's
    /// once-per-frame work (the repair, the frame's contact pairs, sleeping islands), each
    /// substep() one substep of the frame, endFrame what follows the last (soft damping, the
    /// sleep update). Together they give step()'s bytes. The substep count and length are fixed
    /// at beginFrame; a frame still open is closed by restore(). Returns false when no substep
    /// is left (or none is open, or the step was cancelled).
    void beginFrame(double dt);
    bool substep();
    void endFrame();
    /// Whether a frame is open (begun and not ended), its substeps done so far and in all.
    bool frameOpen() const { return frame_.open; }
    int frameSubstepsDone() const { return frame_.done; }
    int frameSubsteps() const { return frame_.substeps; }
    /// Records each constraint's corrections of every substep (substep_corrections.h), or
    /// stops; off by default, when the solve does no extra work. What the last substep recorded,
    /// or null while recording is off.
    void recordCorrections(bool on);
    const SubstepCorrections* corrections() const { return corrections_.get(); }
    /// A copy of everything a step reads that the world carries from frame to frame: bodies
    /// (poses, velocities, previous poses), joints (their drives' reached targets), the contact
    /// pairs and points, the broadphase, soft particles. Restoring it makes the following steps
    /// give the same bytes as the steps that followed the snapshot (world_snapshot.h).
    WorldSnapshot snapshot() const;
    /// Puts the world back in a snapshot's state; settings() stay the current ones.
    void restore(const WorldSnapshot& snapshot);
    /// Asks the next step to repair large violations of hard joint parts first (see
    /// WorldSettings::repairDistance): call it after moving bodies by hand.
    void requestRepair() { repairPending_ = true; }

    const WorldSettings& settings() const { return settings_; }
    /// Changes the settings; a change of gravity or of the sleep settings wakes every body.
    void setSettings(const WorldSettings& settings);
    /// Substep length of the last step (0 before the first).
    double lastSubstep() const { return lastSubstep_; }
    /// The last step's time by stage; zeros unless WorldSettings::measureTime is on.
    const StepTimes& stepTimes() const { return stepTimes_; }

    JointReadout jointReadout(JointId id) const;
    Energies energies() const;
    /// Largest positional error over all joints (m).
    double maxJointError() const;
    /// Deepest current overlap over this substep's contact points (m); 0 without contacts.
    double maxPenetration() const;
    /// Contact points that pushed in the last substep (λ_n > 0).
    int activeContactCount() const;
    /// Whether a body is asleep (WorldSettings::sleeping): its island is not being simulated.
    bool isAsleep(BodyId id) const { return isValid(id) && sleep_.asleep(id.index); }
    /// Number of sleeping bodies.
    int sleepingBodyCount() const { return sleep_.sleepingCount(); }
    /// Wakes a body's island (a sleeping body), or what touches or is jointed to it (a static
    /// body), as every edit of a body does; nothing when sleeping is off.
    void wakeBody(BodyId id);
    /// Clusters of joints around light bodies that the block solve handles (0 when it is off or
    /// no body is light; counted at the last step).
    size_t jointClusterCount() const;
    /// True while every body's state is finite.
    bool isFinite() const;

    /// Storage views for drawing and diagnostics; index 0 is the world's static anchor body.
    std::span<const Body> bodies() const { return bodies_; }
    std::span<const Joint> joints() const { return joints_; }
    /// The pairs the broadphase found this frame and the contact points of the last substep
    /// (a pair's points are contacts()[pair.first, pair.first + pair.count)).
    std::span<const ContactPair> contactPairs() const { return contactPairs_; }
    std::span<const Contact> contacts() const { return contacts_; }
    /// The box the last broadphase paired body `index` with: its shape's box grown by the
    /// frame's motion and the margin (broadphase.h). Empty for a body it left out, or while fewer
    /// than two bodies collide (no broadphase runs); infinite for a plane.
    const Aabb& broadphaseBounds(uint32_t index) const { return broadphase_.bounds(index); }
    /// Candidate pairs beyond contactPairCap() that the last step dropped (0 in any sane
    /// scene; thousands of bodies piled at one point reach it). Callers warn about it.
    std::size_t droppedContactPairs() const { return droppedContactPairs_; }
    /// The most contact pairs a frame keeps: kMaxContactPairs, or kMaxContactPairsPerBody per
    /// colliding body where that is more.
    std::size_t contactPairCap() const {
        return std::max(kMaxContactPairs, kMaxContactPairsPerBody * static_cast<std::size_t>(collidingBodies_));
    }

private:
    /// Copies a definition's parameters into a joint whose bodies are set.
    void setJointParameters(Joint& joint, const JointDef& def);
    uint32_t checked(BodyId id) const {
        if (!isValid(id)) [[unlikely]] invalidHandle("body", id.index, id.generation);
        return id.index;
    }
    uint32_t checked(JointId id) const {
        if (!isValid(id)) [[unlikely]] invalidHandle("joint", id.index, id.generation);
        return id.index;
    }
    [[noreturn]] void invalidHandle(const char* what, uint32_t index, uint32_t generation) const;
    void repairLargeViolations(double h);
    void collectContactPairs(double dt);
    /// The contacts of every pair this substep; `sleeping` notes the pairs that touch.
    void findContacts(bool sleeping);
    void integrate(double h);
    void solvePositions(double h);
    /// The joints one after another; those around light bodies by cluster, each cluster in
    /// the place of its first joint (`clusters` null when no cluster is active).
    void solveJointsInOrder(SolverContext& ctx, JointBlockSolver* clusters);
    void deriveVelocities(double h);
    void solveVelocities(double h);
    /// Adds the time since the last lap to `bucket` (WorldSettings::measureTime).
    void lap(double& bucket);

    // The parallel step (world_parallel.cpp).
    /// Whether this frame solves by colour: Gauss-Seidel, and more than one thread or
    /// WorldSettings::colouredSolve.
    bool colouredSolveActive() const;
    /// The worker pool for settings().threads, made on first use; null at 1 thread.
    WorkerPool* workerPool();
    /// Colours the frame's contact pairs and joints (beginFrame, when coloured).
    void colourConstraints();
    /// Groups this substep's touching pairs by colour (after the narrowphase, when coloured).
    void groupTouchingPairs();
    /// The position solve's joints and contacts by colour, each colour in parallel chunks.
    void solveColouredPositions(SolverContext& ctx, JointBlockSolver* clusters);
    /// The velocity pass's contact solves by colour (after the serial joints and collisions).
    void solveColouredContactVelocities(double h, double gravity);
    /// Calls advance(body) for every body the per-substep loops visit (all, or the awake ones),
    /// in parallel chunks when the pool is there and the bodies are many. `advance` writes its
    /// own body alone, so any split gives the same bytes.
    template <class Advance>
    void forEachMovingBody(const Advance& advance) {
        visitBodyRanges(
            [](const void* context, World& world, size_t first, size_t last) {
                const Advance& visit = *static_cast<const Advance*>(context);
                if (world.sleepFlags_) {
                    for (size_t k = first; k < last; ++k) visit(world.bodies_[world.awakeBodies_[k]]);
                } else {
                    for (size_t k = first; k < last; ++k) visit(world.bodies_[k]);
                }
            },
            &advance);
    }
    /// Runs task(context, *this, first, last) over [0, n) of the bodies forEachMovingBody visits
    /// (n: the awake list's length while some sleep, else every body), in chunks.
    using BodyRangeTask = void (*)(const void* context, World& world, size_t first, size_t last);
    void visitBodyRanges(BodyRangeTask task, const void* context);
    /// Colours, groups and scratch of the coloured solve, made with the first coloured frame.
    std::unique_ptr<ColouredSolve> coloured_;

    /// The frame in progress between beginFrame and endFrame.
    struct FrameInProgress {
        bool open = false;
        double dt = 0.0;
        double h = 0.0;
        int substeps = 0;
        int done = 0;
        bool sleeping = false;  ///< sleeping acts in this frame
        bool soft = false;      ///< soft bodies take part
        bool coloured = false;  ///< the solve takes constraints by colour (colouredSolveActive)
    };
    FrameInProgress frame_;
    std::chrono::steady_clock::time_point lapMark_;
    std::unique_ptr<SubstepCorrections> corrections_;

    WorldSettings settings_;
    std::vector<Body> bodies_;
    std::vector<uint32_t> freeBodies_;
    std::vector<Joint> joints_;
    std::vector<uint32_t> freeJoints_;
    std::vector<JacobiDelta> jacobiDeltas_;
    Broadphase broadphase_;
    std::vector<ContactPair> contactPairs_;
    std::vector<ContactPair> previousPairs_;
    std::vector<double> reaches_;  ///< per body: its shape's reach (0: in no pair this frame)
    std::vector<Pose> poses_;      ///< per body: its shape's pose this substep (a sphere's position alone)
    std::vector<Contact> contacts_;
    /// This substep's pairs with contact points (indices into contactPairs_, in pair order):
    /// the solve and the velocity pass visit these alone.
    std::vector<uint32_t> touchingPairs_;
    ContactSchedule contactSchedule_;  ///< this substep's touching pairs in their solve order (serial step)
    RestitutionScratch restitutionScratch_;  ///< reused by the restitution sweeps
    std::size_t droppedContactPairs_ = 0;
    /// Body pairs joined by a joint that does not let them collide, sorted; rebuilt when the
    /// joints change.
    std::vector<BodyPair> jointExclusions_;
    bool jointsChanged_ = true;
    int collidingBodies_ = 0;  ///< bodies with a shape that collides: below 2, no broadphase
    uint32_t nextGeneration_ = 1;
    double lastSubstep_ = 0.0;
    StepTimes stepTimes_;
    bool anyDamping_ = false;
    bool repairPending_ = false;
    /// The worker threads, made when settings().threads first asks for more than one.
    std::unique_ptr<WorkerPool> pool_;
    /// Per chunk of pairs of a parallel narrowphase: its contacts and its pairs that touch,
    /// merged in chunk order; where each chunk's contacts and touching pairs start in the merge.
    std::vector<std::vector<Contact>> chunkContacts_;
    std::vector<std::vector<uint32_t>> chunkTouching_;
    std::vector<uint32_t> chunkContactOffsets_;
    std::vector<uint32_t> chunkTouchingOffsets_;
    /// The contacts of pairs [first, last) into `out` (first-relative offsets in pair.first):
    /// of contactPairs_[order[k]] for k in [first, last), or contactPairs_[k] when order is null.
    /// The pairs that have a point are appended to `touching` in that order.
    void findPairContacts(const uint32_t* order, size_t first, size_t last, bool sleeping,
                          std::vector<Contact>& out, std::vector<uint32_t>& touching);
    /// Sleep state per body and the islands (WorldSettings::sleeping).
    SleepIslands sleep_;
    /// Pairs with a contact point in some substep of the frame (the islands' contact links).
    std::vector<BodyPair> touching_;
    std::vector<uint8_t> pairTouched_;  ///< per contact pair: touched in some substep
    /// This step's sleep flags per body (1: asleep), null while nothing sleeps.
    const uint8_t* sleepFlags_ = nullptr;
    /// While some body sleeps (sleepFlags_ set), the per-substep loops visit these alone: the
    /// bodies not asleep (static ones and dead slots included, which the loops skip as before),
    /// ascending, rebuilt when a body falls asleep or wakes; and the frame's pairs with no
    /// sleeping body, ascending, rebuilt each frame and when a body wakes.
    std::vector<uint32_t> awakeBodies_;
    std::vector<uint32_t> awakePairs_;
    uint64_t awakeBodiesListedAt_ = ~uint64_t{0};  ///< sleep_.changes() when awakeBodies_ was made
    size_t awakeBodiesListedFor_ = 0;               ///< bodies_.size() then
    uint64_t awakePairsListedAt_ = ~uint64_t{0};   ///< sleep_.changes() when awakePairs_ was made
    /// Brings awakeBodies_ and awakePairs_ up to date with the sleep flags (`newPairs`: the
    /// frame's pairs were just collected).
    void listAwake(bool newPairs);
    /// Whether a joint belongs to a sleeping island (then both its bodies sleep or are static).
    bool sleeps(const Joint& joint) const {
        return sleepFlags_ != nullptr && (sleepFlags_[joint.body0] | sleepFlags_[joint.body1]) != 0;
    }
    /// Whether sleeping acts in this step (on, and no soft bodies).
    bool sleepingActive() const;
    /// The clusters of joints around light bodies and their block solve (joint_block_solve.h),
    /// made when the joints first change; rebuilt when joints are created or destroyed.
    std::unique_ptr<JointBlockSolver> blocks_;
    bool clustersChanged_ = true;
    /// Whether the block solve acts in this step: on, Gauss-Seidel, and some cluster.
    bool blockSolveActive();
    /// Soft bodies, created with the first one: a world without them runs none of their stages.
    std::unique_ptr<SoftSystem> soft_;
    /// Whether soft bodies take part in this step.
    bool hasSoftBodies() const;
};

}  // namespace substep
