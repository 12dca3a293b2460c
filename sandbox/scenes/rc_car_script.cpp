// The RC car's script (the scene is built in rc_car.cpp): the autopilot's laps (rc_car_autopilot.cpp), the driver's
// knobs (throttle, steering, compliances of the tyres, the servo and the suspension), the
// readouts (speed, steering commanded against reached, tyre deflection) and the camera that
// follows the chassis. It acts only through components: the rear axles' motors and the servo's
// target are Joint patches; a new tyre compliance replaces the tyres (a soft body is fixed at
// creation) with new ones around the rims as they are.

#include "scenes/rc_car.h"
#include "scenes/rc_car_autopilot.h"

#include "scenes/scenes.h"

#include "ecs/components.h"
#include "ecs/soft_body_component.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

namespace substep::scenes {
namespace {

using namespace rc_car;

constexpr double kDegree = M_PI / 180.0;
/// rad/s²: the motors' target speed changes at most this fast (3 m/s² of the car).
constexpr double kWheelAcceleration = 40.0;

class RcCarScript : public SceneScript {
  public:
    std::unique_ptr<SceneScript> clone() const override { return std::make_unique<RcCarScript>(*this); }
    RcCarScript() {
        throttle_ = addKnob({.name = "throttle",
                             .label = "throttle (0: motors off)",
                             .value = 0.0,
                             .min = -1.0,
                             .max = 1.0,
                             .format = "%.2f"});
        steer_ = addKnob({.name = "steer",
                          .label = "steering (deg, + left)",
                          .value = 0.0,
                          .min = -kMaxSteer / kDegree,
                          .max = kMaxSteer / kDegree,
                          .format = "%.1f"});
        autopilot_ = addKnob({.name = "autopilot",
                              .label = "autopilot (a lap out and back)",
                              .kind = SceneKnob::Kind::Toggle,
                              .value = 1.0});
        brake_ = addKnob({.name = "brake",
                          .label = "motors hold the wheels at zero throttle",
                          .kind = SceneKnob::Kind::Toggle,
                          .value = 0.0});
        tyreCompliance_ = addKnob({.name = "tyre_compliance",
                                   .label = "tyre compliance (1/Pa; new tyres)",
                                   .value = kTyreCompliance,
                                   .min = 1e-6,
                                   .max = 1e-3,
                                   .format = "%.2e",
                                   .logarithmic = true});
        servoCompliance_ = addKnob({.name = "servo_compliance",
                                    .label = "servo compliance (rad/(N m))",
                                    .value = kServoCompliance,
                                    .min = 1e-6,
                                    .max = 1.0,
                                    .format = "%.2e",
                                    .logarithmic = true});
        suspensionCompliance_ = addKnob({.name = "suspension_compliance",
                                         .label = "suspension compliance (m/N)",
                                         .value = kSuspensionCompliance,
                                         .min = 1e-4,
                                         .max = 1e-2,
                                         .format = "%.2e",
                                         .logarithmic = true});
        // The window drives with the arrows or WASD, or the first gamepad's left stick.
        addKeyAxis({.knob = "throttle", .positiveKeys = "Up W", .negativeKeys = "Down S", .amount = 0.7,
                    .gamepadAxis = 1, .invertGamepad = true});
        addKeyAxis({.knob = "steer", .positiveKeys = "Left A", .negativeKeys = "Right D", .amount = 25.0,
                    .gamepadAxis = 0, .invertGamepad = true});
        follow_ = addKnob({.name = "follow",
                           .label = "camera follows the car",
                           .kind = SceneKnob::Kind::Toggle,
                           .value = 1.0});
    }

    void start(SceneInstance& scene) override {
        chassis_ = scene.bodyNamed("chassis");
        servo_ = scene.jointNamed("servo");
        for (int corner = 0; corner < 4; ++corner) {
            const std::string suffix(kCorners[corner]);
            wheels_[corner] = scene.bodyNamed("wheel_" + suffix);
            axles_[corner] = scene.jointNamed("axle_" + suffix);
            suspensions_[corner] = scene.jointNamed("suspension_" + suffix);
        }
        kingpins_ = {scene.jointNamed("kingpin_fl"), scene.jointNamed("kingpin_fr")};
        wheelSpeed_ = 0.0;
        motorsOn_ = false;
        pilot_ = Autopilot{};
        tyresBuiltWith_ = kTyreCompliance;
        applyCompliances(scene);
        command(scene, 0.0, 0.0);
        observeTyres(scene);
    }

