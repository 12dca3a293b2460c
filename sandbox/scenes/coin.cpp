// Fig. 15: a coin spun on a table. Started nearly upright and spinning about its vertical
// diameter, it tilts over and rolls on its rim with its centre almost still (Euler's disk):
// the contact point runs round the rim ever faster as the tilt falls, until the coin slaps
// down flat. The paper: "With the ability of handling curved geometry and substepping we are
// able to reproduce the high frequency motion of a coin shortly before it comes to rest";
// Table 1: 20 substeps x 1 iteration, 0.3 ms/frame.
//
// The rim is an exact cylinder (collide_cylinder.h), found anew every substep, so the rolling
// contact moves smoothly round it; a polygonal coin would roll on facets instead.
//
// Steady rolling with the centre at rest, tilt α of the coin's face from the table, radius a,
// thickness t, moments A = m(3a² + t²)/12 about a diameter and C = m a²/2 about the axis: the
// angular velocity lies along the line from the centre to the contact point (the contact point
// is at rest), its size Ω sin α, and the torque of the weight about the centre turns the angular
// momentum round the vertical at the precession rate Ω:
//     Ω² sin α (A cos α − C (t/2a) sin α) = m g (a cos α − (t/2) sin α),
// which for a thin disc (t = 0) is Moffatt's Ω² = 4 g / (a sin α): the wobble's rate grows
// without bound as the coin goes flat. coinPrecessionRate() below evaluates it.

#include "scenes/scenes.h"

#include "ecs/components.h"


#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <string_view>

namespace substep::scenes {
namespace {

// A 1 euro coin: 23.25 mm across, 2.33 mm thick, 7.5 g.
constexpr double kCoinRadius = 0.011625;
constexpr double kCoinThickness = 0.00233;
constexpr double kCoinMass = 0.0075;

constexpr double kDefaultSpinRate = 60.0;  ///< rad/s about the vertical diameter
constexpr double kDefaultTilt = 10.0;      ///< degrees from upright
constexpr double kDefaultFriction = 0.4;

constexpr double kDegree = std::numbers::pi / 180.0;

SceneDescription buildCoin() {
    SceneDescription scene{.name = "coin", .gravity = kPaperGravity};
    // A table top (a static box, its top face at y = 0) and the coin on it; the script puts
    // the coin on its rim and spins it.
    scene.bodies.push_back({"table", BodyDef{.shape = boxShape(Vec3(0.4, 0.03, 0.4)),
                                             .type = BodyType::Static,
                                             .position = Vec3(0.0, -0.015, 0.0),
                                             .staticFriction = kDefaultFriction,
                                             .dynamicFriction = kDefaultFriction}});
    scene.bodies.push_back({"coin", BodyDef{.shape = cylinderShape(kCoinRadius, kCoinThickness),
                                            .mass = kCoinMass,
                                            .position = Vec3(0.0, kCoinRadius, 0.0),
                                            .orientation = Quat(Eigen::AngleAxisd(0.5 * std::numbers::pi, Vec3::UnitZ())),
                                            .staticFriction = kDefaultFriction,
                                            .dynamicFriction = kDefaultFriction},
                            Vec3(0.83, 0.69, 0.22)});  // brass
    scene.camera = SceneCamera{.position = Vec3(0.045, 0.04, 0.075), .target = Vec3(0.0, 0.004, 0.0), .fov = 0.55};
    return scene;
}

/// Angle of the coin's face from the table (rad): 0 flat, π/2 upright.
double coinTilt(const Quat& orientation) {
    const Vec3 axis = orientation * Vec3::UnitY();
    return std::acos(std::clamp(std::abs(axis.y()), 0.0, 1.0));
}

/// Rate (rad/s) at which the coin's axis turns about the vertical: the wobble.
double coinPrecessionRate(const Quat& orientation, const Vec3& angularVelocity) {
    // The axis u turns at u̇ = ω × u; its azimuth about the vertical at (u_h × u̇_h)·y / |u_h|².
    const Vec3 axis = orientation * Vec3::UnitY();
    const Vec3 rate = angularVelocity.cross(axis);
    const double horizontal2 = axis.x() * axis.x() + axis.z() * axis.z();
    if (!(horizontal2 > 1e-12)) return 0.0;
    return (axis.z() * rate.x() - axis.x() * rate.z()) / horizontal2;
}

/// Ω of steady rolling with the centre at rest at tilt α (file comment); 0 past the balance.
double steadyPrecessionRate(double tilt) {
    const double a = kCoinRadius;
    const double t = kCoinThickness;
    const double s = std::sin(tilt);
    const double c = std::cos(tilt);
    // Per unit mass: A = (3a² + t²)/12, C = a²/2 (file comment).
    const double left = s * ((3.0 * a * a + t * t) / 12.0 * c - 0.5 * a * a * (t / (2.0 * a)) * s);
    const double right = std::abs(kPaperGravity.y()) * (a * c - 0.5 * t * s);
    if (!(left > 0.0) || !(right > 0.0)) return 0.0;
    return std::sqrt(right / left);
}

class CoinScript : public SceneScript {
  public:
    std::unique_ptr<SceneScript> clone() const override { return std::make_unique<CoinScript>(*this); }
    CoinScript() {
        spin_ = addKnob({.name = "spin",
                         .label = "spin about the vertical (rad/s)",
                         .value = kDefaultSpinRate,
                         .min = 0.0,
                         .max = 80.0,
                         .format = "%.1f"});
        tilt_ = addKnob({.name = "tilt",
                         .label = "initial tilt from upright (deg)",
                         .value = kDefaultTilt,
                         .min = 5.0,
                         .max = 60.0,
                         .format = "%.1f"});
        friction_ = addKnob({.name = "friction",
                             .label = "friction (static = dynamic)",
                             .value = kDefaultFriction,
                             .min = 0.05,
                             .max = 1.0,
                             .format = "%.2f"});
    }

