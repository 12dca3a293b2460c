#pragma once
/// The physics core's draw list: what a World would show a developer — joint links (a spring's
/// stretch, a rope's slack, a joint's error), joint frames and limits, joint forces and torques,
/// contact points and normals, the broadphase's boxes, centres of mass, linear and angular
/// velocities — as plain segments in world coordinates. The core knows no
/// renderer: a front end colours the segments by layer and draws them (sandbox/scene_drawing).

#include "physics/math.h"

#include <cstdint>
#include <vector>

namespace substep {

class World;

/// What a segment shows. The front end picks colours and toggles layers by it.
enum class DebugLayer : uint8_t {
    JointLink,    ///< anchor 0 to anchor 1
    JointFrame,   ///< a joint axis on one body; `part` 0, 1, 2 for the axes a, b, c
    JointLimit,   ///< a hinge's or twist's allowed arc, a slide's range, a swing cone
    JointForce,   ///< the joint's force on body 1 (λ/h², Eq. 10), an arrow
    JointTorque,  ///< the joint's torque on body 1 (Eq. 17), an arrow
    Contact,      ///< a contact point on body 1 (`part` 1: a small cross) and its normal (`part` 0: an arrow)
    // Bodies (issue 20), together:
    Bounds,           ///< the box the broadphase paired a body with (World::broadphaseBounds), 12 edges
    CentreOfMass,     ///< a dynamic body's centre of mass: three crossed lines along its principal axes
    LinearVelocity,   ///< a dynamic body's velocity v at its centre of mass, an arrow
    AngularVelocity,  ///< a dynamic body's ω: an arrow along the axis (`part` 0) and an arc turning its way (`part` 1)
};

struct DebugSegment {
    Vec3 from = Vec3::Zero();
    Vec3 to = Vec3::Zero();
    DebugLayer layer = DebugLayer::JointLink;
    uint8_t part = 0;  ///< JointFrame: which axis
};

/// Layers as bits of DebugDrawOptions::layers.
constexpr uint32_t debugLayerBit(DebugLayer layer) { return 1u << static_cast<uint32_t>(layer); }

struct DebugDrawOptions {
    uint32_t layers = ~0u;       ///< debugLayerBit of each layer to draw
    double markerLength = 0.1;   ///< frame axes, contact normals, limit arcs (m)
    double forceScale = 0.0;     ///< m of arrow per N; 0 draws no forces
    double torqueScale = 0.0;    ///< m of arrow per N m; 0 draws no torques
    double velocityScale = 0.0;         ///< m of arrow per m/s; 0 draws no linear velocities
    double angularVelocityScale = 0.0;  ///< m of arrow per rad/s; 0 draws no angular velocities
    double longestArrow = 1.0;   ///< arrows are clipped to this (m)
};

/// Segments appended by drawWorld; reuse one list across frames to keep its storage.
struct DebugDrawList {
    std::vector<DebugSegment> segments;
    void clear() { segments.clear(); }
    void line(const Vec3& from, const Vec3& to, DebugLayer layer, uint8_t part = 0) {
        segments.push_back({from, to, layer, part});
    }
    /// A line with two barbs at `to`; nothing when shorter than 1e-6 m.
    void arrow(const Vec3& from, const Vec3& to, DebugLayer layer);
};

/// Appends the world's current state as segments of the layers `options` selects.
void drawWorld(const World& world, const DebugDrawOptions& options, DebugDrawList& list);

}  // namespace substep
