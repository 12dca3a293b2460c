// Fig. 17: a robot arm whose gripper follows a box while every joint keeps to its limits
// (paper section 5: "Unreachable positions yield overconstrained problems which our method
// handles gracefully by moving the gripper as close as possible to the target pose").
//
// No inverse kinematics is computed anywhere: the gripper is tied to the target box by a
// spherical joint (attachment, plus a zero swing limit that points the gripper along the box's
// down axis), and the arm's hinges with their limits (Algorithm 3) settle the rest, substep by
// substep. The target is a static body the script (or the viewer's drag) moves between frames.
// Gravity 10, 20 substeps x 1 iteration (Table 1: 0.4 ms per frame).
//
// Links: pedestal (static) -yaw- turret -shoulder- upper arm -elbow- forearm -wrist- hand, with
// two fingers welded on. All pitch hinges turn about the links' z axis.
//
// The pull on the gripper is bounded (the paper's own device under Eq. 25: a compliance
// α = d/f applies the force f at distance d). With one Gauss-Seidel pass per substep, a hard
// pull toward a target out of reach moves the hand the whole gap every substep before the
// arm's joints pull it back, and leaves the joints stretched by a part of that gap; a pull of
// at most F_max moves it by about F_max h²/m instead. Close to the target the compliance is
// the tiny α_min, so a reachable target is met to a fraction of a millimetre.

#include "scenes/scenes.h"

#include "ecs/components.h"
#include "ecs/joint_pose.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>

