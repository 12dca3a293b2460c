// SoftSystem's coupling to rigid bodies: attachments (Eqs. 2-9) and particle contacts
// (Eqs. 26-30 and 34), each particle standing in for a body with w = 1/m and no rotation
// (paper section 4).
#include "physics/collision/heightfield.h"
#include "physics/collision/heightfield_sphere.h"
#include "physics/collision/narrowphase.h"
#include "physics/collision/shape_bounds.h"
#include "physics/soft/soft_system.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace substep {
namespace {

/// A soft body's box over more heightfield cells than this keeps none of their normals
/// (HeightfieldGrid::keepNormals): a big body over a fine grid. A tyre's box covers a few.
constexpr int kMostKeptCells = 256;

/// The speed (m/s) at which an overlap the motion does not explain is pushed out: the rigid
/// contacts' value (contact.cpp), so a particle created sunk into the ground rises gently.
constexpr double kPushOutSpeed = 1.0;
/// Below this speed a contact's velocity is left alone (contact.cpp's kRestingSpeed).
constexpr double kRestingSpeed = 1e-9;

/// A body's generalised inverse mass for a correction along unit n at world offset r
/// (Eqs. 2-3); 0 for static bodies.
inline double bodyInverseMass(const Body& b, const Vec3& r, const Vec3& n) {
    return b.invMass > 0.0 ? b.positionalInverseMass(r, n) : 0.0;
}

/// Velocity of a body's point at world offset r.
inline Vec3 pointVelocity(const Body& b, const Vec3& r) { return b.v + b.omega.cross(r); }

/// Eq. 33 for a particle (velocity v, inverse mass w) against a body's point at r: changes
/// their relative velocity by `change`.
inline void applyVelocityChange(Vec3& v, double w, Body& b, const Vec3& r, const Vec3& change) {
    const double magnitude = change.norm();
    if (!(magnitude > kDirectionEpsilon)) return;
    const Vec3 n = change / magnitude;
    const double wb = bodyInverseMass(b, r, n);
    const Vec3 p = change / (w + wb);
    v += w * p;
    if (b.invMass > 0.0) {
        b.v -= b.invMass * p;
        if (b.rotates()) b.omega -= b.applyInverseInertia(r.cross(p));
    }
}

/// Where a body's point at world offset r was at the start of the substep (a static body does
/// not move; its previous pose is not kept).
inline Vec3 previousPoint(const Body& b, const Vec3& local) {
    if (b.invMass == 0.0) return b.pointToWorld(local);
    return b.xPrev + (b.rotates() ? Vec3(b.qPrev * local) : local);
}

/// Eq. 26 for one particle contact: pushes the particle at x (inverse mass w, velocity v) out
/// of body `body` along n, whose surface point is kept at `local1` in the body's frame (Eqs. 2-4,
/// α = 0), the depth capped as the rigid contacts' push-out is. Returns Δλ_n, 0 when apart.
double pushOut(SolverContext& ctx, uint32_t body, const Vec3& local1, const Vec3& n, double radius, Vec3& x,
               double w, const Vec3& v) {
    const Body& b = ctx.bodies[body];
    const Vec3 r = b.q * local1;
    // d = (p1 − p0)·n with p0 the particle's surface point.
    double depth = (b.x + r - (x - radius * n)).dot(n);
    if (depth > 0.0 && ctx.capPushOut) {
        const double approach = -(v - pointVelocity(b, r)).dot(n);
        depth = std::min(depth, ctx.h * std::max(approach, kPushOutSpeed));
    }
    if (!(depth > 0.0)) return 0.0;
    const double deltaLambda = depth / (w + bodyInverseMass(b, r, n));
    x += (w * deltaLambda) * n;
    if (b.invMass > 0.0) applyImpulse(ctx, body, 0, -deltaLambda * n, r.cross(-deltaLambda * n), Vec3::Zero());
    return deltaLambda;
}

/// Eqs. 27-28 for one particle contact: the particle's tangential motion during the substep
/// relative to the body's point at r (kept at `local1`), as a direction t and the Δλ_t that
/// undoes it. False when it did not slip.
bool staticSlip(const Body& b, const Vec3& r, const Vec3& local1, const Vec3& n, const Vec3& x, const Vec3& xPrev,
                double w, Vec3& t, double& deltaTangent) {
    const Vec3 motion = (x - xPrev) - (b.x + r - previousPoint(b, local1));
    const Vec3 slip = motion - motion.dot(n) * n;
    const double length = slip.norm();
    if (!(length > kDirectionEpsilon)) return false;
    t = slip / length;
    deltaTangent = length / (w + bodyInverseMass(b, r, t));
    return true;
}

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

/// pushOut against a still body whose point is `anchor`: its velocity and generalised inverse
/// mass are zero (and w + 0 = w), so the same depth, cap and Δλ_n without rotating r1.
double pushOutOfStill(const SolverContext& ctx, const Vec3& anchor, const Vec3& n, double radius, Vec3& x, double w,
                      const Vec3& v) {
    double depth = (anchor - (x - radius * n)).dot(n);
    if (depth > 0.0 && ctx.capPushOut) {
        const double approach = -v.dot(n);
        depth = std::min(depth, ctx.h * std::max(approach, kPushOutSpeed));
    }
    if (!(depth > 0.0)) return 0.0;
    const double deltaLambda = depth / w;
    x += (w * deltaLambda) * n;
    return deltaLambda;
}

/// staticSlip against a still body: its point did not move, so the slip is the particle's own
/// tangential motion.
bool staticSlipOnStill(const Vec3& n, const Vec3& x, const Vec3& xPrev, double w, Vec3& t, double& deltaTangent) {
    const Vec3 motion = x - xPrev;
    const Vec3 slip = motion - motion.dot(n) * n;
    const double length = slip.norm();
    if (!(length > kDirectionEpsilon)) return false;
    t = slip / length;
    deltaTangent = length / w;
    return true;
}

/// applyVelocityChange against a still body: the particle takes it all.
inline void changeVelocityOnStill(Vec3& v, double w, const Vec3& change) {
    if (!(change.norm() > kDirectionEpsilon)) return;
    const Vec3 p = change / w;
    v += w * p;
}

/// Eq. 4 for an attachment whose particle is `delta` short of the body's point (c = |delta|,
/// c2 = c²), multiplier lambda (updated) and compliance term α̃ = α / h², between generalised
/// inverse masses w + w_body = wLinear + angular / c² (Eqs. 2-3: `angular` is
/// (r × delta)ᵀ I⁻¹ (r × delta), 0 when wLinear holds the whole sum). Returns the factor f of
/// the impulse Δλ n = Δλ delta / c = f delta. Written over c² (Δλ = c² (c − α̃ λ) /
/// ((wLinear + α̃) c² + angular)), a hard attachment's impulse waits for one division and no
/// square root: the rim's run of attachments is a chain, each correction moving the body the
/// next one starts from.
inline double attachmentImpulse(double& lambda, double alphaTilde, double c2, double wLinear, double angular) {
    const double denominator = (wLinear + alphaTilde) * c2 + angular;
    const double c = std::sqrt(c2);
    const double deltaLambda = c2 * (c - alphaTilde * lambda) / denominator;  // Eq. 4
    const double factor =
        alphaTilde == 0.0 ? c2 / denominator : (c2 - alphaTilde * lambda * c) / denominator;
    lambda += deltaLambda;
    return factor;
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
///   highest sample 5 mm above it;
/// - anything else: the distance to its world bounds.
class StaticGap {
public:
    /// `grid`: a heightfield's, which keeps the normals of the cells under the soft body's box.
    StaticGap(const Shape& shape, const Pose& pose, const Aabb& bounds, const Aabb& softBox, double radius,
              HeightfieldGrid* grid)
        : shape_(shape), pose_(pose), bounds_(bounds), radius_(radius), grid_(grid) {
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
                const Vec3 local = pose_.applyInverse(p);
                return (local.cwiseAbs() - 0.5 * shape_.size).cwiseMax(0.0).norm() - radius_;
            }
            case ShapeType::Plane: return shape_.normal.dot(p) - shape_.offset - radius_;
            case ShapeType::Heightfield: {
                if (!shape_.heightfield || !grid_) return 0.0;
                const Vec3 local = pose_.applyInverse(p);
                const double side = std::min({local.x() - column_.min.x(), column_.max.x() - local.x(),
                                              local.z() - column_.min.z(), column_.max.z() - local.z()});
                // The old bound, the height above the whole field's highest sample, can be the
                // larger where a soft body's box overhangs its column.
                const double column =
                    std::max(local.y() - shape_.heightfield->maxHeight, std::min(local.y() - highest_, side)) - radius_;
                if (column > reach) return column;
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
    Aabb bounds_;
    double radius_;
    Aabb column_;  ///< heightfield: the soft body's box in its frame
    double highest_ = 0.0;
    HeightfieldGrid* grid_;  ///< heightfield: its grid
};

}  // namespace

void SoftSystem::addAttachments(const SoftBodyDef& def, SoftBodyData& data,
                                const Lattice& lattice, std::span<const Body> bodies) {
    ContactManifold manifold;
    for (const SoftAttachmentDef& attach : def.attachments) {
        const uint32_t bodyIndex = attach.body.isNull() ? 0 : attach.body.index;
        if (bodyIndex >= bodies.size() || !bodies[bodyIndex].alive) continue;
        const Body& b = bodies[bodyIndex];
        const Pose pose{b.userPosition(), b.userOrientation()};
        const Shape probe = sphereShape(data.radius);
        data.attachedBodies.push_back(bodyIndex);
        for (uint32_t local = 0; local < data.particleCount; ++local) {
            const uint32_t i = data.firstParticle + local;
            bool held = true;
            if (attach.particles == SoftAttachmentParticles::Inner) held = lattice.inner[local] != 0;
            if (attach.particles == SoftAttachmentParticles::Below) {
                // Inside the shape: the particle's sphere overlaps it by at least its radius.
                collide(probe, Pose{x_[i], Quat::Identity()}, b.shape, pose, 0.0, manifold);
                held = false;
                for (int k = 0; k < manifold.count; ++k) held = held || manifold.points[k].depth >= data.radius;
            }
            if (!held) continue;
            attachments_.push_back({.particle = i,
                                    .body = bodyIndex,
                                    .local = b.q.conjugate() * (x_[i] - b.x),
                                    .compliance = attach.compliance});
        }
    }
}

void SoftSystem::solveAttachments(SolverContext& ctx) {
    // Eqs. 2-9 with body 0 the particle (w = 1/m, no rotation) and body 1 the rigid body:
    // the particle is moved onto the body's point, shared by generalised inverse mass.
    if (ctx.solver == SolverType::Jacobi) {
        for (Attachment& a : attachments_) {
            const Body& b = ctx.bodies[a.body];
            const Vec3 r = b.q * a.local;
            const Vec3 delta = b.x + r - x_[a.particle];
            const double c = delta.norm();
            if (!(c > kDirectionEpsilon)) continue;
            const Vec3 n = delta / c;
            const double w = invMass_[a.particle];
            const double wb = bodyInverseMass(b, r, n);
            const Vec3 p = attachmentImpulse(a.lambda, a.compliance * ctx.invH2, c * c, w + wb, 0.0) * delta;
            x_[a.particle] += w * p;                                                    // Eq. 6
            if (wb > 0.0) applyImpulse(ctx, a.body, 0, -p, r.cross(-p), Vec3::Zero());  // Eqs. 7-9
        }
        return;
    }
    // Gauss-Seidel: attachments come grouped by rigid body, and a run of them to one body (a
    // rim holds hundreds) keeps the body's pose in local variables: its rotation matrix and
    // world inverse inertia from the start of the run, turned to first order by the run's
    // accumulated rotation (microradians per substep), written back once at the end by the
    // exact map. The same corrections as one attachment after the other, to second order in
    // that rotation, without a quaternion update per particle.
    size_t k = 0;
    while (k < attachments_.size()) {
        const uint32_t bodyIndex = attachments_[k].body;
        size_t end = k;
        while (end < attachments_.size() && attachments_[end].body == bodyIndex)
            ++end;
        Body& b = ctx.bodies[bodyIndex];
        const bool moves = b.invMass > 0.0;
        const bool turns = moves && b.rotates();
        const Mat3 rotation = b.q.toRotationMatrix();
        const Mat3 inverseInertia =
            turns ? Mat3(rotation * b.invInertia.asDiagonal() * rotation.transpose())
                  : Mat3::Zero();
        const double inverseMass = moves ? b.invMass : 0.0;
        Vec3 position = b.x, turned = Vec3::Zero();
        for (; k < end; ++k) {
            Attachment& a = attachments_[k];
            const Vec3 r0 = rotation * a.local;
            const Vec3 r = r0 + turned.cross(r0);
            const Vec3 delta = position + r - x_[a.particle];
            const double c2 = delta.squaredNorm();
            if (!(c2 > kDirectionEpsilon * kDirectionEpsilon)) continue;
            const double w = invMass_[a.particle];
            const Vec3 rd = r.cross(delta);
            const Vec3 spin = inverseInertia * rd;
            const double angular = rd.dot(spin);  // Eqs. 2-3, times c²
            // p = f delta, so I⁻¹ (r × p) = f I⁻¹ (r × delta): the body's turn reuses what
            // its inverse mass took, one multiplication after the division on the chain.
            const double factor = attachmentImpulse(a.lambda, a.compliance * ctx.invH2, c2, w + inverseMass, angular);
            x_[a.particle] += (w * factor) * delta;       // Eq. 6
            position -= (inverseMass * factor) * delta;   // Eq. 7, the body receiving −p
            turned -= factor * spin;                      // Eq. 8
        }
        if (moves) {
            b.x = position;
            if (turns) integrateRotation(b.q, turned);  // Eq. 9 by the exact map, as moveBody does
        }
    }
}

void SoftSystem::collectCandidates(std::span<const Body> bodies, double dt, double margin, const Vec3& gravity) {
    // Once per frame: every particle whose sphere may reach a rigid shape during the frame, with
    // a margin for the frame's motion (a particle's speed twice over, for the corrections that
    // move it, and the body's sweep). Each soft body's box is tested against each rigid body's
    // first; then each particle, against a static shape by a lower bound on its gap (StaticGap;
    // where that bound is the distance or near it, the bound alone decides, and a candidate
    // that cannot touch costs the substeps one comparison each), against a moving one by the
    // narrowphase itself.
    candidates_.clear();
    for (FieldGrid& slot : fieldGrids_) slot.field.reset();
    fieldGridCount_ = 0;
    const double fall = gravity.norm() * dt * dt;
    ContactManifold manifold;
    for (uint32_t s = 0; s < bodies_.size(); ++s) {
        const SoftBodyData& soft = bodies_[s];
        if (!soft.alive || !soft.collide || soft.particleCount == 0) continue;
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
                    if (fieldGridCount_ == fieldGrids_.size()) fieldGrids_.emplace_back();
                    FieldGrid& slot = fieldGrids_[fieldGridCount_++];
                    slot.softBody = s, slot.body = bi, slot.field = b.shape.heightfield;
                    slot.grid.reset(*slot.field);
                    grid = &slot.grid;
                }
                const StaticGap gapOf(b.shape, pose, staticBounds, softBox, soft.radius, grid);
                const bool decides = gapOf.tight();
                // A field in the world's axes takes the particle's world coordinates less its
                // position, exactly (a turn by the identity quaternion adds zeros), so its
                // clearance moves to the world by that translation.
                const bool clearance = grid && pose.rotation.w() == 1.0 && pose.rotation.vec().isZero(0.0);
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
                    Candidate& candidate = candidates_.emplace_back(
                        Candidate{.particle = i, .body = bi, .softBody = s, .gap = gap, .origin = x_[i]});
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
                candidates_.push_back({.particle = i, .body = bi, .softBody = s,
                                       .gap = -std::numeric_limits<double>::infinity(), .origin = x_[i]});
            }
        }
    }
}

