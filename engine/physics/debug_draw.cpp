#include "physics/debug_draw.h"

#include "physics/world.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <tuple>

namespace substep {

namespace {

constexpr int kArcSegments = 16;
constexpr double kPi = 3.14159265358979323846;

/// The joint frame's axes a, b, c in world coordinates on one body.
Mat3 worldAxes(const Body& body, const Quat& frame) { return (body.q * frame).toRotationMatrix(); }

/// An arc of radius r about `centre` in the plane of b, c, from angle lo to hi (turning b towards
/// c, the right-hand rule about a = b x c), with spokes at both ends.
void addArc(DebugDrawList& list, const Vec3& centre, const Vec3& b, const Vec3& c, double r, double lo, double hi) {
    const auto at = [&](double angle) { return centre + r * (std::cos(angle) * b + std::sin(angle) * c); };
    const double span = std::clamp(hi - lo, 0.0, 2.0 * kPi);
    Vec3 previous = at(lo);
    for (int i = 1; i <= kArcSegments; ++i) {
        const Vec3 next = at(lo + span * i / kArcSegments);
        list.line(previous, next, DebugLayer::JointLimit);
        previous = next;
    }
    list.line(centre, at(lo), DebugLayer::JointLimit);
    list.line(centre, at(lo + span), DebugLayer::JointLimit);
}

void addLimits(DebugDrawList& list, const Joint& joint, const Body& body0, const Vec3& anchor0, double r) {
    const Mat3 axes = worldAxes(body0, joint.frame0);
    const Vec3 a = axes.col(0), b = axes.col(1), c = axes.col(2);
    switch (joint.type()) {
        case JointType::Hinge:
            if (const HingeJoint& hinge = joint.hinge(); hinge.hasLimits)
                addArc(list, anchor0, b, c, r, hinge.limits.lower, hinge.limits.upper);
            break;
        case JointType::Prismatic:
            if (const PrismaticJoint& prismatic = joint.prismatic(); prismatic.hasLimits) {
                const Vec3 lo = anchor0 + prismatic.limits.lower * a, hi = anchor0 + prismatic.limits.upper * a;
                list.line(lo, hi, DebugLayer::JointLimit);
                for (const Vec3& end : {lo, hi}) list.line(end - 0.3 * r * b, end + 0.3 * r * b, DebugLayer::JointLimit);
            }
            break;
        case JointType::Spherical: {
            const SphericalJoint& spherical = joint.spherical();
            if (spherical.hasSwingLimit) {
                // The cone axis a of body 0 may turn within: its rim and four generatrices.
                const double swing = std::clamp(spherical.swingLimit, 0.0, kPi);
                const Vec3 centre = anchor0 + r * std::cos(swing) * a;
                const double rim = r * std::sin(swing);
                Vec3 previous = centre + rim * b;
                for (int i = 1; i <= kArcSegments; ++i) {
                    const double angle = 2.0 * kPi * i / kArcSegments;
                    const Vec3 next = centre + rim * (std::cos(angle) * b + std::sin(angle) * c);
                    list.line(previous, next, DebugLayer::JointLimit);
                    if (i % (kArcSegments / 4) == 0) list.line(anchor0, next, DebugLayer::JointLimit);
                    previous = next;
                }
            }
            if (spherical.hasTwistLimits)
                addArc(list, anchor0, b, c, 0.6 * r, spherical.twistLimits.lower, spherical.twistLimits.upper);
            break;
        }
        default: break;
    }
}

/// `vector` scaled, clipped to `longest`, as an arrow from `from`.
void addScaledArrow(DebugDrawList& list, const Vec3& from, const Vec3& vector, double scale, double longest,
                    DebugLayer layer) {
    Vec3 arrow = scale * vector;
    const double length = arrow.norm();
    if (!(length > 1e-4)) return;
    if (length > longest) arrow *= longest / length;
    list.arrow(from, from + arrow, layer);
}

/// The twelve edges of `box`.
void addBox(DebugDrawList& list, const Aabb& box) {
    const auto corner = [&](int i) {
        return Vec3((i & 1) ? box.max.x() : box.min.x(), (i & 2) ? box.max.y() : box.min.y(),
                    (i & 4) ? box.max.z() : box.min.z());
    };
    // Corners i and i | bit differ along one axis: each such pair is an edge.
    for (int i = 0; i < 8; ++i)
        for (const int bit : {1, 2, 4})
            if ((i & bit) == 0) list.line(corner(i), corner(i | bit), DebugLayer::Bounds);
}

/// ω as an arrow along its axis from the centre of mass (right-hand rule), and three quarters of a
/// circle about that axis ending in a barb, so the sense of turning reads without the rule.
void addAngularVelocity(DebugDrawList& list, const Body& body, double scale, double longest, double radius) {
    const double rate = body.omega.norm();
    if (!(rate * scale > 1e-4)) return;
    Vec3 arrow = scale * body.omega;
    if (arrow.norm() > longest) arrow *= longest / arrow.norm();
    list.arrow(body.x, body.x + arrow, DebugLayer::AngularVelocity);
    const Vec3 axis = body.omega / rate;
    const Vec3 b = axis.unitOrthogonal();
    const Vec3 c = axis.cross(b);  // b turns towards c about the axis: the sense of ω
    const Vec3 centre = body.x + 0.5 * arrow;
    const auto at = [&](double angle) { return centre + radius * (std::cos(angle) * b + std::sin(angle) * c); };
    constexpr double kSpan = 1.5 * kPi;
    Vec3 previous = at(0.0);
    for (int i = 1; i <= kArcSegments; ++i) {
        const Vec3 next = at(kSpan * i / kArcSegments);
        list.line(previous, next, DebugLayer::AngularVelocity, 1);
        previous = next;
    }
    // The barb points back along the arc's tangent at its end.
    const Vec3 tangent = -std::sin(kSpan) * b + std::cos(kSpan) * c;
    const Vec3 radial = (previous - centre) / radius;
    for (const double sign : {1.0, -1.0})
        list.line(previous, previous - 0.4 * radius * tangent + sign * 0.25 * radius * radial,
                  DebugLayer::AngularVelocity, 1);
}

}  // namespace

void DebugDrawList::arrow(const Vec3& from, const Vec3& to, DebugLayer layer) {
    const Vec3 shaft = to - from;
    const double length = shaft.norm();
    if (!(length > 1e-6)) return;
    line(from, to, layer);
    // Two short barbs in a plane containing the shaft.
    const Vec3 direction = shaft / length;
    const Vec3 side = direction.unitOrthogonal();
    for (const double sign : {1.0, -1.0}) line(to, to - 0.2 * length * direction + sign * 0.08 * length * side, layer);
}

void drawWorld(const World& world, const DebugDrawOptions& options, DebugDrawList& list) {
    const auto wants = [&](DebugLayer layer) { return (options.layers & debugLayerBit(layer)) != 0; };
    const std::span<const Body> bodies = world.bodies();
    const double h = world.lastSubstep();
    const double invH2 = h > 0.0 ? 1.0 / (h * h) : 0.0;

    // Each layer in its own pass, so segments of one kind stay together in the list.
    if (wants(DebugLayer::JointLink))
        for (const Joint& joint : world.joints())
            if (joint.alive)
                list.line(bodies[joint.body0].pointToWorld(joint.anchor0), bodies[joint.body1].pointToWorld(joint.anchor1),
                          DebugLayer::JointLink);
    if (wants(DebugLayer::JointFrame)) {
        for (const Joint& joint : world.joints()) {
            if (!joint.alive) continue;
            for (const auto& [body, frame, anchor] : {std::tuple{&bodies[joint.body0], joint.frame0, joint.anchor0},
                                                      std::tuple{&bodies[joint.body1], joint.frame1, joint.anchor1}}) {
                const Mat3 axes = worldAxes(*body, frame);
                const Vec3 origin = body->pointToWorld(anchor);
                for (uint8_t axis = 0; axis < 3; ++axis)
                    list.line(origin, origin + options.markerLength * axes.col(axis), DebugLayer::JointFrame, axis);
            }
        }
    }
    if (wants(DebugLayer::JointLimit))
        for (const Joint& joint : world.joints())
            if (joint.alive)
                addLimits(list, joint, bodies[joint.body0], bodies[joint.body0].pointToWorld(joint.anchor0),
                          1.5 * options.markerLength);
    // A correction moves body 0 along the impulse, so body 1 feels its opposite.
    if (wants(DebugLayer::JointForce) && options.forceScale > 0.0 && invH2 > 0.0)
        for (const Joint& joint : world.joints())
            if (joint.alive)
                addScaledArrow(list, bodies[joint.body1].pointToWorld(joint.anchor1), -joint.linearImpulse() * invH2,
                               options.forceScale, options.longestArrow, DebugLayer::JointForce);
    if (wants(DebugLayer::JointTorque) && options.torqueScale > 0.0 && invH2 > 0.0)
        for (const Joint& joint : world.joints())
            if (joint.alive)
                addScaledArrow(list, bodies[joint.body1].pointToWorld(joint.anchor1), -joint.angularImpulse() * invH2,
                               options.torqueScale, options.longestArrow, DebugLayer::JointTorque);
    if (wants(DebugLayer::Contact)) {
        const std::span<const Contact> contacts = world.contacts();
        const double cross = 0.25 * options.markerLength;
        for (const ContactPair& pair : world.contactPairs()) {
            for (uint32_t i = pair.first; i < pair.first + pair.count && i < contacts.size(); ++i) {
                const Vec3 point = bodies[pair.body1].pointToWorld(contacts[i].local1);
                list.arrow(point, point + options.markerLength * contacts[i].normal, DebugLayer::Contact);
                // The point itself, a cross in the contact plane: visible where the normal is
                // seen end on, and at a software rasteriser's half resolution.
                const Vec3 t1 = contacts[i].normal.unitOrthogonal();
                const Vec3 t2 = contacts[i].normal.cross(t1);
                list.line(point - cross * t1, point + cross * t1, DebugLayer::Contact, 1);
                list.line(point - cross * t2, point + cross * t2, DebugLayer::Contact, 1);
            }
        }
    }
    // Bodies: boxes of whatever the broadphase saw; the rest for rigid bodies that move (soft
    // bodies' particles would bury the scene under markers).
    if (wants(DebugLayer::Bounds))
        for (uint32_t index = 0; index < bodies.size(); ++index) {
            const Aabb& box = world.broadphaseBounds(index);
            if (bodies[index].alive && bodies[index].type != BodyType::Particle && !box.isEmpty() &&
                box.min.allFinite() && box.max.allFinite())
                addBox(list, box);
        }
    const auto movingRigid = [](const Body& body) { return body.alive && body.type == BodyType::Dynamic && body.isDynamic(); };
    if (wants(DebugLayer::CentreOfMass))
        for (const Body& body : bodies)
            if (movingRigid(body))
                for (uint8_t axis = 0; axis < 3; ++axis) {
                    const Vec3 half = 0.5 * options.markerLength * body.toWorld(Vec3::Unit(axis));
                    list.line(body.x - half, body.x + half, DebugLayer::CentreOfMass, axis);
                }
    if (wants(DebugLayer::LinearVelocity) && options.velocityScale > 0.0)
        for (const Body& body : bodies)
            if (movingRigid(body))
                addScaledArrow(list, body.x, body.v, options.velocityScale, options.longestArrow,
                               DebugLayer::LinearVelocity);
    if (wants(DebugLayer::AngularVelocity) && options.angularVelocityScale > 0.0)
        for (const Body& body : bodies)
            if (movingRigid(body))
                addAngularVelocity(list, body, options.angularVelocityScale, options.longestArrow,
                                   0.5 * options.markerLength);
}

}  // namespace substep
