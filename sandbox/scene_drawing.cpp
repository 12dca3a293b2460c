#include "scene_drawing.h"

#include "ecs/components.h"
#include "ecs/physics_system.h"
#include "ecs/soft_body_component.h"
#include "physics/collision/heightfield.h"
#include "physics/collision/spline_tube.h"
#include "render/camera_framing.h"
#include "render/mesh_builders.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace substep {
namespace {

render::Vec3f toFloat(const Vec3& v) { return v.cast<float>(); }

/// Extent of a body's shape about its frame's origin (m), for framing and floors.
double shapeRadius(const Shape& shape) {
    switch (shape.type) {
        case ShapeType::Sphere: return shape.radius;
        case ShapeType::Box: return shape.size.norm() / 2.0;
        case ShapeType::Capsule: return shape.radius + shape.length / 2.0;
        case ShapeType::Cylinder: return std::hypot(shape.radius, shape.length / 2.0);
        case ShapeType::Mesh:
        case ShapeType::Heightfield:
        case ShapeType::Spline:
            if (shape.localBounds.min.allFinite() && shape.localBounds.max.allFinite()) {
                return std::max(shape.localBounds.min.norm(), shape.localBounds.max.norm());
            }
            return 0.0;
        default: return 0.0;
    }
}

/// Calls visit(entity, transform, collider) for every entity with a Transform and a Collider,
/// in the order their bodies were made (the RigidBody pool's, then any others).
template <class Visit>
void forEachShape(const ecs::Registry& registry, Visit&& visit) {
    const ecs::ComponentPool<ecs::Collider>* colliders = registry.findPool<ecs::Collider>();
    const ecs::ComponentPool<ecs::Transform>* transforms = registry.findPool<ecs::Transform>();
    if (colliders == nullptr || transforms == nullptr) return;
    const std::span<const ecs::Entity> entities = colliders->entities();
    const std::span<const ecs::Collider> components = colliders->components();
    for (std::size_t i = 0; i < components.size(); ++i)
        if (const ecs::Transform* transform = transforms->tryGet(entities[i]))
            visit(entities[i], *transform, components[i]);
}

/// Bounds of every shape but planes, on the current state.
Eigen::AlignedBox3d bodyBounds(const ecs::Registry& registry) {
    Eigen::AlignedBox3d box;
    forEachShape(registry, [&](ecs::Entity, const ecs::Transform& transform, const ecs::Collider& collider) {
        if (collider.shape.type == ShapeType::Plane) return;
        const double radius = shapeRadius(collider.shape);
        box.extend(transform.position - Vec3::Constant(radius));
        box.extend(transform.position + Vec3::Constant(radius));
    });
    if (const ecs::ComponentPool<ecs::SoftBody>* softBodies = registry.findPool<ecs::SoftBody>()) {
        for (const ecs::SoftBody& softBody : softBodies->components()) {
            if (softBody.id.isNull()) continue;
            box.extend(softBody.readout.centreOfMass - softBody.readout.extent / 2.0);
            box.extend(softBody.readout.centreOfMass + softBody.readout.extent / 2.0);
        }
    }
    return box;
}

/// Grid lines at a power of ten that suits the scene's size.
float gridSpacingFor(double size) {
    return static_cast<float>(std::pow(10.0, std::floor(std::log10(std::max(size, 0.1)))));
}

/// Colours of the debug layers: joint axes a, b, c red, green, blue as in every DCC tool.
render::Colour debugColour(const DebugSegment& segment) {
    switch (segment.layer) {
        case DebugLayer::JointLink: return {0.95f, 0.85f, 0.30f};
        case DebugLayer::JointFrame: {
            const render::Colour axes[3] = {{0.9f, 0.2f, 0.2f}, {0.2f, 0.8f, 0.2f}, {0.25f, 0.4f, 1.0f}};
            return axes[std::min<int>(segment.part, 2)];
        }
        case DebugLayer::JointLimit: return {0.35f, 0.85f, 0.95f};
        case DebugLayer::JointForce: return {0.85f, 0.30f, 0.85f};
        case DebugLayer::JointTorque: return {0.95f, 0.55f, 0.15f};
        case DebugLayer::Contact:
            return segment.part == 1 ? render::Colour{1.0f, 1.0f, 0.55f} : render::Colour{1.0f, 0.35f, 0.2f};
        case DebugLayer::Bounds: return {0.45f, 0.95f, 0.45f};
        case DebugLayer::CentreOfMass: return {1.0f, 1.0f, 1.0f};
        case DebugLayer::LinearVelocity: return {0.3f, 0.9f, 1.0f};
        case DebugLayer::AngularVelocity: return {1.0f, 0.45f, 0.75f};
    }
    return {1.0f, 1.0f, 1.0f};
}

}  // namespace