void SoftSystem::clearanceOf(Candidate& candidate, const Body& field, double margin) const {
    const HeightfieldGrid* grid = nullptr;
    for (size_t g = 0; g < fieldGridCount_ && !grid; ++g) {
        const FieldGrid& slot = fieldGrids_[g];
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

void SoftSystem::findContacts(std::span<const Body> bodies, double margin) {
    contacts_.clear();
    ContactManifold manifold;
    uint32_t poseBody = UINT32_MAX;
    uint32_t probeBody = UINT32_MAX;
    Pose pose;
    Shape probe;
    const HeightfieldGrid* grid = nullptr;
    HeightfieldGrid ownGrid;  // a heightfield's without candidates kept by collectCandidates
    double staticFriction = 0.0, dynamicFriction = 0.0, restitution = 0.0;
    bool still = false;
    // Candidates come grouped by soft body, then rigid body: poses and probes are made once
    // per group.
    for (Candidate& candidate : candidates_) {
        // The particle's distance to a static shape changes by at most its own displacement:
        // a particle still further than the margin from it cannot touch it in this substep
        // (compared squared: most candidates of a rolling tyre are skipped here).
        const Vec3& x = x_[candidate.particle];
        const double slack = candidate.gap - margin;
        if (slack > 0.0 && (x - candidate.origin).squaredNorm() < slack * slack) continue;
        // Or it is above every sample of the cells the narrowphase would visit (a rolling tread
        // particle moves along the ground more than toward it). Most candidates never get here,
        // so the clearance is computed the first time one does, from where the particle is.
        if (std::isnan(candidate.clearAbove)) clearanceOf(candidate, bodies[candidate.body], margin);
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
                for (size_t g = 0; g < fieldGridCount_ && !grid; ++g) {
                    const FieldGrid& slot = fieldGrids_[g];
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
        }
        // A heightfield's cells straight from its heights (heightfield_sphere.h), the same points.
        if (grid) collideSphereHeightfield(*grid, x_[candidate.particle], soft.radius, pose, margin, manifold);
        else collide(probe, Pose{x_[candidate.particle], Quat::Identity()}, b.shape, pose, margin, manifold);
        const Quat inverse = b.q.conjugate();
        for (int k = 0; k < manifold.count; ++k) {
            const ContactPoint& point = manifold.points[k];
            const Vec3 local1 = inverse * (point.point1 - b.x);
            contacts_.push_back({.particle = candidate.particle,
                                 .body = candidate.body,
                                 .local1 = local1,
                                 .normal = point.normal,
                                 .radius = soft.radius,
                                 .staticFriction = staticFriction,
                                 .dynamicFriction = dynamicFriction,
                                 .restitution = restitution,
                                 .still = still,
                                 .anchor = still ? b.pointToWorld(local1) : Vec3::Zero()});
        }
    }
}

void SoftSystem::groupContactPatches() {
    // Contacts come grouped by soft body, then rigid body (the candidates' order), so the last
    // patch is nearly always the one; any other order still finds its patch.
    patches_.clear();
    contactPatch_.resize(contacts_.size());
    frictionStep_.assign(contacts_.size(), Vec3::Zero());
    uint32_t owner = 0, ownerFirst = 0, ownerEnd = 0;
    for (size_t k = 0; k < contacts_.size(); ++k) {
        const ParticleContact& c = contacts_[k];
        if (c.particle < ownerFirst || c.particle >= ownerEnd) {
            for (uint32_t s = 0; s < bodies_.size(); ++s) {
                const SoftBodyData& soft = bodies_[s];
                if (soft.alive && c.particle >= soft.firstParticle && c.particle < soft.firstParticle + soft.particleCount) {
                    owner = s, ownerFirst = soft.firstParticle, ownerEnd = soft.firstParticle + soft.particleCount;
                    break;
                }
            }
        }
        size_t patch = patches_.size();
        while (patch > 0 && (patches_[patch - 1].softBody != owner || patches_[patch - 1].body != c.body))
            --patch;
        if (patch == 0) {
            patches_.push_back({.softBody = owner, .body = c.body, .staticFriction = c.staticFriction,
                                .dynamicFriction = c.dynamicFriction});
            patch = patches_.size();
        }
        contactPatch_[k] = static_cast<uint32_t>(patch - 1);
    }
}

void SoftSystem::solveContacts(SolverContext& ctx) {
    if (patchFriction_) solveContactsPerPatch(ctx);
    else solveContactsPerParticle(ctx);
}

double SoftSystem::takeHeldImpulse(SolverContext& ctx, ParticleContact& c) {
    double& held = heldImpulse_[c.particle];
    if (!(held > 0.0)) return 0.0;
    const double taken = held;
    held = 0.0;
    c.lambdaNormal += taken;
    const Body& b = ctx.bodies[c.body];
    if (b.invMass > 0.0) {
        const Vec3 r = b.q * c.local1;
        applyImpulse(ctx, c.body, 0, -taken * c.normal, r.cross(-taken * c.normal), Vec3::Zero());
    }
    return taken;
}

void SoftSystem::solveContactsPerParticle(SolverContext& ctx) {
    for (ParticleContact& c : contacts_) {
        const Body& b = ctx.bodies[c.body];
        const Vec3& n = c.normal;
        Vec3& x = x_[c.particle];
        const double w = invMass_[c.particle];
        // The elements' push this particle's normal did not take first (a moving body
        // receives it), then Eq. 26.
        const double held = takeHeldImpulse(ctx, c);
        if (c.still) {
            // The ground and the obstacles: the same steps with the body's terms left out.
            const double pushed = pushOutOfStill(ctx, c.anchor, n, c.radius, x, w, v_[c.particle]);
            if (!(pushed > 0.0) && !(held > 0.0)) continue;
            if (pushed > 0.0) c.lambdaNormal += pushed;
            if (!(c.staticFriction > 0.0)) continue;
            Vec3 t;
            double deltaTangent;
            if (!staticSlipOnStill(n, x, xPrev_[c.particle], w, t, deltaTangent)) continue;
            if (c.lambdaTangent + deltaTangent > c.staticFriction * c.lambdaNormal) continue;
            c.lambdaTangent += deltaTangent;
            c.frictionImpulse -= deltaTangent * t;
            x -= (w * deltaTangent) * t;
            continue;
        }
        const double pushed = pushOut(ctx, c.body, c.local1, n, c.radius, x, w, v_[c.particle]);
        if (!(pushed > 0.0) && !(held > 0.0)) continue;
        if (pushed > 0.0) c.lambdaNormal += pushed;
        if (!(c.staticFriction > 0.0)) continue;
        // Eqs. 27-28: undo the tangential motion of the particle relative to the body's point
        // during the substep while λ_t stays within μ_s λ_n.
        const Vec3 r = b.q * c.local1;
        Vec3 t;
        double deltaTangent;
        if (!staticSlip(b, r, c.local1, n, x, xPrev_[c.particle], w, t, deltaTangent)) continue;
        if (c.lambdaTangent + deltaTangent > c.staticFriction * c.lambdaNormal) continue;
        c.lambdaTangent += deltaTangent;
        c.frictionImpulse -= deltaTangent * t;
        x -= (w * deltaTangent) * t;
        if (b.invMass > 0.0) applyImpulse(ctx, c.body, 0, deltaTangent * t, r.cross(deltaTangent * t), Vec3::Zero());
    }
}

void SoftSystem::solveContactsPerPatch(SolverContext& ctx) {
    groupContactPatches();
    // Eq. 26 for every contact first, so that static friction is judged on the patch's whole
    // normal multiplier of this substep.
    for (ParticleContact& c : contacts_) {
        takeHeldImpulse(ctx, c);
        const double pushed =
            pushOut(ctx, c.body, c.local1, c.normal, c.radius, x_[c.particle], invMass_[c.particle], v_[c.particle]);
        if (pushed > 0.0) c.lambdaNormal += pushed;
    }
    // Each patch's load: Σ λ_n, its λ_n-weighted centre and normal, and Σ λ_n ρ (ρ a particle's
    // distance from the centre across the normal), the twist μ_s holds per unit μ_s.
    for (size_t k = 0; k < contacts_.size(); ++k) {
        const ParticleContact& c = contacts_[k];
        ContactPatch& patch = patches_[contactPatch_[k]];
        patch.normal += c.lambdaNormal;
        patch.centre += c.lambdaNormal * x_[c.particle];
        patch.direction += c.lambdaNormal * c.normal;
    }
    for (ContactPatch& patch : patches_) {
        if (!(patch.normal > 0.0)) continue;
        patch.centre /= patch.normal;
        const double length = patch.direction.norm();
        patch.direction = length > kDirectionEpsilon ? Vec3(patch.direction / length) : Vec3::Zero();
    }
    for (size_t k = 0; k < contacts_.size(); ++k) {
        const ParticleContact& c = contacts_[k];
        ContactPatch& patch = patches_[contactPatch_[k]];
        if (!(c.lambdaNormal > 0.0) || !(patch.staticFriction > 0.0)) continue;
        const Vec3 offset = x_[c.particle] - patch.centre;
        patch.reach += c.lambdaNormal * (offset - offset.dot(patch.direction) * patch.direction).norm();
    }
    // Eqs. 27-28 for each pushing contact: the tangential motion of the particle relative to
    // the body's point during the substep is undone ...
    for (size_t k = 0; k < contacts_.size(); ++k) {
        ParticleContact& c = contacts_[k];
        if (!(c.lambdaNormal > 0.0) || !(patches_[contactPatch_[k]].staticFriction > 0.0)) continue;
        const Body& b = ctx.bodies[c.body];
        const Vec3& n = c.normal;
        Vec3& x = x_[c.particle];
        const double w = invMass_[c.particle];
        const Vec3 r = b.q * c.local1;
        Vec3 t;
        double deltaTangent;
        if (!staticSlip(b, r, c.local1, n, x, xPrev_[c.particle], w, t, deltaTangent)) continue;
        const Vec3 impulse = -deltaTangent * t;  // on the particle
        c.lambdaTangent += deltaTangent;
        c.frictionImpulse += impulse;
        frictionStep_[k] = impulse;
        x += w * impulse;
        if (b.invMass > 0.0) applyImpulse(ctx, c.body, 0, -impulse, r.cross(-impulse), Vec3::Zero());
    }
    // ... and kept whole where the patch's static friction, its force and its twist about the
    // patch's normal, stays within μ_s Σλ_n and μ_s Σλ_n ρ (combined as an ellipse): a patch
    // holds or slides as one, whatever share of the load each particle carries while the body
    // settles. Particle by particle, the least loaded ones (uphill on a slope) let go first and
    // a soft box slid off well below atan(μ_s).
    for (size_t k = 0; k < contacts_.size(); ++k) {
        const ParticleContact& c = contacts_[k];
        ContactPatch& patch = patches_[contactPatch_[k]];
        patch.force += c.frictionImpulse;
        patch.twist += (x_[c.particle] - patch.centre).cross(c.frictionImpulse).dot(patch.direction);
    }
    for (ContactPatch& patch : patches_) {
        const double forceLimit = patch.staticFriction * patch.normal;
        // A twist limit of at least μ_s Σλ_n × 1 µm: a one-point patch holds no twist worth
        // the name, and the ratio stays finite.
        const double twistLimit = patch.staticFriction * std::max(patch.reach, 1e-6 * patch.normal);
        const double force = patch.force.norm() / forceLimit;
        const double twist = patch.twist / twistLimit;
        const double ratio = std::sqrt(force * force + twist * twist);
        // A patch past the limit slides, and keeps μ_d / μ_s of that, scaled back onto the
        // limit: kinetic friction μ_d Σλ_n at the position level. Eq. 30 in the velocity pass
        // would change the particles' velocities only, not take back the slip the elements'
        // pull made within the substep, and a box that broke loose slid on with less than μ_d.
        patch.kept = forceLimit > 0.0 ? (ratio <= 1.0 ? 1.0 : patch.dynamicFriction / (patch.staticFriction * ratio)) : 0.0;
    }
    for (size_t k = 0; k < contacts_.size(); ++k) {
        const double kept = patches_[contactPatch_[k]].kept;
        if (kept >= 1.0 || frictionStep_[k].isZero(0.0)) continue;
        const Vec3 impulse = (1.0 - kept) * frictionStep_[k];  // the part taken back
        ParticleContact& c = contacts_[k];
        const Body& b = ctx.bodies[c.body];
        const Vec3 r = b.q * c.local1;
        c.lambdaTangent -= impulse.norm();
        c.frictionImpulse -= impulse;
        x_[c.particle] -= invMass_[c.particle] * impulse;
        if (b.invMass > 0.0) applyImpulse(ctx, c.body, 0, impulse, r.cross(impulse), Vec3::Zero());
    }
}

void SoftSystem::solveContactVelocities(Body* bodies, double h, double gravity) {
    const double restingSpeed = 2.0 * gravity * h;
    for (size_t k = 0; k < contacts_.size(); ++k) {
        const ParticleContact& c = contacts_[k];
        if (!(c.lambdaNormal > 0.0)) continue;
        Body& b = bodies[c.body];
        const Vec3& n = c.normal;
        Vec3& v = v_[c.particle];
        const double w = invMass_[c.particle];
        // A sliding patch's contact had its μ_d in the solve.
        const bool slid = patchFriction_ && c.lambdaTangent > 0.0 && k < contactPatch_.size() &&
                          patches_[contactPatch_[k]].kept < 1.0;
        if (c.still) {
            // The ground and the obstacles: below, with the body's velocities and inverse mass,
            // zero, left out (the same bits).
            const double vn = v.dot(n);
            const double vnBefore = vPrev_[c.particle].dot(n);
            const double e = std::abs(vnBefore) <= restingSpeed ? 0.0 : c.restitution;
            const double change = std::max(-e * vnBefore, 0.0) - vn;
            if (std::abs(change) > kRestingSpeed) changeVelocityOnStill(v, w, change * n);
            if (!(c.dynamicFriction > 0.0) || slid) continue;
            const Vec3 slip = v - v.dot(n) * n;
            const double slipSpeed = slip.norm();
            if (!(slipSpeed > kRestingSpeed)) continue;
            const Vec3 t = slip / slipSpeed;
            const double maxChange = c.dynamicFriction * c.lambdaNormal / h * w;
            changeVelocityOnStill(v, w, -std::min(maxChange, slipSpeed) * t);
            continue;
        }
        const Vec3 r = b.q * c.local1;
        // Eq. 34: the normal velocity becomes −e v̄_n (no bounce below 2|g|h).
        const double vn = (v - pointVelocity(b, r)).dot(n);
        const double vnBefore = (vPrev_[c.particle] - (b.vPrev + b.omegaPrev.cross(r))).dot(n);
        const double e = std::abs(vnBefore) <= restingSpeed ? 0.0 : c.restitution;
        const double change = std::max(-e * vnBefore, 0.0) - vn;
        if (std::abs(change) > kRestingSpeed) applyVelocityChange(v, w, b, r, change * n);
        if (!(c.dynamicFriction > 0.0) || slid) continue;
        // Eq. 30 (ERRATA item 2's units): slip removed by at most h μ_d |f_n| = μ_d λ_n / h.
        const Vec3 relative = v - pointVelocity(b, r);
        const Vec3 slip = relative - relative.dot(n) * n;
        const double slipSpeed = slip.norm();
        if (!(slipSpeed > kRestingSpeed)) continue;
        const Vec3 t = slip / slipSpeed;
        const double maxChange = c.dynamicFriction * c.lambdaNormal / h * (w + bodyInverseMass(b, r, t));
        applyVelocityChange(v, w, b, r, -std::min(maxChange, slipSpeed) * t);
    }
}

int SoftSystem::activeContactCount() const {
    return static_cast<int>(std::count_if(contacts_.begin(), contacts_.end(),
                                          [](const ParticleContact& c) { return c.lambdaNormal > 0.0; }));
}

Vec3 SoftSystem::contactForce(double h) const {
    Vec3 impulse = Vec3::Zero();
    for (const ParticleContact& c : contacts_) impulse += c.lambdaNormal * c.normal + c.frictionImpulse;
    return impulse / (h * h);
}

double SoftSystem::maxPenetration(std::span<const Body> bodies) const {
    double deepest = 0.0;
    for (const ParticleContact& c : contacts_) {
        const Body& b = bodies[c.body];
        const Vec3 p1 = b.pointToWorld(c.local1);
        deepest = std::max(deepest, (p1 - (x_[c.particle] - c.radius * c.normal)).dot(c.normal));
    }
    return deepest;
}

}  // namespace substep
