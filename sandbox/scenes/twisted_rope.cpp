// Twisted rope (paper Fig. 18, section 5): "a simple chain of 100 capsules connected by spherical
// joints" whose swing and twist limits, each with its own compliance, make it a rope that
// resists bending and twisting separately. The rope hangs between two supports; one end is
// turned about the rope's axis, the other is held against turning on a slider pulled outwards
// with the rope's own horizontal tension, so that the rope starts at rest. Once the twisting
// moment exceeds Greenhill's threshold 2√(B T) (B bending stiffness, T tension; lowest tension
// is at the bottom of the sag) the rope coils up: twist turns into writhe, loops form and wrap
// round one another, and the held end is drawn in. The coils cannot pass through themselves:
// the capsules collide with every link but their jointed neighbours.
//
// A swing limit of 0 with a compliance is a bending spring (torque = angle / compliance), a
// twist limit [-t, t] with a compliance a torsion spring beyond ±t: together a discrete elastic
// rod with B = pitch / α_swing and C = pitch / α_twist, each joint's two parts solved by
// Algorithm 3 (paper 3.4.1, Eqs. 22-24).

#include "scenes/scenes.h"

#include "ecs/components.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

namespace substep::scenes {
namespace {

constexpr int kLinks = 100;
constexpr double kRadius = 0.04;                   // capsule radius (m)
constexpr double kSegment = 0.04;                  // capsule segment between cap centres (m)
constexpr double kPitch = kSegment + 2 * kRadius;  // tip to tip: joint to joint (m)
constexpr double kLength = kLinks * kPitch;        // 12 m
/// A capsule of water-like density (1000 kg/m³): 0.469 kg a link, a 47 kg rope.
constexpr double kLinkMass =
    1000.0 * (M_PI * kRadius * kRadius * kSegment + 4.0 / 3.0 * M_PI * kRadius * kRadius * kRadius);
constexpr double kGravity = 10.0;  // kPaperGravity
constexpr double kHeight = 7.0;    // the supports' height (m)
/// Catenary parameter a = T/w of the rope as built: its horizontal tension over its weight per
/// metre. With a = 2.5 m the 12 m rope spans 8.05 m and sags 4 m.
constexpr double kCatenary = 2.5;  // m
/// The rope's tension at the bottom of its sag, T = a w (97.7 N): the held end's pull.
constexpr double kTension = kCatenary * kLinkMass * kGravity / kPitch;
/// The pulled end's slider drives towards an offset this far out, so its spring force
/// (reach − offset)/compliance stays within a few % of the pull wherever the end is.
constexpr double kPullReach = 200.0;  // m
/// The nearest the held end may come to the turned one, and how far beyond where it starts it
/// may slide out (m).
constexpr double kMinimumSpan = 1.0;
constexpr double kMaximumOut = 0.5;

/// The span S between the supports of a catenary of parameter kCatenary and length kLength:
/// kLength = 2 a sinh(S / 2a), solved by bisection.
double span() {
    double lo = 0.0, hi = kLength;
    for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        (2.0 * kCatenary * std::sinh(mid / (2.0 * kCatenary)) < kLength ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

/// The point at arc length s along the hanging rope (s = 0 at the turned end, on the left).
Vec3 ropePoint(double s) {
    const double a = kCatenary;
    const double x = a * std::asinh((s - kLength / 2) / a);
    return Vec3(x, kHeight + a * (std::cosh(x / a) - std::cosh(span() / (2 * a))), 0.0);
}

/// The rope's unit tangent at arc length s.
Vec3 ropeTangent(double s) {
    const double slope = (s - kLength / 2) / kCatenary;  // dy/dx = sinh(x/a)
    return Vec3(1.0, slope, 0.0).normalized();
}

SceneDescription buildTwistedRope() {
    // Table 1: rope, 20 substeps x 1 iteration.
    SceneDescription scene{.name = "twisted_rope", .gravity = kPaperGravity, .substeps = 20, .iterations = 1};
    // The links lie along the hanging curve, their capsule axis (local y) on its tangent and
    // their local z on world z, square to the curve's plane: every joint starts untwisted.
    for (int i = 0; i < kLinks; ++i) {
        const double s = kPitch * (i + 0.5);
        scene.bodies.push_back(
            {"link" + std::to_string(i + 1),
             BodyDef{.shape = capsuleShape(kRadius, kSegment),
                     .mass = kLinkMass,
                     .position = ropePoint(s),
                     .orientation = Quat::FromTwoVectors(Vec3::UnitY(), ropeTangent(s)),
                     .staticFriction = 0.6,
                     .dynamicFriction = 0.4}});
    }
    const Vec3 tip(0.0, kPitch / 2, 0.0);
    // The turned end: a hinge about the rope's end tangent whose motor the script runs.
    addJoint(scene, "drive", "", "link1",
             {.type = JointType::Hinge,
              .anchor0 = ropePoint(0.0),
              .anchor1 = -tip,
              .axis0 = ropeTangent(0.0),
              .axis1 = Vec3::UnitY(),
              .normal0 = Vec3::UnitZ(),
              .normal1 = Vec3::UnitZ(),
              .targetVelocity = 0.0});
    // The rope: ball joints tip to tip, axis along the capsules, normal local z on both sides.
    // Limits and compliances come from the knobs (script start()).
    for (int i = 0; i + 1 < kLinks; ++i) {
        addJoint(scene, "joint" + std::to_string(i + 1), "link" + std::to_string(i + 1),
                 "link" + std::to_string(i + 2),
                 {.type = JointType::Spherical,
                  .anchor0 = tip,
                  .anchor1 = -tip,
                  .normal0 = Vec3::UnitZ(),
                  .normal1 = Vec3::UnitZ(),
                  .swingLimit = 0.0,
                  .twistLimits = Range{0.0, 0.0},
                  .angularDamping = 1.0});
    }
    // The held end: slides horizontally (orientation locked: it cannot turn), pulled outwards;
    // it may slide in to kMinimumSpan.
    const Quat heldOrientation = Quat::FromTwoVectors(Vec3::UnitY(), ropeTangent(kLength - kPitch / 2));
    addJoint(scene, "hold", "", "link" + std::to_string(kLinks),
             {.type = JointType::Prismatic,
              .anchor0 = ropePoint(kLength),
              .anchor1 = tip,
              .axis0 = Vec3::UnitX(),
              .axis1 = heldOrientation.conjugate() * Vec3::UnitX(),
              .normal0 = Vec3::UnitZ(),
              .normal1 = Vec3::UnitZ(),
              .limits = Range{-(span() - kMinimumSpan), kMaximumOut},
              .targetOffset = kPullReach,
              .driveCompliance = kPullReach / kTension,
              .linearDamping = 10.0});
    scene.bodies.push_back({"turner", BodyDef{.shape = boxShape(Vec3(0.1, 0.6, 0.6)),
                                              .type = BodyType::Static,
                                              .position = ropePoint(0.0) - Vec3(0.06, 0.0, 0.0),
                                              .collide = false}});
    const double railLength = span() - kMinimumSpan + kMaximumOut;
    scene.bodies.push_back({"rail", BodyDef{.shape = boxShape(Vec3(railLength, 0.04, 0.04)),
                                            .type = BodyType::Static,
                                            .position = Vec3(ropePoint(kLength).x() + kMaximumOut - railLength / 2,
                                                             kHeight + 0.1, 0.0),
                                            .collide = false}});
    addGroundPlane(scene, 0.5);
    scene.camera = SceneCamera{.position = Vec3(3.0, 5.5, 10.0), .target = Vec3(0.0, 4.4, 0.0)};
    return scene;
}

class TwistedRopeScript final : public SceneScript {
  public:
    std::unique_ptr<SceneScript> clone() const override { return std::make_unique<TwistedRopeScript>(*this); }
    TwistedRopeScript() {
        turnRate_ = addKnob({.name = "turn_rate", .label = "turn rate (turns/s)", .value = 0.5,
                             .min = -2.0, .max = 2.0, .format = "%.2f"});
        turns_ = addKnob({.name = "turns", .label = "turns to apply", .value = 8.0, .min = 0.0,
                          .max = 30.0, .format = "%.1f"});
        twistLimit_ = addKnob({.name = "twist_limit", .label = "twist limit (deg)", .value = 0.0,
                               .min = 0.0, .max = 45.0, .format = "%.1f"});
        twistCompliance_ = addKnob({.name = "twist_compliance", .label = "twist compliance (rad/Nm)",
                                    .value = 0.01, .min = 0.0, .max = 1.0, .format = "%.2g",
                                    .logarithmic = true});
        swingLimit_ = addKnob({.name = "swing_limit", .label = "swing limit (deg)", .value = 0.0,
                               .min = 0.0, .max = 90.0, .format = "%.1f"});
        swingCompliance_ = addKnob({.name = "swing_compliance", .label = "swing compliance (rad/Nm)",
                                    .value = 0.1, .min = 0.0, .max = 1.0, .format = "%.2g",
                                    .logarithmic = true});
        pull_ = addKnob({.name = "pull", .label = "pull on the held end (N)", .value = kTension,
                         .min = 0.0, .max = 1000.0, .format = "%.0f"});
    }

    void start(SceneInstance& scene) override {
        turnsApplied_ = 0.0;
        drive_ = hold_ = {};
        joints_.clear();
        for (const ecs::Entity joint : scene.jointEntities) {
            const ecs::Name* name = scene.registry.tryGet<ecs::Name>(joint);
            if (name == nullptr) continue;
            if (name->value == "drive") drive_ = joint;
            else if (name->value == "hold") hold_ = joint;
            else if (name->value.rfind("joint", 0) == 0) joints_.push_back(joint);
        }
        end_ = scene.bodyNamed("link" + std::to_string(kLinks));
        applyRope(scene.registry);
    }

    void beforeFrame(SceneInstance& scene, double /*time*/, double dt) override {
        if (!scene.registry.isValid(drive_) || dt <= 0.0) return;
        // Turn at the knob's rate until the knob's number of turns is applied, the last frame's
        // share clipped so that the total is exact; the hinge motor spreads it over the substeps.
        const double rate = knob(turnRate_);
        const double remaining = std::max(0.0, knob(turns_) - std::abs(turnsApplied_));
        const double step = std::copysign(std::min(std::abs(rate) * dt, remaining), rate);
        scene.registry.patch<ecs::Joint>(
            drive_, [&](ecs::Joint& drive) { drive.def.targetVelocity = 2.0 * M_PI * step / dt; });
        turnsApplied_ += step;
    }

    void knobChanged(SceneInstance& scene, std::size_t index) override {
        if (index != turnRate_ && index != turns_) applyRope(scene.registry);
    }

    void readouts(const SceneInstance& scene, std::vector<SceneReadout>& out) const override {
        out.push_back({.label = "turns applied", .value = turnsApplied_, .format = "%.2f"});
        const ecs::Registry& registry = scene.registry;
        if (!registry.isValid(end_) || !registry.isValid(drive_)) return;
        const ecs::Transform& end = registry.get<ecs::Transform>(end_);
        const Vec3 tip = end.position + end.rotation * Vec3(0.0, kPitch / 2, 0.0);
        out.push_back({.label = "end-to-end distance (m)", .value = (tip - ropePoint(0.0)).norm(), .format = "%.3f"});
        out.push_back({.label = "twisting moment (N m)", .value = registry.get<ecs::Joint>(drive_).readout.torque,
                       .format = "%.1f"});
        // Greenhill: a straight rod under tension T buckles under a moment 2√(B T).
        const double swingCompliance = knob(swingCompliance_);
        const double threshold =
            swingCompliance > 0.0 ? 2.0 * std::sqrt(kPitch / swingCompliance * knob(pull_)) : 0.0;
        out.push_back({.label = "Greenhill moment 2√(B T) (N m)", .value = threshold, .format = "%.1f"});
        int touching = 0;  // link-link pairs in contact: the coils wrapping round one another
        // Contacts are a measure of the whole world, read (never changed) from it.
        const auto bodies = scene.world().bodies();
        for (const ContactPair& pair : scene.world().contactPairs())
            if (pair.count > 0 && bodies[pair.body0].isDynamic() && bodies[pair.body1].isDynamic()) ++touching;
        out.push_back({.label = "links touching", .value = static_cast<double>(touching), .format = "%.0f"});
    }

  private:
    /// Puts the knobs' limits and compliances into the rope's joints and the pull into the hold.
    void applyRope(ecs::Registry& registry) const {
        const double twist = knob(twistLimit_) * M_PI / 180.0;
        for (const ecs::Entity entity : joints_) {
            registry.patch<ecs::Joint>(entity, [&](ecs::Joint& joint) {
                joint.def.swingLimit = knob(swingLimit_) * M_PI / 180.0;
                joint.def.limitCompliance = knob(swingCompliance_);
                joint.def.twistLimits = Range{-twist, twist};
                joint.def.twistCompliance = knob(twistCompliance_);
            });
        }
        if (registry.isValid(hold_)) {
            // A spring towards kPullReach: force ≈ reach / compliance = the pull.
            registry.patch<ecs::Joint>(hold_, [&](ecs::Joint& hold) {
                const double pull = knob(pull_);
                hold.def.targetOffset = pull > 0.0 ? std::optional(kPullReach) : std::nullopt;
                hold.def.driveCompliance = pull > 0.0 ? kPullReach / pull : 0.0;
            });
        }
    }

    std::size_t turnRate_ = 0, turns_ = 0, twistLimit_ = 0, twistCompliance_ = 0;
    std::size_t swingLimit_ = 0, swingCompliance_ = 0, pull_ = 0;
    ecs::Entity drive_, hold_;
    ecs::Entity end_;
    std::vector<ecs::Entity> joints_;
    double turnsApplied_ = 0.0;  ///< signed
};

}  // namespace

SceneEntry twistedRopeEntry() {
    return {.name = "twisted_rope",
            .description = "Fig. 18: 100 capsules on ball joints with swing and twist limits, one end turned until it coils",
            .build = buildTwistedRope,
            .paperMsPerFrame = 3.5,
            .makeScript = []() -> std::unique_ptr<SceneScript> { return std::make_unique<TwistedRopeScript>(); }};
}

}  // namespace substep::scenes
