// SoftSystem's particle contacts, found: once per frame the (particle, rigid body) candidates
// with lower bounds on their gaps to static shapes, and every substep the contact points of the
// candidates those bounds do not skip. Solved in soft_coupling.cpp (Eqs. 26-30 and 34).
#include "physics/collision/heightfield.h"
#include "physics/collision/heightfield_sphere.h"
#include "physics/collision/heightfield_turns.h"
#include "physics/collision/narrowphase.h"
#include "physics/collision/shape_bounds.h"
#include "physics/soft/soft_body_loops.h"
#include "physics/soft/soft_system.h"
#include "physics/worker_pool.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace substep {
namespace {

/// A soft body's box over more heightfield cells than this keeps none of their normals
/// (HeightfieldGrid::keepNormals): a big body over a fine grid. A tyre's box covers a few.
constexpr int kMostKeptCells = 256;

/// Whether a body is still for a particle contact (ParticleContact::still): no inverse mass and
/// every velocity +0, so that its point's velocity b.v + ω × r is +0 and v − that is v, bit for
/// bit (−0 would turn a particle's −0 into +0).
bool isStill(const Body& b) {
    const auto positiveZero = [](const Vec3& a) {
        return a.x() == 0.0 && a.y() == 0.0 && a.z() == 0.0 && !std::signbit(a.x()) && !std::signbit(a.y()) &&
               !std::signbit(a.z());
    };
    return b.invMass == 0.0 && positiveZero(b.v) && positiveZero(b.omega) && positiveZero(b.vPrev) &&
           positiveZero(b.omegaPrev);
}

/// The highest sample of the heightfield cells that reach into the local x–z box [lo, hi] (the
/// surface over a cell lies between its corners' samples), or −∞ where the box misses the field
/// (nothing is solid there). A box over more than 4096 samples takes the field's maximum.
double highestSampleUnder(const HeightfieldData& field, const Vec3& lo, const Vec3& hi) {
    // The cells' range as HeightfieldData::forTrianglesIn takes it.
    const auto range = [](double a, double b, double origin, double cell, int cells, int& first, int& last) {
        const double i0 = std::floor((a - origin) / cell), i1 = std::floor((b - origin) / cell);
        if (!(i1 >= 0.0) || !(i0 <= cells - 1)) return false;  // also rejects NaN
        first = static_cast<int>(std::max(i0, 0.0));
        last = static_cast<int>(std::min(i1, static_cast<double>(cells - 1)));
        return true;
    };
    int i0, i1, j0, j1;
    if (!range(lo.x(), hi.x(), -0.5 * field.sizeX, field.cellX(), field.columns - 1, i0, i1) ||
        !range(lo.z(), hi.z(), -0.5 * field.sizeZ, field.cellZ(), field.rows - 1, j0, j1))
        return -std::numeric_limits<double>::infinity();
    if ((i1 - i0 + 2) * (j1 - j0 + 2) > 4096) return field.maxHeight;
    double highest = -std::numeric_limits<double>::infinity();
    for (int j = j0; j <= j1 + 1; ++j)
        for (int i = i0; i <= i1 + 1; ++i)
            highest = std::max(highest, field.heights[j * field.columns + i]);
    return highest;
}

/// Lower bounds on the gap between a particle's sphere and a static shape, for the particles of
/// one soft body in a frame (all inside `softBox`, world). The narrowphase's points are not a
/// bound (a heightfield reports the triangles under the sphere), so each shape gets its own:
/// - a box: the distance to it, in its frame;
/// - a plane: the height above it;
/// - a heightfield, solid below its surface: in its frame, the height above the highest sample
///   under the soft body's box, or, for solid outside that column, the distance to the column's
///   side, whichever is less (or the height above the field's highest sample, if larger); where
///   that leaves the particle within reach, the height above the planes of the cells within its
///   own reach (heightfieldGapBound), which on sloping cells is the distance, not the cells'
///   highest sample 5 mm above it. Not for a field whose candidates the substeps also test
///   against their clearance (`cleared`, a field in the world's axes): the clearance does that
///   bound's work for the pairs the column's bound does not skip, at less cost (rc_car: the
///   column's bound alone 0.97x the frame; heightfieldGapBound took 3.5 % of it);
/// - anything else: the distance to its world bounds.
class StaticGap {
public:
    /// `grid`: a heightfield's, which keeps the normals of the cells under the soft body's box;
    /// `cleared`: the substeps test its candidates against their clearance (SoftSystem::clearanceOf).
    StaticGap(const Shape& shape, const Pose& pose, const Aabb& bounds, const Aabb& softBox, double radius,
              HeightfieldGrid* grid, bool cleared)
        : shape_(shape), pose_(pose), plain_(heightfield_turns::isPlainIdentity(pose.rotation)), bounds_(bounds),
          radius_(radius), grid_(grid), cleared_(cleared) {
        if (shape.type != ShapeType::Heightfield || !shape.heightfield || !grid) return;
        for (int corner = 0; corner < 8; ++corner)
            column_.grow(pose.applyInverse(Vec3(corner & 1 ? softBox.max.x() : softBox.min.x(),
                                                corner & 2 ? softBox.max.y() : softBox.min.y(),
                                                corner & 4 ? softBox.max.z() : softBox.min.z())));
        highest_ = highestSampleUnder(*shape.heightfield, column_.min, column_.max);
        grid->keepNormals(column_, kMostKeptCells);
    }

