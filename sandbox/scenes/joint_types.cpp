// Fig. 7: prismatic, hinge and spherical joints side by side, each kind with a hard and a soft
// limit so the difference shows, plus a prismatic drive to a target offset and a hinge drive to a
// target angle (paper 3.4.1-3.4.2). Gravity 10, 20 substeps x 1 iteration (Table 1 style); the
// links are joint demos and do not collide.
//
// Everything hangs from static mounts and gravity loads every limit, so each example rests where
// its constraint puts it: a hard limit at its bound, a soft one beyond it by α·load (the
// compliance α is the inverse stiffness, paper 3.3.1), a drive at its target plus α·load.
// Joint damping (Eqs. 31-32) lets the soft ones come to rest.

#include "scenes/scenes.h"

#include "ecs/components.h"
#include "ecs/joint_pose.h"


#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>

namespace substep::scenes {
namespace {

constexpr double kMountHeight = 1.6;  ///< pivots and rail tops (m)
constexpr double kBarLength = 0.4;    ///< hinge bars and spherical plates (m)
constexpr double kLinkMass = 1.0;     ///< every moving body (kg)
constexpr double kRailTop = 1.7;      ///< prismatic rails end here (m)
constexpr double kRailLength = 0.9;
constexpr double kPrismaticUpper = -0.1;  ///< offsets below the rail top are negative (m)
/// Default joint damping (1/s). Eq. 32 damps the bar's spin about its centre, a quarter of a
/// pivoting bar's energy, so the swing itself dies about four times slower than this rate.
constexpr double kDamping = 3.0;

// Column x of each example, left to right.
constexpr double kPrismaticHardX = -2.0;
constexpr double kPrismaticSoftX = -1.6;
constexpr double kPrismaticDriveX = -1.2;
constexpr double kHingeHardX = -0.8;
constexpr double kHingeSoftX = -0.2;
constexpr double kHingeDriveX = 0.4;
constexpr double kBallHardX = 1.1;
constexpr double kBallSoftX = 1.8;

/// A vertical rail with a carriage sliding on it along y (prismatic axis +y: the offset is the
/// carriage's height relative to the rail top).
void addRailCarriage(SceneDescription& scene, const std::string& name, double x, const JointDef& base) {
    addStaticBox(scene, name + "_rail", Vec3(0.03, kRailLength, 0.03),
                 Vec3(x, kRailTop - 0.5 * kRailLength, 0.0));
    addBox(scene, name, Vec3(0.14, 0.1, 0.14), kLinkMass, Vec3(x, kRailTop - 0.2, 0.0));
    JointDef def = base;
    def.type = JointType::Prismatic;
    def.anchor0 = Vec3(0.0, 0.5 * kRailLength, 0.0);
    def.axis0 = def.axis1 = Vec3::UnitY();
    def.linearDamping = def.angularDamping = kDamping;
    addJoint(scene, name + "_joint", name + "_rail", name, def);
}

/// A bar hinged at its left end to a mount, about z, starting level (angle 0).
void addHingedBar(SceneDescription& scene, const std::string& name, double x, const JointDef& base) {
    addStaticBox(scene, name + "_mount", Vec3(0.06, 0.12, 0.1), Vec3(x - 0.03, kMountHeight, 0.0));
    addBox(scene, name, Vec3(kBarLength, 0.04, 0.04), kLinkMass,
           Vec3(x + 0.5 * kBarLength, kMountHeight, 0.0));
    JointDef def = base;
    def.type = JointType::Hinge;
    def.anchor0 = Vec3(0.03, 0.0, 0.0);
    def.anchor1 = Vec3(-0.5 * kBarLength, 0.0, 0.0);
    def.axis0 = def.axis1 = Vec3::UnitZ();
    def.linearDamping = def.angularDamping = kDamping;
    addJoint(scene, name + "_joint", name + "_mount", name, def);
}

/// A plate on a ball joint at one corner of its near edge, joint axis along the plate's length
/// (+x, level): its weight loads the swing (about z) and, being off the axis by half its width,
/// the twist (about x) too.
void addBallPlate(SceneDescription& scene, const std::string& name, double x, const JointDef& base) {
    const double width = 0.2;
    addStaticBox(scene, name + "_mount", Vec3(0.06, 0.06, 0.06), Vec3(x - 0.03, kMountHeight, 0.0));
    addBox(scene, name, Vec3(kBarLength, 0.02, width), kLinkMass,
           Vec3(x + 0.5 * kBarLength, kMountHeight, 0.5 * width));
    JointDef def = base;
    def.type = JointType::Spherical;
    def.anchor0 = Vec3(0.03, 0.0, 0.0);
    def.anchor1 = Vec3(-0.5 * kBarLength, 0.0, -0.5 * width);
    def.axis0 = def.axis1 = Vec3::UnitX();
    def.normal0 = def.normal1 = Vec3::UnitZ();
    def.linearDamping = def.angularDamping = kDamping;
    addJoint(scene, name + "_joint", name + "_mount", name, def);
}

SceneDescription build() {
    SceneDescription scene{.name = "joint_types", .gravity = kPaperGravity, .substeps = 20, .iterations = 1};
    // Limits and drives here are the scene's defaults; the script puts its knobs' values in.
    const Range prismaticLimits{-0.5, kPrismaticUpper};
    addRailCarriage(scene, "prismatic_hard", kPrismaticHardX, {.limits = prismaticLimits});
    addRailCarriage(scene, "prismatic_soft", kPrismaticSoftX,
                    {.limits = prismaticLimits, .limitCompliance = 0.01});
    addRailCarriage(scene, "prismatic_drive", kPrismaticDriveX, {.targetOffset = -0.3});

    const Range hingeLimits{-0.5, 0.5};
    addHingedBar(scene, "hinge_hard", kHingeHardX, {.limits = hingeLimits});
    addHingedBar(scene, "hinge_soft", kHingeSoftX, {.limits = hingeLimits, .limitCompliance = 0.1});
    addHingedBar(scene, "hinge_drive", kHingeDriveX, {.targetAngle = 0.6});

    addBallPlate(scene, "ball_hard", kBallHardX, {.swingLimit = 0.6, .twistLimits = Range{-0.4, 0.4}});
    addBallPlate(scene, "ball_soft", kBallSoftX,
                 {.limitCompliance = 0.1, .swingLimit = 0.6, .twistLimits = Range{-0.4, 0.4},
                  .twistCompliance = 0.1});

    scene.camera = SceneCamera{.position = Vec3(0.1, 1.45, 3.3), .target = Vec3(0.1, 1.25, 0.0), .fov = 0.8};
    return scene;
}

std::string rangeLabel(const char* what, double lower, double upper, const char* unit) {
    char text[96];
    std::snprintf(text, sizeof text, "%s [%s] (limits %.2f .. %.2f)", what, unit, lower, upper);
    return text;
}

class JointTypesScript : public SceneScript {
  public:
    std::unique_ptr<SceneScript> clone() const override { return std::make_unique<JointTypesScript>(*this); }
    JointTypesScript() {
        animate_ = addKnob({.name = "animate", .label = "sweep the drive targets", .kind = SceneKnob::Kind::Toggle,
                            .value = 1.0});
        drives_ = addKnob({.name = "drives", .label = "drives on", .kind = SceneKnob::Kind::Toggle, .value = 1.0});
        hingeTarget_ = addKnob({.name = "hinge_target", .label = "hinge target angle (rad)",
                                .value = 0.6, .min = -1.5, .max = 1.5, .format = "%.2f"});
        prismaticTarget_ = addKnob({.name = "prismatic_target", .label = "prismatic target offset (m)",
                                    .value = -0.3, .min = -0.7, .max = 0.0, .format = "%.2f"});
        driveCompliance_ = addKnob({.name = "drive_compliance", .label = "drive compliance (SI)",
                                    .value = 0.0, .min = 0.0, .max = 0.1, .format = "%.2g",
                                    .logarithmic = true});
        softLinear_ = addKnob({.name = "soft_linear_compliance", .label = "soft prismatic limit compliance (m/N)",
                               .value = 0.01, .min = 0.0, .max = 0.03, .format = "%.2g", .logarithmic = true});
        softAngular_ = addKnob({.name = "soft_angular_compliance", .label = "soft angular limit compliance (rad/Nm)",
                                .value = 0.1, .min = 0.0, .max = 0.5, .format = "%.2g", .logarithmic = true});
        prismaticLower_ = addKnob({.name = "prismatic_lower", .label = "prismatic lower limit (m)",
                                   .value = -0.5, .min = -0.7, .max = kPrismaticUpper, .format = "%.2f"});
        hingeLimit_ = addKnob({.name = "hinge_limit", .label = "hinge limits +- (rad)",
                               .value = 0.5, .min = 0.0, .max = 1.5, .format = "%.2f"});
        swingLimit_ = addKnob({.name = "swing_limit", .label = "spherical swing limit (rad)",
                               .value = 0.6, .min = 0.0, .max = 1.5, .format = "%.2f"});
        twistLimit_ = addKnob({.name = "twist_limit", .label = "spherical twist limits +- (rad)",
                               .value = 0.4, .min = 0.0, .max = 1.5, .format = "%.2f"});
        damping_ = addKnob({.name = "damping", .label = "joint damping (1/s)",
                            .value = kDamping, .min = 0.0, .max = 10.0, .format = "%.2f"});
    }

