// Paper Fig. 12 and section 5: "a single marble hits a group of three marbles from the right.
// The impulse is correctly transferred to the right most marble". The striker here comes from
// the right, as the sentence's first half says, so the far marble it must reach is the LEFT
// most; the sentence's "right most" only holds for a striker from the left (the figure may be
// mirrored). Either way the claim is the same: the far marble leaves, the rest stop.
//
// Four equal marbles with restitution 1 (the figure's caption) roll on a ground plane. With the
// velocity pass (paper 3.6, Eq. 34: v_n ← −e v̄_n per contact) the striker's speed passes
// through the row; with plain PBD velocities (v = Δx/h, Algorithm 2 without the pass) the
// overlaps are only pushed apart and the marbles share the striker's momentum.

#include "scenes/scenes.h"

#include "ecs/components.h"


#include <algorithm>
#include <array>
#include <memory>
#include <string>

namespace substep::scenes {

namespace {

constexpr double kMarbleRadius = 0.1;   ///< m: sandbox scale, so the hit is easy to see
constexpr double kGlassDensity = 2500;  ///< kg/m³: 10.5 kg marbles, all equal
constexpr int kRowSize = 3;
constexpr double kStrikerGap = 0.6;    ///< m between the striker and the row at the start
constexpr double kDefaultSpeed = 2.0;  ///< m/s
/// Marbles are frictionless against each other: a rolling striker's surface moves vertically
/// where it meets the row, and friction there would lift the marbles off the ground instead of
/// passing the push along. Against the ground the pair's friction (the average, paper 3.5) is
/// half the ground's, enough to roll.
constexpr double kMarbleFriction = 0.0;
constexpr double kGroundFriction = 0.6;

/// x of row marble `i`, touching its neighbours; marble 0 is the far one (left most).
double rowX(int i) {
    return 2.0 * kMarbleRadius * i;
}
double strikerStartX() {
    return rowX(kRowSize - 1) + 2.0 * kMarbleRadius + kStrikerGap;
}

std::string rowName(int i) {
    return "marble" + std::to_string(i);
}

SceneDescription buildCradle() {
    SceneDescription scene{.name = "cradle", .gravity = kPaperGravity};
    addGroundPlane(scene, kGroundFriction);
    const auto marble = [](const Vec3& position) {
        return BodyDef{.shape = sphereShape(kMarbleRadius),
                       .density = kGlassDensity,
                       .position = position,
                       .staticFriction = kMarbleFriction,
                       .dynamicFriction = kMarbleFriction,
                       .restitution = 1.0};
    };
    for (int i = 0; i < kRowSize; ++i)
        scene.bodies.push_back({rowName(i), marble(Vec3(rowX(i), kMarbleRadius, 0.0))});
    // The striker's velocity is set by the script (its speed knob).
    scene.bodies.push_back({"striker", marble(Vec3(strikerStartX(), kMarbleRadius, 0.0)), Vec3(0.85, 0.12, 0.10)});  // the paper's red
    scene.camera =
        SceneCamera{.position = Vec3(0.0, 0.55, 1.9), .target = Vec3(0.0, 0.1, 0.0), .fov = 0.8};
    return scene;
}

class CradleScript : public SceneScript {
  public:
    std::unique_ptr<SceneScript> clone() const override { return std::make_unique<CradleScript>(*this); }
    CradleScript() {
        velocityPass_ = addKnob({.name = "velocity_pass",
                                 .label = "velocity pass (off: plain PBD)",
                                 .kind = SceneKnob::Kind::Toggle,
                                 .value = 1.0});
        speed_ = addKnob({.name = "striker_speed",
                          .label = "striker speed (m/s)",
                          .value = kDefaultSpeed,
                          .min = 0.2,
                          .max = 10.0,
                          .format = "%.2f"});
        restitution_ = addKnob({.name = "restitution",
                                .label = "restitution",
                                .value = 1.0,
                                .min = 0.0,
                                .max = 1.0,
                                .format = "%.2f"});
    }