namespace substep::scenes {
namespace {

// Geometry (m): the shoulder pivot sits on the yaw axis, so it never moves.
constexpr double kPedestalHeight = 0.1;
constexpr double kTurretHeight = 0.15;
constexpr double kUpperArm = 0.5;
constexpr double kForearm = 0.45;
constexpr double kHand = 0.1;
constexpr double kFinger = 0.08;
/// Gripper point (between the fingertips' roots and tips) from the wrist pivot, along the hand.
constexpr double kGripperReach = 0.16;
const Vec3 kShoulder(0.0, kPedestalHeight + kTurretHeight, 0.0);

/// The arm's hinges: name, limits (rad) and the pose the arm is built in.
struct ArmJoint {
    const char* name;
    Range limits;
    double initial;
};
constexpr std::array<ArmJoint, 4> kArmJoints{{
    {"yaw", {-2.6, 2.6}, 0.5},
    {"shoulder", {-1.3, 0.8}, -0.6},
    {"elbow", {-2.5, 0.2}, -1.3},
    {"wrist", {-1.7, 1.7}, -(M_PI - 1.9)},  // the gripper points straight down
}};

/// Bounded pull: the compliance never goes below this (m/N) ...
constexpr double kMinCompliance = 1e-7;
/// ... and the attachment pulls with at most this force (N), the swing with this torque (N m).
constexpr double kMaxPull = 100.0;
constexpr double kMaxTwistingPull = 5.0;
/// Damping of the arm's hinges (Eq. 32, 1/s): without it a stretched arm swings about the line
/// to an unreachable target for ever.
constexpr double kJointDamping = 10.0;
/// Speed at which the box follows its sliders (m/s).
constexpr double kGlideSpeed = 1.0;

/// World poses of the links for the given joint angles (forward kinematics): each pitch hinge
/// turns about the turret's z axis.
struct ArmPose {
    Quat turret, upper, fore, hand;
    Vec3 elbow, wrist;
};
ArmPose forwardKinematics(double yaw, double shoulder, double elbow, double wrist) {
    ArmPose pose;
    pose.turret = Quat(Eigen::AngleAxisd(yaw, Vec3::UnitY()));
    pose.upper = pose.turret * Quat(Eigen::AngleAxisd(shoulder, Vec3::UnitZ()));
    pose.fore = pose.upper * Quat(Eigen::AngleAxisd(elbow, Vec3::UnitZ()));
    pose.hand = pose.fore * Quat(Eigen::AngleAxisd(wrist, Vec3::UnitZ()));
    pose.elbow = kShoulder + pose.upper * Vec3(0.0, kUpperArm, 0.0);
    pose.wrist = pose.elbow + pose.fore * Vec3(0.0, kForearm, 0.0);
    return pose;
}

void addLink(SceneDescription& scene, const char* name, const Vec3& size, double mass, const Vec3& base,
             const Quat& orientation) {
    addBox(scene, name, size, mass, base + orientation * Vec3(0.0, 0.5 * size.y(), 0.0), orientation);
}

JointDef pitchHinge(const ArmJoint& joint, double parentLength, double childLength) {
    return {.type = JointType::Hinge,
            .anchor0 = Vec3(0.0, 0.5 * parentLength, 0.0),
            .anchor1 = Vec3(0.0, -0.5 * childLength, 0.0),
            .axis0 = Vec3::UnitZ(),
            .axis1 = Vec3::UnitZ(),
            .limits = joint.limits,
            .angularDamping = kJointDamping};
}

SceneDescription build() {
    SceneDescription scene{.name = "robot_arm", .gravity = kPaperGravity, .substeps = 20, .iterations = 1};
    addGroundPlane(scene, 0.5);
    addStaticBox(scene, "pedestal", Vec3(0.3, kPedestalHeight, 0.3), Vec3(0.0, 0.5 * kPedestalHeight, 0.0));

    // Built at rest in its initial pose, with the target box where the gripper already is.
    const ArmPose pose = forwardKinematics(kArmJoints[0].initial, kArmJoints[1].initial, kArmJoints[2].initial,
                                           kArmJoints[3].initial);
    addLink(scene, "turret", Vec3(0.22, kTurretHeight, 0.22), 2.0, Vec3(0.0, kPedestalHeight, 0.0), pose.turret);
    addLink(scene, "upper_arm", Vec3(0.08, kUpperArm, 0.08), 1.0, kShoulder, pose.upper);
    addLink(scene, "forearm", Vec3(0.07, kForearm, 0.07), 0.8, pose.elbow, pose.fore);
    addLink(scene, "hand", Vec3(0.1, kHand, 0.08), 0.3, pose.wrist, pose.hand);
    for (const double side : {-1.0, 1.0}) {
        const std::string name = side < 0.0 ? "finger_left" : "finger_right";
        const Vec3 root = pose.wrist + pose.hand * Vec3(0.035 * side, kHand, 0.0);
        addLink(scene, name.c_str(), Vec3(0.02, kFinger, 0.06), 0.05, root, pose.hand);
        addJoint(scene, name + "_weld", "hand", name,
                 {.type = JointType::Fixed,
                  .anchor0 = Vec3(0.035 * side, 0.5 * kHand, 0.0),
                  .anchor1 = Vec3(0.0, -0.5 * kFinger, 0.0)});
    }
    const Vec3 gripper = pose.wrist + pose.hand * Vec3(0.0, kGripperReach, 0.0);
    scene.bodies.push_back({"target", BodyDef{.shape = boxShape(Vec3(0.08, 0.08, 0.08)),
                                              .type = BodyType::Static,
                                              .position = gripper,
                                              .collide = false}});

    // The gripper point on the hand to the box's centre; the hand's +y (out through the fingers)
    // held along the box's −y by a zero swing limit. Created (so solved) before the arm's hinges:
    // each substep then ends with the hinges' limits met and what the arm cannot give left in
    // this soft joint (solved last, its pull turned the light hand 0.05 rad past the wrist limit).
    addJoint(scene, "grip", "target", "hand",
             {.type = JointType::Spherical,
              .anchor1 = Vec3(0.0, kGripperReach - 0.5 * kHand, 0.0),
              .axis0 = -Vec3::UnitY(),
              .axis1 = Vec3::UnitY(),
              .compliance = kMinCompliance,
              .limitCompliance = kMinCompliance,
              .swingLimit = 0.0});

    addJoint(scene, "yaw", "pedestal", "turret",
             {.type = JointType::Hinge,
              .anchor0 = Vec3(0.0, 0.5 * kPedestalHeight, 0.0),
              .anchor1 = Vec3(0.0, -0.5 * kTurretHeight, 0.0),
              .axis0 = Vec3::UnitY(),
              .axis1 = Vec3::UnitY(),
              .limits = kArmJoints[0].limits,
              .angularDamping = kJointDamping});
    addJoint(scene, "shoulder", "turret", "upper_arm", pitchHinge(kArmJoints[1], kTurretHeight, kUpperArm));
    addJoint(scene, "elbow", "upper_arm", "forearm", pitchHinge(kArmJoints[2], kUpperArm, kForearm));
    addJoint(scene, "wrist", "forearm", "hand", pitchHinge(kArmJoints[3], kForearm, kHand));
    scene.camera = SceneCamera{.position = Vec3(1.1, 1.3, 2.0), .target = Vec3(0.1, 0.5, 0.0), .fov = 0.8};
    return scene;
}

class RobotArmScript : public SceneScript {
  public:
    std::unique_ptr<SceneScript> clone() const override { return std::make_unique<RobotArmScript>(*this); }
    RobotArmScript() {
        orbit_ = addKnob({.name = "orbit", .label = "move the target on a path", .kind = SceneKnob::Kind::Toggle,
                          .value = 1.0});
        x_ = addKnob({.name = "target_x", .label = "target x (m)", .value = 0.0, .min = -1.6, .max = 1.6, .format = "%.2f"});
        y_ = addKnob({.name = "target_y", .label = "target y (m)", .value = 0.0, .min = -0.2, .max = 1.8, .format = "%.2f"});
        z_ = addKnob({.name = "target_z", .label = "target z (m)", .value = 0.0, .min = -1.6, .max = 1.6, .format = "%.2f"});
        orient_ = addKnob({.name = "hold_orientation", .label = "gripper points along the box",
                           .kind = SceneKnob::Kind::Toggle, .value = 1.0});
        // The sliders start where the scene puts the box.
        const Vec3 start = initialTarget();
        knobValue(x_) = start.x();
        knobValue(y_) = start.y();
        knobValue(z_) = start.z();
    }