render::Camera renderCamera(const SceneCamera& camera) {
    return {.position = toFloat(camera.position),
            .target = toFloat(camera.target),
            .up = render::Vec3f::UnitY(),
            .fovY = static_cast<float>(camera.fov)};
}

render::Colour bodyColour(std::size_t index, bool isStatic) {
    if (isStatic) return {0.55f, 0.56f, 0.60f};
    // Warm and cool colours alternating, saturated enough to tell neighbours apart.
    static constexpr std::array<std::array<float, 3>, 8> kPalette{{
        {0.90f, 0.45f, 0.25f},  // orange
        {0.25f, 0.55f, 0.85f},  // blue
        {0.95f, 0.75f, 0.25f},  // yellow
        {0.40f, 0.70f, 0.40f},  // green
        {0.85f, 0.35f, 0.45f},  // red
        {0.55f, 0.45f, 0.80f},  // violet
        {0.30f, 0.75f, 0.75f},  // teal
        {0.85f, 0.60f, 0.45f},  // sand
    }};
    const auto& c = kPalette[(index + kPalette.size() - 1) % kPalette.size()];
    return {c[0], c[1], c[2]};
}

SceneDrawing::SceneDrawing(const SceneDescription& description, SceneInstance& sceneInstance, float aspect,
                           const DrawingOptions& options)
    : options_(options) {
    const ecs::Registry& registry = sceneInstance.registry;
    const Eigen::AlignedBox3d box = bodyBounds(registry);
    const Vec3 centre = box.isEmpty() ? Vec3(Vec3::Zero()) : Vec3(box.center());
    const double radius = box.isEmpty() ? 1.0 : std::max(box.diagonal().norm() / 2.0, 0.05);

    if (description.camera) {
        camera_ = renderCamera(*description.camera);
    } else {
        camera_ = render::framingCamera(toFloat(centre), static_cast<float>(radius), 0.8f, aspect);
    }

    // The scene's own plane is the ground; without one a reference floor sits at y = 0, or under
    // the lowest body if something starts below that.
    forEachShape(registry, [&](ecs::Entity, const ecs::Transform&, const ecs::Collider& collider) {
        if (ground_ || collider.shape.type != ShapeType::Plane) return;
        ground_ = render::Ground{.normal = toFloat(collider.shape.normal.normalized()),
                                 .offset = static_cast<float>(collider.shape.offset)};
    });
    if (!ground_) {
        const double lowest = box.isEmpty() ? 0.0 : box.min().y();
        ground_ = render::Ground{.normal = render::Vec3f::UnitY(),
                                 .offset = static_cast<float>(std::min(0.0, lowest - 0.1 * radius))};
    }
    ground_->gridSpacing = gridSpacingFor(radius);

    // Overlays are sized to the bodies as well as to the scene, so a rope of thin capsules is not
    // buried under its own joint frames: the median body's size caps them.
    std::vector<double> bodySizes;
    forEachShape(registry, [&](ecs::Entity, const ecs::Transform&, const ecs::Collider& collider) {
        if (collider.shape.type != ShapeType::Plane && shapeRadius(collider.shape) > 0.0)
            bodySizes.push_back(shapeRadius(collider.shape));
    });
    double medianSize = radius;
    if (!bodySizes.empty()) {
        std::nth_element(bodySizes.begin(), bodySizes.begin() + bodySizes.size() / 2, bodySizes.end());
        medianSize = bodySizes[bodySizes.size() / 2];
    }
    markerLength_ = static_cast<float>(std::min(0.06 * radius, 0.8 * medianSize));
    // Forces: the heaviest moving body's weight is drawn a tenth of the scene's size long, and no
    // arrow is longer than a quarter of it (a whipping pendulum pulls many times its weight).
    double heaviestWeight = 0.0;
    const double gravity = sceneInstance.physics().settings().gravity.norm();
    sceneInstance.registry.view<ecs::RigidBody>().each([&](const ecs::RigidBody& body) {
        heaviestWeight = std::max(heaviestWeight, body.simulatedMass * gravity);
    });
    forceScale_ = heaviestWeight > 0.0 ? static_cast<float>(0.1 * radius / heaviestWeight) : 0.0f;
    longestArrow_ = static_cast<float>(std::min(0.25 * radius, 3.0 * medianSize));
    // Torques: the heaviest weight at the scene's size, drawn as long as its weight's arrow.
    torqueScale_ = heaviestWeight > 0.0 ? forceScale_ / static_cast<float>(radius) : 0.0f;
    // Velocities: the speed of a fall through the scene's size, sqrt(g R), is drawn a quarter of
    // that size long; a turn rate of sqrt(g / R) (a pendulum of the scene's size) likewise.
    const double g = gravity > 0.0 ? gravity : 10.0;
    velocityScale_ = static_cast<float>(0.25 * radius / std::sqrt(g * radius));
    angularVelocityScale_ = static_cast<float>(0.25 * radius / std::sqrt(g / radius));
}