    /// The bound for a particle at p that may move by `reach` in the frame (beyond it, the
    /// bound is no tighter than `reach`).
    double operator()(const Vec3& p, double reach) const {
        switch (shape_.type) {
            case ShapeType::Box: {
                const Vec3 local = heightfield_turns::applyInverse(pose_, plain_, p);
                return (local.cwiseAbs() - 0.5 * shape_.size).cwiseMax(0.0).norm() - radius_;
            }
            case ShapeType::Plane: return shape_.normal.dot(p) - shape_.offset - radius_;
            case ShapeType::Heightfield: {
                if (!shape_.heightfield || !grid_) return 0.0;
                const Vec3 local = heightfield_turns::applyInverse(pose_, plain_, p);
                const double side = std::min({local.x() - column_.min.x(), column_.max.x() - local.x(),
                                              local.z() - column_.min.z(), column_.max.z() - local.z()});
                // The old bound, the height above the whole field's highest sample, can be the
                // larger where a soft body's box overhangs its column.
                const double column =
                    std::max(local.y() - shape_.heightfield->maxHeight, std::min(local.y() - highest_, side)) - radius_;
                if (column > reach || cleared_) return column;
                return std::max(column, heightfieldGapBound(*grid_, local, radius_ + reach) - radius_);
            }
            default: return (bounds_.min - p).cwiseMax(p - bounds_.max).cwiseMax(0.0).norm() - radius_;
        }
    }

    /// Whether the bound is the distance itself, or close to it where it matters (a heightfield's
    /// near its surface): the bound alone then decides a particle's candidacy.
    bool tight() const {
        return shape_.type == ShapeType::Box || shape_.type == ShapeType::Plane ||
               shape_.type == ShapeType::Heightfield;
    }

private:
    const Shape& shape_;
    Pose pose_;
    bool plain_;  ///< pose_ is in the world's axes: its turns are shifts (heightfield_turns.h)
    Aabb bounds_;
    double radius_;
    Aabb column_;  ///< heightfield: the soft body's box in its frame
    double highest_ = 0.0;
    HeightfieldGrid* grid_;  ///< heightfield: its grid
    bool cleared_;           ///< heightfield: its candidates' clearance does heightfieldGapBound's work
};

}  // namespace

void SoftSystem::collectCandidates(std::span<const Body> bodies, double dt, double margin, const Vec3& gravity,
                                   WorkerPool* pool) {
    // Once per frame: every particle whose sphere may reach a rigid shape during the frame, with
    // a margin for the frame's motion (a particle's speed twice over, for the corrections that
    // move it, and the body's sweep). Each soft body's box is tested against each rigid body's
    // first; then each particle, against a static shape by a lower bound on its gap (StaticGap;
    // where that bound is the distance or near it, the bound alone decides, and a candidate
    // that cannot touch costs the substeps one comparison each), against a moving one by the
    // narrowphase itself. Each soft body into its own lists (with a pool, on a thread of its own).
    if (bodyCandidates_.size() < bodies_.size()) bodyCandidates_.resize(bodies_.size());
    const double fall = gravity.norm() * dt * dt;
    for (size_t s = 0; s < bodies_.size(); ++s)
        if (!bodies_[s].alive) bodyCandidates_[s].clear();
    forEachBody(pool, [&](SoftBodyData& soft) {
        collectBodyCandidates(static_cast<uint32_t>(&soft - bodies_.data()), bodies, dt, margin, fall);
    });
}