    void start(SceneInstance& scene) override {
        target_ = scene.bodyNamed("target");
        hand_ = scene.bodyNamed("hand");
        grip_ = scene.jointNamed("grip");
        for (std::size_t i = 0; i < kArmJoints.size(); ++i) joints_[i] = scene.jointNamed(kArmJoints[i].name);
        gripSwingLimit_ = scene.registry.get<ecs::Joint>(grip_).def.swingLimit.value_or(0.0);
        holdOrientation(scene.registry);
        placeTarget(scene.registry, toggled(orbit_) ? orbitPoint(0.0) : knobTarget());
        gliding_ = false;
        boundPull(scene);
    }

    void beforeFrame(SceneInstance& scene, double time, double dt) override {
        if (toggled(orbit_)) {
            placeTarget(scene.registry, orbitPoint(time));
        } else if (gliding_) {
            // The box glides to the sliders' point rather than jumping there: a jump of a metre
            // would pull the arm through its limits at full force in one frame.
            const Vec3 from = targetPosition(scene.registry);
            const Vec3 to = knobTarget();
            const double step = kGlideSpeed * dt;
            const double distance = (to - from).norm();
            gliding_ = distance > step;
            placeTarget(scene.registry, gliding_ ? Vec3(from + (to - from) * (step / distance)) : to);
        }
        if (!gliding_) followTarget(scene.registry);
        boundPull(scene);
    }

    void knobChanged(SceneInstance& scene, std::size_t index) override {
        if (index == orient_) holdOrientation(scene.registry);
        if (index == x_ || index == y_ || index == z_) {
            // Moving a slider takes the box off its path.
            knobValue(orbit_) = 0.0;
            gliding_ = true;
        }
    }

    void readouts(const SceneInstance& scene, std::vector<SceneReadout>& out) const override {
        const ecs::Registry& registry = scene.registry;
        const ecs::JointPose grip = ecs::jointPose(registry, registry.get<ecs::Joint>(grip_));
        out.push_back({"gripper to target [mm]", 1000.0 * (grip.anchor1 - grip.anchor0).norm(), "%.2f"});
        for (std::size_t i = 0; i < kArmJoints.size(); ++i) {
            const ArmJoint& joint = kArmJoints[i];
            char label[80];
            std::snprintf(label, sizeof label, "%s [deg] (limits %.0f .. %.0f)", joint.name,
                          joint.limits.lower * 180.0 / M_PI, joint.limits.upper * 180.0 / M_PI);
            const double angle = ecs::hingeAngle(ecs::jointPose(registry, registry.get<ecs::Joint>(joints_[i])));
            out.push_back({label, angle * 180.0 / M_PI, "%.1f"});
        }
    }