DebugDrawOptions SceneDrawing::debugOptions() const {
    uint32_t layers = 0;
    // A joint's link always shows: its length is the spring's stretch or the joint's error.
    layers |= debugLayerBit(DebugLayer::JointLink);
    if (options_.jointFrames) layers |= debugLayerBit(DebugLayer::JointFrame) | debugLayerBit(DebugLayer::JointLimit);
    if (options_.jointForces) layers |= debugLayerBit(DebugLayer::JointForce);
    if (options_.jointTorques) layers |= debugLayerBit(DebugLayer::JointTorque);
    if (options_.contacts) layers |= debugLayerBit(DebugLayer::Contact);
    if (options_.bounds) layers |= debugLayerBit(DebugLayer::Bounds);
    if (options_.centresOfMass) layers |= debugLayerBit(DebugLayer::CentreOfMass);
    if (options_.velocities)
        layers |= debugLayerBit(DebugLayer::LinearVelocity) | debugLayerBit(DebugLayer::AngularVelocity);
    // A non-finite or non-positive scale from a caller draws the scene's own.
    const double scale = options_.arrowScale > 0.0f && std::isfinite(options_.arrowScale) ? options_.arrowScale : 1.0;
    return {.layers = layers,
            .markerLength = markerLength_,
            .forceScale = scale * forceScale_,
            .torqueScale = scale * torqueScale_,
            .velocityScale = scale * velocityScale_,
            .angularVelocityScale = scale * angularVelocityScale_,
            .longestArrow = std::max(scale, 1.0) * longestArrow_};
}

render::RenderScene SceneDrawing::draw(SceneInstance& sceneInstance) {
    render::RenderScene scene;
    scene.camera = camera_;
    scene.ground = ground_;
    addBodies(sceneInstance.registry, scene);
    addSoftBodies(sceneInstance.physics(), scene);
    addDebugLines(sceneInstance.physics(), scene);
    return scene;
}

std::shared_ptr<const render::MeshData> SceneDrawing::meshFor(const std::shared_ptr<const TriangleMesh>& source) {
    if (const auto found = meshes_.find(source.get()); found != meshes_.end()) return found->second;
    std::vector<render::Vec3f> points;
    points.reserve(source->vertices.size());
    for (const Vec3& v : source->vertices) points.push_back(toFloat(v));
    std::vector<uint32_t> triangles;
    triangles.reserve(source->triangles.size() * 3);
    for (const auto& t : source->triangles) {
        triangles.insert(triangles.end(), {static_cast<uint32_t>(t[0]), static_cast<uint32_t>(t[1]),
                                           static_cast<uint32_t>(t[2])});
    }
    auto mesh = std::make_shared<render::MeshData>(render::flatShadedMesh(points, triangles));
    meshes_.emplace(source.get(), mesh);
    return mesh;
}

std::shared_ptr<const render::MeshData> SceneDrawing::meshFor(const Shape& shape) {
    const void* source = nullptr;
    if (shape.type == ShapeType::Mesh) source = shape.mesh.get();
    if (shape.type == ShapeType::Spline) source = shape.spline.get();
    if (shape.type == ShapeType::Heightfield) source = shape.heightfield.get();
    if (source == nullptr) return nullptr;
    if (shape.type == ShapeType::Mesh) return meshFor(shape.mesh);
    if (const auto found = meshes_.find(source); found != meshes_.end()) return found->second;

    auto mesh = std::make_shared<render::MeshData>();
    if (shape.type == ShapeType::Heightfield) {
        const HeightfieldData& field = *shape.heightfield;
        const std::vector<float> heights(field.heights.begin(), field.heights.end());
        *mesh = render::heightfieldMesh(
            field.columns, field.rows,
            render::Vec2f(static_cast<float>(-0.5 * field.sizeX), static_cast<float>(-0.5 * field.sizeZ)),
            render::Vec2f(static_cast<float>(field.cellX()), static_cast<float>(field.cellZ())), heights);
    } else {
        // The tube's curve sampled finely enough that its polyline looks smooth.
        const SplineTube& tube = *shape.spline;
        std::vector<render::Vec3f> centres;
        constexpr int kSamplesPerSegment = 12;
        for (std::size_t s = 0; s < tube.segments.size(); ++s) {
            const bool lastOfOpen = !tube.closed && s + 1 == tube.segments.size();
            const int samples = kSamplesPerSegment + (lastOfOpen ? 1 : 0);
            for (int i = 0; i < samples; ++i) {
                centres.push_back(toFloat(tube.segments[s].point(static_cast<double>(i) / kSamplesPerSegment)));
            }
        }
        if (tube.segments.empty() && !tube.points.empty()) centres.push_back(toFloat(tube.points.front()));
        *mesh = render::tubeMesh(centres, static_cast<float>(tube.radius), tube.closed);
    }
    meshes_.emplace(source, mesh);
    return mesh;
}