void SoftSystem::collectBodyCandidates(uint32_t s, std::span<const Body> bodies, double dt, double margin, double fall) {
    BodyCandidates& own = bodyCandidates_[s];
    own.clear();
    const SoftBodyData& soft = bodies_[s];
    if (!soft.collide || soft.particleCount == 0) return;
    ContactManifold manifold;
    const uint32_t first = soft.firstParticle, end = first + soft.particleCount;
    Aabb softBox;
    double fastest = 0.0;
    for (uint32_t i = first; i < end; ++i) {
        softBox.grow(x_[i]);
        fastest = std::max(fastest, v_[i].squaredNorm());
    }
    softBox = softBox.inflated(soft.radius + margin + 2.0 * dt * std::sqrt(fastest) + fall);
    const Shape probe = sphereShape(soft.radius);
    for (uint32_t bi = 1; bi < bodies.size(); ++bi) {
        const Body& b = bodies[bi];
        if (!b.alive || !b.collide || b.shape.type == ShapeType::None) continue;
        if (!canCollide(ShapeType::Sphere, b.shape.type)) continue;
        // The filters, as two rigid bodies' (Body::filtersMeet).
        if ((soft.collisionGroup & b.collisionMask) == 0 || (b.collisionGroup & soft.collisionMask) == 0)
            continue;
        // Attached particles sit on (or in) the body: they are held, not pushed out.
        if (std::find(soft.attachedBodies.begin(), soft.attachedBodies.end(), bi) != soft.attachedBodies.end())
            continue;
        const Pose pose{b.userPosition(), b.userOrientation()};
        // A static body stays put for the frame: its candidates keep their gap.
        const bool still = b.type == BodyType::Static;
        const double reach = shapeReach(b.shape);
        double sweep = dt * b.v.norm();
        if (std::isfinite(reach)) sweep += dt * b.omega.norm() * reach;
        const Aabb staticBounds = shapeBounds(b.shape, pose.position, pose.rotation);
        const Aabb bodyBox = staticBounds.inflated(sweep);
        if (!bodyBox.overlaps(softBox)) continue;
        if (still) {
            HeightfieldGrid* grid = nullptr;
            if (b.shape.type == ShapeType::Heightfield && b.shape.heightfield) {
                if (own.fieldGridCount == own.fieldGrids.size()) own.fieldGrids.emplace_back();
                FieldGrid& slot = own.fieldGrids[own.fieldGridCount++];
                slot.softBody = s, slot.body = bi, slot.field = b.shape.heightfield;
                slot.grid.reset(*slot.field);
                grid = &slot.grid;
            }
            // A field in the world's axes takes the particle's world coordinates less its
            // position, exactly (a turn by the identity quaternion adds zeros), so its
            // clearance moves to the world by that translation.
            const bool clearance = grid && pose.rotation.w() == 1.0 && pose.rotation.vec().isZero(0.0);
            const StaticGap gapOf(b.shape, pose, staticBounds, softBox, soft.radius, grid, clearance);
            const bool decides = gapOf.tight();
            for (uint32_t i = first; i < end; ++i) {
                const double reachOut = margin + 2.0 * dt * v_[i].norm() + fall;
                const Aabb point = Aabb{x_[i], x_[i]}.inflated(soft.radius + reachOut);
                if (!point.overlaps(bodyBox)) continue;
                const double gap = gapOf(x_[i], reachOut);
                if (gap > reachOut) continue;  // the narrowphase would find nothing
                if (!decides) {
                    collide(probe, Pose{x_[i], Quat::Identity()}, b.shape, pose, reachOut, manifold);
                    if (manifold.count == 0) continue;
                }
                Candidate& candidate = own.add({.particle = i, .body = bi, .softBody = s}, gap, x_[i]);
                if (clearance) {
                    candidate.clearAbove = std::numeric_limits<double>::quiet_NaN();  // findContacts'
                    candidate.roam = reachOut - margin;
                }
            }
            continue;
        }
        for (uint32_t i = first; i < end; ++i) {
            const double reachOut = margin + 2.0 * dt * v_[i].norm() + sweep + fall;
            const Aabb point = Aabb{x_[i], x_[i]}.inflated(soft.radius + reachOut);
            if (!point.overlaps(bodyBox)) continue;
            collide(probe, Pose{x_[i], Quat::Identity()}, b.shape, pose, reachOut, manifold);
            if (manifold.count == 0) continue;
            // Never skipped: a moving body's gap changes with its own motion too.
            own.add({.particle = i, .body = bi, .softBody = s}, -std::numeric_limits<double>::infinity(), x_[i]);
        }
    }
}