    void start(SceneInstance& scene) override {
        for (int i = 0; i < kRowSize; ++i)
            row_[i] = scene.bodyNamed(rowName(i));
        striker_ = scene.bodyNamed("striker");
        leavingSpeed_ = 0.0;
        applyVelocityPass(scene);
        applyRestitution(scene);
        launch(scene);
    }

    void knobChanged(SceneInstance& scene, size_t index) override {
        if (index == velocityPass_) applyVelocityPass(scene);
        if (index == restitution_) applyRestitution(scene);
        // A new speed takes effect while the striker is still on its way in, else at restart.
        if (index == speed_ && scene.registry.isValid(striker_) &&
            scene.registry.get<ecs::RigidBody>(striker_).centreOfMass.x() >
                rowX(kRowSize - 1) + 2.0 * kMarbleRadius + 1e-3)
            launch(scene);
    }

    void beforeFrame(SceneInstance& scene, double /*time*/, double /*dt*/) override {
        // The far marble's speed in the first frame it moves: the paper's measure of the hit
        // (Fig. 12, 0.98 of the striker's), before the ground's friction slows it further.
        if (leavingSpeed_ > 0.0 || !scene.registry.isValid(row_[0])) return;
        const double speed = scene.registry.get<ecs::RigidBody>(row_[0]).velocity.norm();
        if (speed > 0.01 * launchedSpeed_) leavingSpeed_ = speed;
    }

    void readouts(const SceneInstance& scene, std::vector<SceneReadout>& out) const override {
        if (!scene.registry.isValid(row_[0]) || !scene.registry.isValid(striker_)) return;
        const double initial = std::max(launchedSpeed_, 1e-9);
        const auto speed = [&](ecs::Entity marble) {
            return scene.registry.get<ecs::RigidBody>(marble).velocity.norm();
        };
        out.push_back({"far marble's leaving speed / striker's (paper: 0.98)", leavingSpeed_ / initial, "%.3f"});
        out.push_back({"far marble speed / striker's initial", speed(row_[0]) / initial, "%.3f"});
        out.push_back({"striker speed / its initial", speed(striker_) / initial, "%.3f"});
    }

  private:
    void applyVelocityPass(SceneInstance& scene) const {
        ecs::PhysicsSystem physics = scene.physics();
        WorldSettings settings = physics.settings();
        settings.velocityPass = toggled(velocityPass_);
        physics.setSettings(settings);
    }

    void applyRestitution(SceneInstance& scene) const {
        const auto setRestitution = [&](ecs::Entity marble) {
            if (!scene.registry.isValid(marble)) return;
            scene.registry.patch<ecs::Collider>(
                marble, [&](ecs::Collider& collider) { collider.restitution = knob(restitution_); });
        };
        for (const ecs::Entity marble : row_) setRestitution(marble);
        setRestitution(striker_);
    }

    /// Sets the striker rolling towards the row: v along −x, ω = v / r about +z, so its
    /// contact point with the ground is at rest.
    void launch(SceneInstance& scene) {
        launchedSpeed_ = knob(speed_);
        if (!scene.registry.isValid(striker_)) return;
        scene.registry.patch<ecs::RigidBody>(striker_, [&](ecs::RigidBody& striker) {
            striker.velocity = Vec3(-launchedSpeed_, 0.0, 0.0);
            striker.angularVelocity = Vec3(0.0, 0.0, launchedSpeed_ / kMarbleRadius);
        });
    }

    size_t velocityPass_ = 0;
    size_t speed_ = 0;
    size_t restitution_ = 0;
    std::array<ecs::Entity, kRowSize> row_{};
    ecs::Entity striker_{};
    double launchedSpeed_ = kDefaultSpeed;
    double leavingSpeed_ = 0.0;  ///< m/s, the far marble's in the first frame it moves; 0 before
};

}  // namespace

SceneEntry cradleEntry() {
    return {.name = "cradle",
            .description = "Fig. 12: a marble hits a row of three; the impulse reaches the far one",
            .build = buildCradle,
            .paperMsPerFrame = 0,
            .makeScript = []() -> std::unique_ptr<SceneScript> {
                return std::make_unique<CradleScript>();
            }};
}

}  // namespace substep::scenes