    void start(SceneInstance& scene) override {
        prismaticHard_ = scene.jointNamed("prismatic_hard_joint");
        prismaticSoft_ = scene.jointNamed("prismatic_soft_joint");
        prismaticDrive_ = scene.jointNamed("prismatic_drive_joint");
        hingeHard_ = scene.jointNamed("hinge_hard_joint");
        hingeSoft_ = scene.jointNamed("hinge_soft_joint");
        hingeDrive_ = scene.jointNamed("hinge_drive_joint");
        ballHard_ = scene.jointNamed("ball_hard_joint");
        ballSoft_ = scene.jointNamed("ball_soft_joint");
        applyAll(scene.registry, 0.0);
    }

    void beforeFrame(SceneInstance& scene, double time, double /*dt*/) override {
        if (toggled(animate_)) applyTargets(scene.registry, time);
    }

    void knobChanged(SceneInstance& scene, std::size_t /*index*/) override {
        applyAll(scene.registry, lastTime_);
        // A limit moved past a body is put right before the next step, not turned into speed.
        scene.physics().requestRepair();
    }

    void readouts(const SceneInstance& scene, std::vector<SceneReadout>& out) const override {
        const ecs::Registry& registry = scene.registry;
        const auto pose = [&](ecs::Entity joint) {
            return ecs::jointPose(registry, registry.get<ecs::Joint>(joint));
        };
        const double lower = knob(prismaticLower_);
        out.push_back({rangeLabel("prismatic hard offset", lower, kPrismaticUpper, "m"),
                       ecs::prismaticOffset(pose(prismaticHard_)), "%.4f"});
        out.push_back({rangeLabel("prismatic soft offset", lower, kPrismaticUpper, "m"),
                       ecs::prismaticOffset(pose(prismaticSoft_)), "%.4f"});
        out.push_back({"prismatic drive offset [m] (target " + format("%.3f", slideTarget_) + ")",
                       ecs::prismaticOffset(pose(prismaticDrive_)), "%.4f"});
        const double hinge = knob(hingeLimit_);
        out.push_back({rangeLabel("hinge hard angle", -hinge, hinge, "rad"),
                       ecs::hingeAngle(pose(hingeHard_)), "%.4f"});
        out.push_back({rangeLabel("hinge soft angle", -hinge, hinge, "rad"),
                       ecs::hingeAngle(pose(hingeSoft_)), "%.4f"});
        out.push_back({"hinge drive angle [rad] (target " + format("%.3f", hingeTarget()) + ")",
                       ecs::hingeAngle(pose(hingeDrive_)), "%.4f"});
        const double swing = knob(swingLimit_);
        const double twist = knob(twistLimit_);
        for (const auto& [label, joint] : {std::pair{"ball hard", ballHard_}, std::pair{"ball soft", ballSoft_}}) {
            out.push_back({rangeLabel((std::string(label) + " swing").c_str(), 0.0, swing, "rad"),
                           ecs::swingAngle(pose(joint)), "%.4f"});
            out.push_back({rangeLabel((std::string(label) + " twist").c_str(), -twist, twist, "rad"),
                           ecs::twistAngle(pose(joint)), "%.4f"});
        }
    }