void SoftSystem::BodyCandidates::clear() {
    candidates.clear();
    skips.clear();
    for (FieldGrid& slot : fieldGrids) slot.field.reset();
    fieldGridCount = 0;
}

SoftSystem::Candidate& SoftSystem::BodyCandidates::add(const Candidate& candidate, double gap, const Vec3& origin) {
    skips.add(origin, gap, candidate.particle);
    return candidates.emplace_back(candidate);
}

void SoftSystem::clearanceOf(const BodyCandidates& own, Candidate& candidate, const Body& field, double margin) const {
    const HeightfieldGrid* grid = nullptr;
    for (size_t g = 0; g < own.fieldGridCount && !grid; ++g) {
        const FieldGrid& slot = own.fieldGrids[g];
        if (slot.softBody == candidate.softBody && slot.body == candidate.body) grid = &slot.grid;
    }
    candidate.clearAbove = std::numeric_limits<double>::infinity();
    if (!grid) return;
    // The field's frame is the world's shifted by its position (collectCandidates checked
    // that its turn is the identity), so its clearance moves to the world by that shift, with
    // a slack for the rounding of the shift.
    const Vec3 t = field.userPosition();
    const double shiftSlack = 1e-9 * (1.0 + t.cwiseAbs().maxCoeff());
    const HeightfieldClearance clear = heightfieldClearance(*grid, x_[candidate.particle] - t,
                                                            bodies_[candidate.softBody].radius + margin, candidate.roam);
    candidate.clearAbove = clear.above + t.y() + shiftSlack;
    candidate.clearLowX = clear.lowX + t.x() + shiftSlack;
    candidate.clearHighX = clear.highX + t.x() - shiftSlack;
    candidate.clearLowZ = clear.lowZ + t.z() + shiftSlack;
    candidate.clearHighZ = clear.highZ + t.z() - shiftSlack;
}

void SoftSystem::findContacts(std::span<const Body> bodies, double margin, WorkerPool* pool) {
    // Each soft body's candidates on their own (with a pool, on a thread of their own, into
    // their own list, the lists joined in the bodies' order): the contacts and their order are
    // the serial ones whichever thread found them.
    contacts_.clear();
    if (!pool || liveBodies_ < 2) {
        for (BodyCandidates& own : bodyCandidates_) {
            own.firstContact = contacts_.size();
            if (!own.candidates.empty()) findBodyContacts(own, bodies, margin, contacts_);
            own.endContact = contacts_.size();
        }
        bodiesApart_ = false;
        return;
    }
    pool->parallelFor(static_cast<int>(bodyCandidates_.size()), [&](int s) {
        BodyCandidates& own = bodyCandidates_[static_cast<size_t>(s)];
        own.contacts.clear();
        if (!own.candidates.empty()) findBodyContacts(own, bodies, margin, own.contacts);
    });
    for (BodyCandidates& own : bodyCandidates_) {
        own.firstContact = contacts_.size();
        contacts_.insert(contacts_.end(), own.contacts.begin(), own.contacts.end());
        own.endContact = contacts_.size();
    }
    planShares(bodies);
}