void SceneDrawing::addBodies(const ecs::Registry& registry, render::RenderScene& scene) {
    forEachShape(registry, [&](ecs::Entity entity, const ecs::Transform& transform, const ecs::Collider& collider) {
        const ecs::RenderMaterial* material = registry.tryGet<ecs::RenderMaterial>(entity);
        if (material != nullptr && !material->visible) return;
        const ecs::RigidBody* rigidBody = registry.tryGet<ecs::RigidBody>(entity);
        const bool isStatic = rigidBody == nullptr || rigidBody->type == BodyType::Static;
        render::RenderInstance instance{
            .position = toFloat(transform.position),
            .orientation = transform.rotation.cast<float>(),
            .colour = material != nullptr ? render::Colour(material->colour.cast<float>())
                                          : bodyColour(entity.index + 1, isStatic)};
        // A material's own mesh is a finer look than the collision shape: it wins.
        if (material != nullptr && material->mesh) {
            instance.kind = render::ShapeKind::Mesh;
            instance.mesh = meshFor(material->mesh);
            scene.instances.push_back(std::move(instance));
            return;
        }
        const Shape& shape = collider.shape;
        switch (shape.type) {
            case ShapeType::Sphere:
                instance.kind = render::ShapeKind::Sphere;
                instance.dimensions = render::Vec3f::Constant(static_cast<float>(shape.radius));
                break;
            case ShapeType::Box:
                instance.kind = render::ShapeKind::Box;
                instance.dimensions = toFloat(shape.size);
                break;
            case ShapeType::Capsule:
                instance.kind = render::ShapeKind::Capsule;
                instance.dimensions = render::Vec3f(static_cast<float>(shape.radius),
                                                    static_cast<float>(shape.length), 0.0f);
                break;
            case ShapeType::Cylinder:
                instance.kind = render::ShapeKind::Cylinder;
                instance.dimensions = render::Vec3f(static_cast<float>(shape.radius),
                                                    static_cast<float>(shape.length), 0.0f);
                break;
            case ShapeType::Mesh:
            case ShapeType::Heightfield:
            case ShapeType::Spline:
                instance.kind = render::ShapeKind::Mesh;
                instance.mesh = meshFor(shape);
                if (!instance.mesh) return;
                break;
            default: return;  // planes are the ground; shapeless bodies have nothing to show
        }
        scene.instances.push_back(std::move(instance));
    });
}

void SceneDrawing::addSoftBodies(const ecs::PhysicsSystem& physics, render::RenderScene& scene) {
    const ecs::Registry& registry = physics.registry();
    const ecs::ComponentPool<ecs::SoftBody>* softBodies = registry.findPool<ecs::SoftBody>();
    if (softBodies == nullptr) return;
    const std::span<const ecs::Entity> entities = softBodies->entities();
    const std::span<const ecs::SoftBody> components = softBodies->components();
    for (std::size_t i = 0; i < components.size(); ++i) {
        const ecs::RenderMaterial* material = registry.tryGet<ecs::RenderMaterial>(entities[i]);
        if (material != nullptr && !material->visible) continue;
        // The surface moves with every particle: its mesh is made afresh each frame, in world
        // coordinates (the instance's frame is the identity).
        const SoftSurface surface = physics.softBodySurface(components[i]);
        if (surface.triangles.empty()) continue;
        softPoints_.clear();
        for (const Vec3& p : surface.positions) softPoints_.push_back(toFloat(p));
        softIndices_.clear();
        for (const auto& t : surface.triangles) softIndices_.insert(softIndices_.end(), t.begin(), t.end());
        render::RenderInstance instance{
            .kind = render::ShapeKind::Mesh,
            .mesh = std::make_shared<render::MeshData>(render::flatShadedMesh(softPoints_, softIndices_)),
            .colour = material != nullptr ? render::Colour(material->colour.cast<float>())
                                          : bodyColour(entities[i].index + 1, false)};
        scene.instances.push_back(std::move(instance));
    }
}

void SceneDrawing::addDebugLines(const ecs::PhysicsSystem& physics, render::RenderScene& scene) {
    debugList_.clear();
    physics.debugDraw(debugOptions(), debugList_);
    for (const DebugSegment& segment : debugList_.segments)
        scene.lines.push_back({toFloat(segment.from), toFloat(segment.to), debugColour(segment)});
}

}  // namespace substep
