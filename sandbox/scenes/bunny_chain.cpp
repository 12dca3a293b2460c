// Bunny chain (paper Figs. 10-11, section 4): 100 Stanford bunnies hanging from the ceiling as a
// chain of spherical joints. At one solver budget per frame (20 projections of every joint),
// 20 substeps of 1 iteration keep the chain near its rest length while 1 substep of 20
// iterations lets it stretch: Gauss-Seidel iterations cannot carry the ceiling's support down
// 100 links within one step, while substeps shrink the error of every projection as h².
//
// Each bunny is the asset mesh assets/meshes/bunny.obj as a convex mesh shape: it collides and
// weighs as its hull (Blow-Binstock over the hull's triangles, mass_properties.h), not as a box.
// The mesh is read once per build and the shape shared by all 100 bodies.

#include "scenes/asset_path.h"
#include "scenes/scenes.h"

#include "ecs/components.h"

#include "physics/collision/convex_hull.h"
#include "physics/collision/convex_mesh_shape.h"
#include "physics/mass_properties.h"
#include "scene/mesh_import.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace substep::scenes {
namespace {

constexpr int kBunnies = 100;
/// Joint to joint along each bunny (m): the bunny is scaled so that the vertical line through
/// its centre of mass crosses its hull over exactly this length (a bunny about 20 cm long).
constexpr double kPitch = 0.2;
constexpr double kDensity = 1000.0;  // kg/m³: about 4 kg per bunny
/// The chain hangs from this world point (the ceiling's underside), 1 m above its rest end.
constexpr double kCeilingHeight = kBunnies * kPitch + 1.0;
Vec3 ceilingAnchor() { return Vec3(0.0, kCeilingHeight, 0.0); }

/// Where the vertical line through `point` (x, z) enters and leaves a solid hull: {lowest y,
/// highest y} of the hull's points on it, from the face planes n·x <= offset.
std::array<double, 2> verticalChord(const ConvexHull& hull, const Vec3& point) {
    double low = -std::numeric_limits<double>::infinity();
    double high = std::numeric_limits<double>::infinity();
    for (const HullFace& face : hull.faces) {
        const double rest = face.offset - face.normal.x() * point.x() - face.normal.z() * point.z();
        if (face.normal.y() > 1e-12) high = std::min(high, rest / face.normal.y());
        if (face.normal.y() < -1e-12) low = std::max(low, rest / face.normal.y());
    }
    return {low, high};
}

/// The bunny as a convex mesh shape in its user frame: y up, the joint anchors at (0, ±kPitch/2,
/// 0) on the vertical through the centre of mass, where that line meets the hull's bottom and
/// top. Hanging from its top anchor a bunny then hangs upright with both anchors on one
/// vertical, so the chain at rest is straight and exactly kBunnies x kPitch long.
Shape bunnyShape() {
    const std::filesystem::path file = findAsset("meshes/bunny.obj");
    MeshImport imported = importTriangleMesh(file);
    if (!imported.ok()) throw std::runtime_error("bunny_chain: " + file.string() + ": " + imported.error);
    const ConvexHull rawHull = buildConvexHull(imported.mesh.vertices);
    if (!rawHull.isSolid()) throw std::runtime_error("bunny_chain: " + file.string() + " spans no volume");
    const Vec3 centre = meshMassProperties(hullTriangleMesh(rawHull), 1.0).centerOfMass;
    const auto [bottom, top] = verticalChord(rawHull, centre);
    if (!(top - bottom > 0.0)) throw std::runtime_error("bunny_chain: degenerate bunny hull");

    const double scale = kPitch / (top - bottom);
    const Vec3 origin(centre.x(), 0.5 * (bottom + top), centre.z());
    for (Vec3& vertex : imported.mesh.vertices) vertex = scale * (vertex - origin);
    return convexMeshShape(std::make_shared<const TriangleMesh>(std::move(imported.mesh)));
}

SceneDescription buildBunnyChain() {
    // Table 1: 20 substeps x 1 iteration per 1/60 s frame.
    SceneDescription scene{.name = "bunny_chain", .gravity = kPaperGravity, .substeps = 20, .iterations = 1};
    const Shape bunny = bunnyShape();  // one mesh and hull for all bodies
    const Vec3 halfPitch(0.0, kPitch / 2, 0.0);
    const Vec3 ceiling = ceilingAnchor();
    for (int i = 0; i < kBunnies; ++i) {
        const std::string name = "bunny" + std::to_string(i + 1);
        scene.bodies.push_back({name, BodyDef{.shape = bunny,
                                              .density = kDensity,
                                              .position = ceiling - Vec3(0.0, kPitch * (i + 0.5), 0.0),
                                              .collide = false}});
        JointDef ball{.type = JointType::Spherical, .anchor0 = -halfPitch, .anchor1 = halfPitch};
        if (i == 0) ball.anchor0 = ceiling;
        addJoint(scene, "joint" + std::to_string(i + 1), i == 0 ? "" : "bunny" + std::to_string(i), name, ball);
    }
    addStaticBox(scene, "ceiling", Vec3(1.0, 0.1, 1.0), ceiling + Vec3(0.0, 0.05, 0.0));
    addGroundPlane(scene, 0.5);
    // From the front, a little to the side, far enough for the whole 20 m from ceiling to
    // ground and the arc the chain swings through from release_angle to the other side.
    scene.camera = SceneCamera{.position = Vec3(6.0, 11.0, 27.0), .target = Vec3(0.0, 11.0, 0.0), .fov = 0.85};
    return scene;
}

/// The solver splits of one budget (20 projections per frame) that Fig. 11 compares.
struct SolverSplit {
    int substeps;
    int iterations;
};
/// The release angle the chain starts from (degrees from the vertical, about z).
constexpr double kDefaultReleaseDegrees = 30.0;
constexpr std::array<SolverSplit, 5> kSplits{{{20, 1}, {10, 2}, {5, 4}, {2, 10}, {1, 20}}};

class BunnyChainScript final : public SceneScript {
  public:
    std::unique_ptr<SceneScript> clone() const override { return std::make_unique<BunnyChainScript>(*this); }
    BunnyChainScript() {
        solver_ = addKnob({.name = "solver",
                           .label = "substeps x iterations",
                           .kind = SceneKnob::Kind::Choice,
                           .choices = {"20 x 1", "10 x 2", "5 x 4", "2 x 10", "1 x 20"}});
        releaseAngle_ = addKnob({.name = "release_angle",
                                 .label = "release angle (deg, on restart)",
                                 // Released out to the side, the chain swings and whips, as
                                 // in the paper's video; 0 hangs it at rest (Fig. 11's measure).
                                 .value = kDefaultReleaseDegrees,
                                 .min = 0.0,
                                 .max = 90.0,
                                 .format = "%.0f"});
    }