void SoftSystem::findBodyContacts(BodyCandidates& own, std::span<const Body> bodies, double margin,
                                  std::vector<ParticleContact>& out) {
    ContactManifold manifold;
    uint32_t poseBody = UINT32_MAX;
    uint32_t probeBody = UINT32_MAX;
    Pose pose;
    Shape probe;
    const HeightfieldGrid* grid = nullptr;
    HeightfieldGrid ownGrid;  // a heightfield's without candidates kept by collectCandidates
    double staticFriction = 0.0, dynamicFriction = 0.0, restitution = 0.0;
    bool still = false;
    bool plain = false;  // the body's rotation is the plain identity (heightfield_turns.h)
    // Candidates come grouped by soft body, then rigid body: poses and probes are made once
    // per group.
    // The candidates that may touch in this substep (candidate_skips.h: most candidates of a
    // rolling tyre are skipped there).
    own.kept.resize(own.candidates.size());
    const uint32_t* const kept = own.kept.data();
    const size_t keptCount = keepUnskipped(own.skips, x_.data(), margin, own.kept.data());
    // The kept ones' records are fetched ahead: a rolling tyre keeps about a fifth of its
    // candidates, scattered, and each was a cache miss.
    const Candidate* const candidates = own.candidates.data();
    constexpr size_t kFetchAhead = 8;
    for (size_t n = 0; n < std::min(keptCount, kFetchAhead); ++n) __builtin_prefetch(candidates + kept[n]);
    for (size_t n = 0; n < keptCount; ++n) {
        if (n + kFetchAhead < keptCount) __builtin_prefetch(candidates + kept[n + kFetchAhead]);
        Candidate& candidate = own.candidates[kept[n]];
        const Vec3& x = x_[candidate.particle];
        // Or it is above every sample of the cells the narrowphase would visit (a rolling tread
        // particle moves along the ground more than toward it). Most candidates never get here,
        // so the clearance is computed the first time one does, from where the particle is.
        if (std::isnan(candidate.clearAbove)) clearanceOf(own, candidate, bodies[candidate.body], margin);
        if (x.y() > candidate.clearAbove && x.x() > candidate.clearLowX && x.x() < candidate.clearHighX &&
            x.z() > candidate.clearLowZ && x.z() < candidate.clearHighZ)
            continue;
        const Body& b = bodies[candidate.body];
        const SoftBodyData& soft = bodies_[candidate.softBody];
        if (candidate.body != poseBody || candidate.softBody != probeBody) {
            poseBody = candidate.body;
            probeBody = candidate.softBody;
            pose = {b.userPosition(), b.userOrientation()};
            probe = sphereShape(soft.radius);
            grid = nullptr;
            if (b.shape.type == ShapeType::Heightfield && b.shape.heightfield) {
                for (size_t g = 0; g < own.fieldGridCount && !grid; ++g) {
                    const FieldGrid& slot = own.fieldGrids[g];
                    if (slot.softBody == candidate.softBody && slot.body == candidate.body && slot.field == b.shape.heightfield)
                        grid = &slot.grid;
                }
                if (!grid) {
                    ownGrid.reset(*b.shape.heightfield);
                    grid = &ownGrid;
                }
            }
            // Paper 3.5: a pair's coefficients are the averages of its bodies'.
            staticFriction = 0.5 * (soft.staticFriction + b.staticFriction);
            dynamicFriction = 0.5 * (soft.dynamicFriction + b.dynamicFriction);
            restitution = 0.5 * (soft.restitution + b.restitution);
            still = isStill(b);
            plain = heightfield_turns::isPlainIdentity(b.q);
        }
        // A heightfield's cells straight from its heights (heightfield_sphere.h), the same points.
        if (grid) collideSphereHeightfield(*grid, x_[candidate.particle], soft.radius, pose, margin, manifold);
        else collide(probe, Pose{x_[candidate.particle], Quat::Identity()}, b.shape, pose, margin, manifold);
        const Quat inverse = b.q.conjugate();
        for (int m = 0; m < manifold.count; ++m) {
            const ContactPoint& point = manifold.points[m];
            const Vec3 offset = point.point1 - b.x;
            // A body in the world's axes (rc_car's ground) turns a finite vector, either way, by
            // a shift of nothing: the same bits as Eigen's two turns (heightfield_turns.h).
            const bool shift = plain && heightfield_turns::isFinite(offset);
            const Vec3 local1 = shift ? heightfield_turns::unturned(offset) : Vec3(inverse * offset);
            out.push_back({.particle = candidate.particle,
                           .body = candidate.body,
                           .local1 = local1,
                           .normal = point.normal,
                           .radius = soft.radius,
                           .staticFriction = staticFriction,
                           .dynamicFriction = dynamicFriction,
                           .restitution = restitution,
                           .still = still,
                           .anchor = !still ? Vec3::Zero()
                                     : shift ? Vec3(b.x + heightfield_turns::unturned(local1))
                                             : b.pointToWorld(local1)});
        }
    }
}

}  // namespace substep