    void knobChanged(SceneInstance& scene, size_t index) override {
        // The driver takes over from the autopilot.
        if (index == throttle_ || index == steer_) knobs()[autopilot_].value = 0.0;
        if (index == tyreCompliance_ || index == servoCompliance_ || index == suspensionCompliance_)
            applyCompliances(scene);
    }

    void beforeFrame(SceneInstance& scene, double time, double dt) override {
        observeTyres(scene);
        double throttle = knob(throttle_);
        double steer = knob(steer_);
        if (toggled(autopilot_)) {
            const ecs::Transform& chassis = scene.registry.get<ecs::Transform>(chassis_);
            const DriveCommand drive = pilot_.drive(time, chassis.position, headingOf(chassis.rotation * Vec3::UnitX()));
            throttle = drive.throttle;
            steer = drive.steer;
        }
        command(scene, throttle, steer * kDegree, dt);
    }

    void readouts(const SceneInstance& scene, std::vector<SceneReadout>& out) const override {
        const ecs::Transform& chassis = scene.registry.get<ecs::Transform>(chassis_);
        const Vec3 forward = chassis.rotation * Vec3::UnitX();
        const double speed = scene.registry.get<ecs::RigidBody>(chassis_).velocity.dot(forward);
        const double reached = 0.5 * (scene.registry.get<ecs::Joint>(kingpins_[0]).readout.coordinate +
                                      scene.registry.get<ecs::Joint>(kingpins_[1]).readout.coordinate);
        out.push_back({"speed (m/s)", speed, "%.2f"});
        out.push_back({"steering commanded (deg)", steerTarget_ / kDegree, "%.1f"});
        out.push_back({"steering reached (deg)", reached / kDegree, "%.1f"});
        out.push_back({"servo arm (deg)", scene.registry.get<ecs::Joint>(servo_).readout.coordinate / kDegree, "%.1f"});
        out.push_back({"tyre deflection, largest (mm)", deflection_ * 1e3, "%.1f"});
        out.push_back({"motor target (rad/s)", wheelSpeed_, "%.1f"});
    }

    std::optional<SceneCamera> camera(const SceneInstance& scene) const override {
        if (!toggled(follow_) || !scene.registry.isValid(chassis_)) return std::nullopt;
        // Behind and above the chassis, along its heading on the ground.
        const ecs::Transform& chassis = scene.registry.get<ecs::Transform>(chassis_);
        Vec3 forward = chassis.rotation * Vec3::UnitX();
        forward.y() = 0.0;
        forward = forward.norm() > 1e-6 ? forward.normalized() : Vec3::UnitX();
        const Vec3 right = forward.cross(Vec3::UnitY());
        return SceneCamera{.position = chassis.position - 1.0 * forward + 0.4 * Vec3::UnitY() + 0.3 * right,
                           .target = chassis.position + 0.2 * forward,
                           .fov = 0.9};
    }

  private:
    /// Drives the rear motors and the servo. Throttle 0 switches the motors off (the wheels roll
    /// freely) unless `brake` is on; the motors' speed follows the throttle at most
    /// kWheelAcceleration fast.
    void command(SceneInstance& scene, double throttle, double steer, double dt = 0.0) {
        const double target = throttle * kMaxWheelSpeed;
        const double step = kWheelAcceleration * dt;
        wheelSpeed_ = dt > 0.0 ? std::clamp(target, wheelSpeed_ - step, wheelSpeed_ + step) : 0.0;
        const bool on = throttle != 0.0 || wheelSpeed_ != 0.0 || toggled(brake_);
        if (on != motorsOn_ || (on && wheelSpeed_ != motorSpeed_)) {
            for (int corner = 2; corner < 4; ++corner)
                scene.registry.patch<ecs::Joint>(axles_[corner], [&](ecs::Joint& axle) {
                    axle.def.targetVelocity = on ? std::optional<double>(wheelSpeed_) : std::nullopt;
                    axle.def.driveCompliance = kMotorCompliance;
                });
            motorsOn_ = on;
            motorSpeed_ = wheelSpeed_;
        }
        steer = std::clamp(steer, -kMaxSteer, kMaxSteer);
        if (steer != steerTarget_) {
            scene.registry.patch<ecs::Joint>(servo_, [&](ecs::Joint& servo) { servo.def.targetAngle = steer; });
            steerTarget_ = steer;
        }
    }