    void start(SceneInstance& scene) override {
        end_ = scene.bodyNamed("bunny" + std::to_string(kBunnies));
        // The chain swings out from the ceiling anchor by the release angle, joints intact.
        const double angle = knob(releaseAngle_) * M_PI / 180.0;
        if (angle == 0.0) return;
        const Quat turn(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
        const Vec3 anchor = ceilingAnchor();
        for (const ecs::Entity body : scene.bodyEntities) {
            const ecs::Name* name = scene.registry.tryGet<ecs::Name>(body);
            if (name == nullptr || name->value.rfind("bunny", 0) != 0) continue;
            scene.registry.patch<ecs::Transform>(body, [&](ecs::Transform& transform) {
                transform.position = anchor + turn * (transform.position - anchor);
                transform.rotation = (turn * transform.rotation).normalized();
            });
        }
    }

    void knobChanged(SceneInstance& scene, std::size_t index) override {
        if (index != solver_) return;
        const SolverSplit split = kSplits[static_cast<std::size_t>(knob(solver_))];
        ecs::PhysicsSystem physics = scene.physics();
        WorldSettings settings = physics.settings();
        settings.substeps = split.substeps;
        settings.iterations = split.iterations;
        physics.setSettings(settings);
    }

    void readouts(const SceneInstance& scene, std::vector<SceneReadout>& out) const override {
        if (!scene.registry.isValid(end_)) return;
        const ecs::Transform& last = scene.registry.get<ecs::Transform>(end_);
        const Vec3 endPoint = last.position + last.rotation * Vec3(0.0, -kPitch / 2, 0.0);
        const double rest = kBunnies * kPitch;
        out.push_back({.label = "elongation (%)", .value = 100.0 * ((endPoint - ceilingAnchor()).norm() - rest) / rest});
        out.push_back({.label = "substeps", .value = double(scene.world().settings().substeps), .format = "%.0f"});
        out.push_back({.label = "iterations", .value = double(scene.world().settings().iterations), .format = "%.0f"});
    }

  private:
    std::size_t solver_ = 0;
    std::size_t releaseAngle_ = 0;
    ecs::Entity end_;
};

}  // namespace

SceneEntry bunnyChainEntry() {
    return {.name = "bunny_chain",
            .description = "Figs. 10-11: 100 bunnies hanging from the ceiling as a chain",
            .build = buildBunnyChain,
            .paperMsPerFrame = 2.3,
            // The ceiling anchor to the last bunny's bottom anchor, kBunnies x kPitch at rest.
            .chain = {.endBody = "bunny100",
                      .anchor = {0.0, kCeilingHeight, 0.0},
                      .endPoint = {0.0, -kPitch / 2, 0.0},
                      .restLength = kBunnies * kPitch},
            .makeScript = []() -> std::unique_ptr<SceneScript> { return std::make_unique<BunnyChainScript>(); }};
}

}  // namespace substep::scenes