  private:
    static std::string format(const char* pattern, double value) {
        char text[32];
        std::snprintf(text, sizeof text, pattern, value);
        return text;
    }

    double hingeTarget() const { return hingeAngleTarget_; }

    /// Changes joint `entity`'s definition through the engine layer.
    template <class Change>
    static void editJoint(ecs::Registry& registry, ecs::Entity entity, Change&& change) {
        registry.patch<ecs::Joint>(entity, [&](ecs::Joint& joint) { change(joint.def); });
    }

    /// The drive targets: the knobs' values, swept about them while `animate` is on; a drive
    /// that is off has no target.
    void applyTargets(ecs::Registry& registry, double time) {
        lastTime_ = time;
        const bool sweep = toggled(animate_);
        const double hingeSweep = sweep ? 0.8 * std::sin(1.2 * time) : 0.0;
        const double slideSweep = sweep ? 0.15 * std::sin(1.7 * time) : 0.0;
        hingeAngleTarget_ = knob(hingeTarget_) + hingeSweep;
        slideTarget_ = std::min(knob(prismaticTarget_) + slideSweep, 0.0);
        const bool drives = toggled(drives_);
        editJoint(registry, hingeDrive_, [&](JointDef& def) {
            def.targetAngle = drives ? std::optional(hingeAngleTarget_) : std::nullopt;
        });
        editJoint(registry, prismaticDrive_, [&](JointDef& def) {
            def.targetOffset = drives ? std::optional(slideTarget_) : std::nullopt;
        });
    }