    /// The servo's and the springs' compliances, and the tyres' (by new tyres).
    void applyCompliances(SceneInstance& scene) {
        scene.registry.patch<ecs::Joint>(servo_, [&](ecs::Joint& servo) {
            servo.def.driveCompliance = knob(servoCompliance_);
        });
        // The springs stay preloaded to the ride height: target = −(sprung weight) x compliance.
        const double sprungLoad = 0.25 * (kChassisMass + kServoArmMass) * -kPaperGravity.y();
        for (const ecs::Entity suspension : suspensions_)
            scene.registry.patch<ecs::Joint>(suspension, [&](ecs::Joint& spring) {
                spring.def.driveCompliance = knob(suspensionCompliance_);
                spring.def.targetOffset = -sprungLoad * knob(suspensionCompliance_);
            });
        if (knob(tyreCompliance_) != tyresBuiltWith_) replaceTyres(scene);
    }

    /// New tyres of the knob's compliance around the rims, at their pose and motion.
    void replaceTyres(SceneInstance& scene) {
        ecs::PhysicsSystem physics = scene.physics();
        for (int corner = 0; corner < 4; ++corner) {
            const std::string name = "tyre_" + std::string(kCorners[corner]);
            const ecs::Entity old = scene.softBodyNamed(name);
            const auto slot = std::find(scene.softBodyEntities.begin(), scene.softBodyEntities.end(), old);
            const Vec3 colour = scene.registry.get<ecs::RenderMaterial>(old).colour;
            physics.destroy(old);
            const ecs::Transform& rim = scene.registry.get<ecs::Transform>(wheels_[corner]);
            const ecs::RigidBody& motion = scene.registry.get<ecs::RigidBody>(wheels_[corner]);
            const ecs::Entity tyre = scene.registry.create();
            scene.registry.emplace<ecs::SoftBody>(
                tyre, ecs::SoftBody{.def = tyreDef(rim.position, rim.rotation, motion.velocity, motion.angularVelocity,
                                                   knob(tyreCompliance_)),
                                    .attachedBodies = {wheels_[corner]}});
            scene.registry.emplace<ecs::RenderMaterial>(tyre, ecs::RenderMaterial{.colour = colour});
            scene.registry.emplace<ecs::Name>(tyre, name);
            if (slot != scene.softBodyEntities.end()) *slot = tyre;
        }
        tyresBuiltWith_ = knob(tyreCompliance_);
    }

    /// The largest tyre deflection: how far the lowest particle of each tyre is inside the
    /// unloaded radius, measured from its rim's axle.
    void observeTyres(SceneInstance& scene) {
        ecs::PhysicsSystem physics = scene.physics();
        deflection_ = 0.0;
        for (int corner = 0; corner < 4; ++corner) {
            const ecs::SoftBody* tyre =
                scene.registry.tryGet<ecs::SoftBody>(scene.softBodyNamed("tyre_" + std::string(kCorners[corner])));
            if (tyre == nullptr) continue;
            const std::span<const Vec3> positions = physics.softBodyPositions(*tyre);
            if (positions.empty()) continue;
            const ecs::Transform& rim = scene.registry.get<ecs::Transform>(wheels_[corner]);
            const Vec3 axle = rim.rotation * Vec3::UnitY();
            const Vec3* lowest = &positions[0];
            for (const Vec3& p : positions)
                if (p.y() < lowest->y()) lowest = &p;
            const Vec3 r = *lowest - rim.position;
            const double radial = (r - r.dot(axle) * axle).norm() + kParticleRadius;
            deflection_ = std::max(deflection_, kTyreRadius - radial);
        }
    }

    size_t throttle_ = 0, steer_ = 0, autopilot_ = 0, brake_ = 0;
    size_t tyreCompliance_ = 0, servoCompliance_ = 0, suspensionCompliance_ = 0, follow_ = 0;
    ecs::Entity chassis_, servo_;
    std::array<ecs::Entity, 4> wheels_{}, axles_{}, suspensions_{};
    std::array<ecs::Entity, 2> kingpins_{};
    double wheelSpeed_ = 0.0;   ///< rad/s, the motors' current target speed
    double motorSpeed_ = 0.0;   ///< rad/s, the speed last given to the motors
    bool motorsOn_ = false;
    double steerTarget_ = std::numeric_limits<double>::quiet_NaN();  ///< rad, last given to the servo
    double tyresBuiltWith_ = kTyreCompliance;
    double deflection_ = 0.0;  ///< m
    Autopilot pilot_;
};

}  // namespace

SceneEntry rcCarEntry() {
    return {.name = "rc_car",
            .description = "Figs. 1, 16: an RC car on soft tyres with its whole steering linkage (servo arm 1:760 of a "
                           "wheel) over bumps, planks, a curb and a ramp",
            .build = rc_car::build,
            .paperMsPerFrame = 18,
            .makeScript = []() -> std::unique_ptr<SceneScript> { return std::make_unique<RcCarScript>(); }};
}

}  // namespace substep::scenes