    /// Where the scene builds the box (the gripper of the initial pose).
    static Vec3 initialTarget() {
        const ArmPose pose = forwardKinematics(kArmJoints[0].initial, kArmJoints[1].initial, kArmJoints[2].initial,
                                               kArmJoints[3].initial);
        return pose.wrist + pose.hand * Vec3(0.0, kGripperReach, 0.0);
    }

  private:
    double& knobValue(std::size_t index) { return knobs()[index].value; }
    Vec3 knobTarget() const { return Vec3(knob(x_), knob(y_), knob(z_)); }

    /// A path round the robot that leaves its reach (and its yaw range) and comes back: radius
    /// 0.45-1.45 m about the base, height 0.15-0.95 m, starting at the built target.
    static Vec3 orbitPoint(double time) {
        const Vec3 start = initialTarget();
        const double startRadius = std::hypot(start.x(), start.z());
        const double startAngle = std::atan2(-start.z(), start.x());
        const double radius = startRadius + 0.5 * std::sin(0.45 * time);
        const double angle = startAngle + 0.35 * time;
        const double height = start.y() + 0.4 * std::sin(0.8 * time);
        return Vec3(radius * std::cos(angle), height, -radius * std::sin(angle));
    }

    /// The target sliders show where the box is (moved by its orbit or dragged in the window),
    /// clamped to their ranges, so they never stand stale; while it glides they keep the point
    /// it glides to.
    void followTarget(const ecs::Registry& registry) {
        const Vec3 at = targetPosition(registry);
        for (const auto& [index, value] : {std::pair{x_, at.x()}, std::pair{y_, at.y()}, std::pair{z_, at.z()}}) {
            const SceneKnob& slider = knobs()[index];
            knobValue(index) = std::clamp(value, slider.min, slider.max);
        }
    }

    Vec3 targetPosition(const ecs::Registry& registry) const {
        return registry.get<ecs::Transform>(target_).position;
    }

    /// The swing limit that keeps the gripper along the box, on or off by the knob.
    void holdOrientation(ecs::Registry& registry) const {
        registry.patch<ecs::Joint>(grip_, [&](ecs::Joint& grip) {
            grip.def.swingLimit = toggled(orient_) ? std::optional(gripSwingLimit_) : std::nullopt;
        });
    }

    /// Moves the static box; the physics system carries it there without velocity.
    void placeTarget(ecs::Registry& registry, const Vec3& position) const {
        registry.patch<ecs::Transform>(target_, [&](ecs::Transform& box) { box.position = position; });
    }

    /// α = max(α_min, gap / F_max) for the attachment, likewise for the swing limit: a pull of at
    /// most F_max (see the top of this file). The gap and the swing are the grip's readout, on
    /// the target where it has just been put: the physics system applies the move first.
    void boundPull(SceneInstance& scene) const {
        ecs::PhysicsSystem physics = scene.physics();
        physics.sync();
        physics.writeBack();
        scene.registry.patch<ecs::Joint>(grip_, [&](ecs::Joint& grip) {
            grip.def.compliance = std::max(kMinCompliance, grip.readout.error / kMaxPull);
            grip.def.limitCompliance = std::max(kMinCompliance, grip.readout.coordinate / kMaxTwistingPull);
        });
    }

    std::size_t orbit_, x_, y_, z_, orient_;
    bool gliding_ = false;
    ecs::Entity target_, hand_;
    ecs::Entity grip_;
    std::array<ecs::Entity, kArmJoints.size()> joints_;
    double gripSwingLimit_ = 0.0;  ///< the scene's swing limit of the grip (rad)
};

}  // namespace

SceneEntry robotArmEntry() {
    return {.name = "robot_arm",
            .description = "Fig. 17: a robot arm with joint limits whose gripper follows a box",
            .build = build,
            .paperMsPerFrame = 0.4,
            .makeScript = []() -> std::unique_ptr<SceneScript> { return std::make_unique<RobotArmScript>(); }};
}

}  // namespace substep::scenes