    void applyAll(ecs::Registry& registry, double time) {
        for (const ecs::Entity joint : {hingeDrive_, prismaticDrive_})
            editJoint(registry, joint, [&](JointDef& def) { def.driveCompliance = knob(driveCompliance_); });
        applyTargets(registry, time);

        const Range slide{knob(prismaticLower_), kPrismaticUpper};
        for (const ecs::Entity joint : {prismaticHard_, prismaticSoft_})
            editJoint(registry, joint, [&](JointDef& def) { def.limits = slide; });
        editJoint(registry, prismaticSoft_, [&](JointDef& def) { def.limitCompliance = knob(softLinear_); });

        const double hinge = knob(hingeLimit_);
        for (const ecs::Entity joint : {hingeHard_, hingeSoft_})
            editJoint(registry, joint, [&](JointDef& def) { def.limits = Range{-hinge, hinge}; });
        editJoint(registry, hingeSoft_, [&](JointDef& def) { def.limitCompliance = knob(softAngular_); });

        for (const ecs::Entity joint : {ballHard_, ballSoft_}) {
            editJoint(registry, joint, [&](JointDef& def) {
                def.swingLimit = knob(swingLimit_);
                def.twistLimits = Range{-knob(twistLimit_), knob(twistLimit_)};
            });
        }
        editJoint(registry, ballSoft_, [&](JointDef& def) {
            def.limitCompliance = knob(softAngular_);
            def.twistCompliance = knob(softAngular_);
        });

        for (const ecs::Entity joint : {prismaticHard_, prismaticSoft_, prismaticDrive_, hingeHard_, hingeSoft_,
                                        hingeDrive_, ballHard_, ballSoft_}) {
            editJoint(registry, joint, [&](JointDef& def) {
                def.linearDamping = knob(damping_);
                def.angularDamping = knob(damping_);
            });
        }
    }

    std::size_t animate_, drives_, hingeTarget_, prismaticTarget_, driveCompliance_, softLinear_, softAngular_,
        prismaticLower_, hingeLimit_, swingLimit_, twistLimit_, damping_;
    ecs::Entity prismaticHard_, prismaticSoft_, prismaticDrive_, hingeHard_, hingeSoft_, hingeDrive_, ballHard_,
        ballSoft_;
    double lastTime_ = 0.0;
    double hingeAngleTarget_ = 0.0;  ///< the hinge drive's current target (rad)
    double slideTarget_ = 0.0;        ///< the prismatic drive's current target (m)
};

}  // namespace

SceneEntry jointTypesEntry() {
    return {.name = "joint_types",
            .description = "Fig. 7: prismatic, hinge and spherical joints with hard and soft limits and drives",
            .build = build,
            .paperMsPerFrame = 0,
            .makeScript = []() -> std::unique_ptr<SceneScript> { return std::make_unique<JointTypesScript>(); }};
}

}  // namespace substep::scenes