    void start(SceneInstance& scene) override {
        coin_ = scene.bodyNamed("coin");
        table_ = scene.bodyNamed("table");
        applyFriction(scene);
        place(scene);
    }

    void knobChanged(SceneInstance& scene, std::size_t index) override {
        // The friction acts at once; a new spin or tilt is a new throw from the start pose
        // (restart throws again with the knobs' values too).
        if (index == friction_) applyFriction(scene);
        if (index == spin_ || index == tilt_) place(scene);
    }

    void readouts(const SceneInstance& scene, std::vector<SceneReadout>& out) const override {
        if (!scene.registry.isValid(coin_)) return;
        const Quat& orientation = scene.registry.get<ecs::Transform>(coin_).rotation;
        const Vec3& angularVelocity = scene.registry.get<ecs::RigidBody>(coin_).angularVelocity;
        const double tilt = coinTilt(orientation);
        out.push_back({"tilt of the face from the table (deg)", tilt / kDegree, "%.2f"});
        out.push_back({"precession rate (rad/s)", std::abs(coinPrecessionRate(orientation, angularVelocity)), "%.1f"});
        out.push_back({"steady rolling prediction (rad/s)", steadyPrecessionRate(tilt), "%.1f"});
    }

  private:
    void applyFriction(SceneInstance& scene) const {
        for (const ecs::Entity body : {coin_, table_}) {
            if (!scene.registry.isValid(body)) continue;
            scene.registry.patch<ecs::Collider>(body, [&](ecs::Collider& collider) {
                collider.staticFriction = knob(friction_);
                collider.dynamicFriction = knob(friction_);
            });
        }
    }

    /// On its rim at the knob's tilt from upright, the lowest rim corner on the table, spinning
    /// about the vertical through its centre.
    void place(SceneInstance& scene) const {
        if (!scene.registry.isValid(coin_)) return;
        const double alpha = std::clamp(90.0 - knob(tilt_), 0.0, 90.0) * kDegree;  // face to table
        const Quat orientation(Eigen::AngleAxisd(alpha, Vec3::UnitZ()));
        const Vec3 centre(0.0, kCoinRadius * std::sin(alpha) + 0.5 * kCoinThickness * std::cos(alpha), 0.0);
        scene.registry.patch<ecs::Transform>(coin_, [&](ecs::Transform& transform) {
            transform.position = centre;
            transform.rotation = orientation;
        });
        scene.registry.patch<ecs::RigidBody>(coin_, [&](ecs::RigidBody& coin) {
            coin.velocity = Vec3::Zero();
            coin.angularVelocity = Vec3(0.0, knob(spin_), 0.0);
        });
    }

    std::size_t spin_ = 0;
    std::size_t tilt_ = 0;
    std::size_t friction_ = 0;
    ecs::Entity coin_;
    ecs::Entity table_;
};

}  // namespace

SceneEntry coinEntry() {
    return {.name = "coin",
            .description = "Fig. 15: a coin spun on a table wobbles faster and faster before it rests",
            .build = buildCoin,
            .paperMsPerFrame = 0.3,
            .makeScript = []() -> std::unique_ptr<SceneScript> { return std::make_unique<CoinScript>(); }};
}

}  // namespace substep::scenes
