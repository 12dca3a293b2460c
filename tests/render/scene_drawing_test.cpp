// Tests sandbox/scene_drawing.cpp: a scene's components become a RenderScene with every body's shape where
// the body is, each soft body's surface where its particles are, a ground under everything, a
// camera that sees the bodies, and debug lines for joints and their forces.

#include "scene_drawing.h"

#include "physics/collision/heightfield.h"
#include "physics/collision/spline_tube.h"
#include "ecs/components.h"
#include "ecs/soft_body_component.h"
#include "render/render_math.h"
#include "scenes/scene_registry.h"

#include <gtest/gtest.h>

namespace substep {
namespace {

std::size_t drawableBodies(const World& world) {
    std::size_t count = 0;
    for (std::size_t i = 1; i < world.bodies().size(); ++i) {
        const ShapeType type = world.bodies()[i].shape.type;
        if (world.bodies()[i].alive && type != ShapeType::Plane && type != ShapeType::None) ++count;
    }
    return count;
}

/// Where a world point lands in normalised device coordinates of the drawing's camera.
render::Vec3f project(const render::Camera& camera, float aspect, const render::Vec3f& point) {
    const render::Mat4f viewProjection = render::perspective(camera.fovY, aspect, 0.01f, 1000.0f) *
                                         render::lookAt(camera.position, camera.target, camera.up);
    const render::Vec4f clip = viewProjection * point.homogeneous();
    return clip.head<3>() / clip.w();
}

TEST(SceneDrawing, EveryBuiltinSceneShowsEachBodyAboveTheGround) {
    for (const SceneEntry& entry : builtinScenes()) {
        SCOPED_TRACE(std::string(entry.name));
        const SceneDescription description = entry.build();
        SceneInstance scene = buildScene(description);
        SceneDrawing drawing(description, scene, 4.0f / 3.0f);
        const render::RenderScene drawn = drawing.draw(scene);
        // Each soft body (the RC car's tyres) is drawn as one instance of its surface.
        EXPECT_EQ(drawn.instances.size(), drawableBodies(scene.world()) + scene.softBodyEntities.size());
        ASSERT_TRUE(drawn.ground.has_value());
        for (const render::RenderInstance& instance : drawn.instances) {
            EXPECT_GE(drawn.ground->normal.dot(instance.position), drawn.ground->offset);
        }
        if (description.camera) {
            EXPECT_TRUE(drawn.camera.position.isApprox(description.camera->position.cast<float>()));
        }
    }
}

TEST(SceneDrawing, InstancesFollowTheBodies) {
    const SceneDescription description = findBuiltinScene("pendula")->build();
    SceneInstance scene = buildScene(description);
    SceneDrawing drawing(description, scene, 1.0f);
    const render::RenderScene before = drawing.draw(scene);
    for (int i = 0; i < 30; ++i) scene.physics().step(description.dt);
    const render::RenderScene after = drawing.draw(scene);
    ASSERT_EQ(before.instances.size(), after.instances.size());
    float largestMove = 0.0f;
    for (std::size_t i = 0; i < before.instances.size(); ++i) {
        largestMove = std::max(largestMove, (after.instances[i].position - before.instances[i].position).norm());
    }
    EXPECT_GT(largestMove, 0.05f);
    // The camera is fixed for the whole rendering.
    EXPECT_TRUE(after.camera.position.isApprox(before.camera.position));
    // The instance is at the body's user frame, as `run --csv` reports it.
    const Body& body = scene.world().bodies()[1];
    EXPECT_TRUE(after.instances[0].position.isApprox(body.userPosition().cast<float>(), 1e-5f));
}

TEST(SceneDrawing, JointsGetFramesAndForces) {
    const SceneDescription description = findBuiltinScene("boxes3")->build();
    SceneInstance scene = buildScene(description);
    SceneDrawing drawing(description, scene, 1.0f);
    const std::size_t joints = description.joints.size();
    // Before any step: a link line and two three-axis frames per joint, no forces yet.
    EXPECT_EQ(drawing.draw(scene).lines.size(), joints * 7);
    scene.physics().step(description.dt);
    // After one: a spring that pulls (the world reports a force) holds its box up with an arrow
    // of three lines pointing up.
    const render::RenderScene drawn = drawing.draw(scene);
    std::size_t pulling = 0;
    for (const auto& [name, id] : scene.namedJointIds()) pulling += scene.world().jointReadout(id).force > 0.0 ? 1 : 0;
    ASSERT_EQ(drawn.lines.size(), joints * 7 + pulling * 3);
    for (std::size_t line = joints * 7; line < drawn.lines.size(); line += 3) {
        EXPECT_GT(drawn.lines[line].to.y() - drawn.lines[line].from.y(), 0.0f) << "arrow " << line;
    }
    SceneDrawing plain(description, scene, 1.0f, {.jointFrames = false, .jointForces = false});
    EXPECT_EQ(plain.draw(scene).lines.size(), joints);
}

TEST(SceneDrawing, DefaultCameraSeesEveryBody) {
    SceneDescription description = findBuiltinScene("pendula")->build();
    description.camera.reset();
    SceneInstance scene = buildScene(description);
    const float aspect = 16.0f / 9.0f;
    SceneDrawing drawing(description, scene, aspect);
    for (const render::RenderInstance& instance : drawing.draw(scene).instances) {
        const render::Vec3f ndc = project(drawing.camera(), aspect, instance.position);
        EXPECT_LT(std::abs(ndc.x()), 1.0f);
        EXPECT_LT(std::abs(ndc.y()), 1.0f);
    }
}

TEST(SceneDrawing, SplineTubesHeightfieldsAndMeshesBecomeMeshInstances) {
    SceneDescription description;
    const auto field = makeHeightfield(3, 2, {0, 0.5, 0, 0, 0.2, 0}, 2.0, 1.0);
    description.bodies.push_back({"", {.shape = heightfieldShape(field), .type = BodyType::Static}});
    const auto tube = makeSplineTube({Vec3(0, 1, 0), Vec3(1, 1.5, 0), Vec3(2, 1, 0)}, 0.05, false);
    description.bodies.push_back({"", {.shape = splineShape(tube), .type = BodyType::Static}});
    auto tetrahedron = std::make_shared<TriangleMesh>();
    tetrahedron->vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    tetrahedron->triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    Shape mesh{.type = ShapeType::Mesh, .mesh = tetrahedron};
    description.bodies.push_back({"", {.shape = mesh, .type = BodyType::Static, .position = Vec3(0, 2, 0)}});
    description.bodies.push_back({"", {.shape = mesh, .type = BodyType::Static, .position = Vec3(1, 2, 0)}});
    SceneInstance scene = buildScene(description);

    SceneDrawing drawing(description, scene, 1.0f);
    const render::RenderScene drawn = drawing.draw(scene);
    ASSERT_EQ(drawn.instances.size(), 4u);
    // The heightfield's grid is centred on its frame, as the physics has it.
    float lowestX = 1e9f;
    for (const render::MeshVertex& v : drawn.instances[0].mesh->vertices) lowestX = std::min(lowestX, v.position[0]);
    EXPECT_FLOAT_EQ(lowestX, -1.0f);
    for (const render::RenderInstance& instance : drawn.instances) {
        EXPECT_EQ(instance.kind, render::ShapeKind::Mesh);
        ASSERT_TRUE(instance.mesh);
        EXPECT_FALSE(instance.mesh->indices.empty());
    }
    // Bodies sharing a mesh share its render mesh (one instanced draw), frame after frame.
    EXPECT_EQ(drawn.instances[2].mesh, drawn.instances[3].mesh);
    EXPECT_EQ(drawing.draw(scene).instances[2].mesh, drawn.instances[2].mesh);
}

TEST(SceneDrawing, BodiesHaveDistinctColoursAndStaticOnesAreGrey) {
    EXPECT_FALSE(bodyColour(1, false).isApprox(bodyColour(2, false)));
    const render::Colour grey = bodyColour(5, true);
    EXPECT_NEAR(grey.x(), grey.z(), 0.1f);
}

}  // namespace
}  // namespace substep

namespace substep {
namespace {

TEST(SceneDrawing, ContactsAreArrowsAlongTheirNormalsWhenAskedFor) {
    const SceneEntry* entry = findBuiltinScene("stack10");
    if (entry == nullptr) GTEST_SKIP() << "no stack10 scene in this build";
    const SceneDescription description = entry->build();
    SceneInstance scene = buildScene(description);
    for (int i = 0; i < 5; ++i) scene.physics().step(description.dt);
    std::size_t points = 0;
    for (const ContactPair& pair : scene.world().contactPairs()) points += pair.count;
    const DrawingOptions contactsOnly{.jointFrames = false, .jointForces = false, .contacts = true};
    SceneDrawing drawing(description, scene, 1.0f, contactsOnly);
    // Per point a normal (a shaft and two barbs) and a cross (two strokes) at the point.
    EXPECT_EQ(drawing.draw(scene).lines.size(), points * 5);
    // Off by default.
    SceneDrawing plain(description, scene, 1.0f);
    EXPECT_EQ(plain.draw(scene).lines.size(), scene.world().joints().size() * 7);
}

TEST(SceneDrawing, BodyLayersAreOffByDefaultAndTheArrowScaleMultipliesEveryArrow) {
    const SceneEntry* entry = findBuiltinScene("stack10");
    if (entry == nullptr) GTEST_SKIP() << "no stack10 scene in this build";
    const SceneDescription description = entry->build();
    SceneInstance scene = buildScene(description);
    for (int i = 0; i < 5; ++i) scene.physics().step(description.dt);
    SceneDrawing drawing(description, scene, 1.0f);
    const DebugDrawOptions plain = drawing.debugOptions();
    for (const DebugLayer layer : {DebugLayer::Bounds, DebugLayer::CentreOfMass, DebugLayer::LinearVelocity,
                                   DebugLayer::AngularVelocity})
        EXPECT_EQ(plain.layers & debugLayerBit(layer), 0u);
    EXPECT_GT(plain.velocityScale, 0.0);
    EXPECT_GT(plain.angularVelocityScale, 0.0);

    // Every body's box: 12 edges for each of the 10 boxes (the ground plane has none).
    drawing.setOptions({.jointFrames = false, .jointForces = false, .bounds = true});
    EXPECT_EQ(drawing.draw(scene).lines.size(), 10u * 12u);
    drawing.setOptions({.velocities = true, .arrowScale = 3.0f});
    const DebugDrawOptions tripled = drawing.debugOptions();
    EXPECT_NE(tripled.layers & debugLayerBit(DebugLayer::LinearVelocity), 0u);
    EXPECT_NE(tripled.layers & debugLayerBit(DebugLayer::AngularVelocity), 0u);
    EXPECT_DOUBLE_EQ(tripled.forceScale, 3.0 * plain.forceScale);
    EXPECT_DOUBLE_EQ(tripled.torqueScale, 3.0 * plain.torqueScale);
    EXPECT_DOUBLE_EQ(tripled.velocityScale, 3.0 * plain.velocityScale);
    EXPECT_DOUBLE_EQ(tripled.angularVelocityScale, 3.0 * plain.angularVelocityScale);
    EXPECT_DOUBLE_EQ(tripled.longestArrow, 3.0 * plain.longestArrow) << "a longer arrow is not clipped back";
    drawing.setOptions({.arrowScale = 0.5f});
    EXPECT_DOUBLE_EQ(drawing.debugOptions().longestArrow, plain.longestArrow) << "shorter arrows keep the clip";
    drawing.setOptions({.arrowScale = -1.0f});
    EXPECT_DOUBLE_EQ(drawing.debugOptions().forceScale, plain.forceScale) << "a bad scale draws the scene's own";
}

}  // namespace
}  // namespace substep

namespace substep {
namespace {

// Drawn from a SceneInstance, bodies take the ECS look: a description's colour, a material
// changed at run time, a hidden body left out.
TEST(SceneDrawing, SceneInstanceBodiesWearTheirRenderMaterial) {
    SceneDescription description;
    description.bodies.push_back({"red", BodyDef{.shape = sphereShape(0.1), .mass = 1.0}, Vec3(1.0, 0.0, 0.0)});
    description.bodies.push_back({"plain", BodyDef{.shape = sphereShape(0.1), .mass = 1.0, .position = Vec3(1.0, 0.0, 0.0)}});
    SceneInstance scene = buildScene(description);
    SceneDrawing drawing(description, scene, 1.0f);

    render::RenderScene drawn = drawing.draw(scene);
    ASSERT_EQ(drawn.instances.size(), 2u);
    EXPECT_TRUE(drawn.instances[0].colour.isApprox(render::Colour(1.0f, 0.0f, 0.0f)));
    EXPECT_TRUE(drawn.instances[1].colour.isApprox(
        scene.registry.get<ecs::RenderMaterial>(scene.bodyEntities[1]).colour.cast<float>()));

    scene.registry.get<ecs::RenderMaterial>(scene.bodyEntities[1]).colour = Vec3(0.0, 0.0, 1.0);
    scene.registry.get<ecs::RenderMaterial>(scene.bodyEntities[0]).visible = false;
    drawn = drawing.draw(scene);
    ASSERT_EQ(drawn.instances.size(), 1u);
    EXPECT_TRUE(drawn.instances[0].colour.isApprox(render::Colour(0.0f, 0.0f, 1.0f)));
}

// The render system draws from components: a RenderMaterial's mesh is drawn instead of the
// collision shape, and a body moved through its Transform is drawn where it was put.
TEST(SceneDrawing, RenderMaterialMeshReplacesTheShapeAndTransformsPlaceBodies) {
    SceneDescription description;
    description.bodies.push_back({"ball", BodyDef{.shape = sphereShape(0.1), .mass = 1.0}});
    description.bodies.push_back({"mount", BodyDef{.shape = boxShape(Vec3(0.2, 0.2, 0.2)), .type = BodyType::Static,
                                                   .position = Vec3(0.0, 1.0, 0.0), .collide = false}});
    SceneInstance scene = buildScene(description);
    SceneDrawing drawing(description, scene, 1.0f);
    ASSERT_EQ(drawing.draw(scene).instances[0].kind, render::ShapeKind::Sphere);

    auto look = std::make_shared<TriangleMesh>();
    look->vertices = {Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0, 0.1, 0), Vec3(0, 0, 0.1)};
    look->triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    scene.registry.get<ecs::RenderMaterial>(scene.bodyEntities[0]).mesh = look;
    scene.registry.patch<ecs::Transform>(scene.bodyEntities[1],
                                         [](ecs::Transform& mount) { mount.position = Vec3(2.0, 1.0, 0.0); });
    scene.physics().step(1.0 / 60.0);
    const render::RenderScene drawn = drawing.draw(scene);
    ASSERT_EQ(drawn.instances.size(), 2u);
    EXPECT_EQ(drawn.instances[0].kind, render::ShapeKind::Mesh);
    ASSERT_TRUE(drawn.instances[0].mesh);
    EXPECT_EQ(drawn.instances[0].mesh->indices.size(), 12u);  // the material mesh's 4 triangles
    EXPECT_TRUE(drawn.instances[1].position.isApprox(render::Vec3f(2.0f, 1.0f, 0.0f)));
}

// A soft body is drawn as its lattice's surface, remade from the particles every frame: a box of
// nx x ny x nz cells has 2 (nx ny + ny nz + nz nx) boundary quads, two triangles each, every
// vertex on a particle, wound so each face looks away from the box.
TEST(SceneDrawing, ASoftBodyIsDrawnWhereItsParticlesAre) {
    SceneDescription description;
    description.bodies.push_back({"ground", BodyDef{.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static}});
    description.softBodies.push_back({.name = "jelly",
                                      .def = {.size = Vec3(0.6, 0.4, 0.8), .cells = {3, 2, 4},
                                              .position = Vec3(0.5, 1.0, -0.2), .compliance = 1e-6},
                                      .colour = Vec3(0.2, 0.8, 0.4)});
    SceneInstance scene = buildScene(description);
    SceneDrawing drawing(description, scene, 1.0f);
    const ecs::Entity jelly = scene.softBodyNamed("jelly");

    for (const int frames : {0, 20, 60}) {
        SCOPED_TRACE(frames);
        for (int i = 0; i < frames; ++i) scene.physics().step(description.dt);
        const render::RenderScene drawn = drawing.draw(scene);
        ASSERT_EQ(drawn.instances.size(), 1u);  // the plane is the ground
        const render::RenderInstance& instance = drawn.instances[0];
        ASSERT_EQ(instance.kind, render::ShapeKind::Mesh);
        ASSERT_NE(instance.mesh, nullptr);
        EXPECT_TRUE(instance.position.isZero());
        EXPECT_TRUE(instance.orientation.coeffs().isApprox(render::Quatf::Identity().coeffs()));
        EXPECT_TRUE(instance.colour.isApprox(render::Colour(0.2f, 0.8f, 0.4f)));

        constexpr std::size_t kQuads = 2 * (3 * 2 + 2 * 4 + 4 * 3);
        ASSERT_EQ(instance.mesh->indices.size(), kQuads * 2 * 3);
        // Every vertex on a particle of the current state.
        const std::span<const Vec3> particles = scene.physics().softBodyPositions(scene.registry.get<ecs::SoftBody>(jelly));
        ASSERT_EQ(particles.size(), 4u * 3u * 5u);
        Eigen::AlignedBox3f drawnBox;
        Vec3 centre = Vec3::Zero();
        for (const Vec3& p : particles) centre += p / static_cast<double>(particles.size());
        for (std::size_t v = 0; v < instance.mesh->vertices.size(); ++v) {
            const render::MeshVertex& vertex = instance.mesh->vertices[v];
            const render::Vec3f position(vertex.position[0], vertex.position[1], vertex.position[2]);
            drawnBox.extend(position);
            double nearest = 1e9;
            for (const Vec3& p : particles) nearest = std::min(nearest, (p.cast<float>() - position).norm() + 0.0);
            EXPECT_LT(nearest, 1e-6) << "vertex " << v;
            // Faces look outwards: away from the (convex, nearly undeformed) box's centre.
            const render::Vec3f normal(vertex.normal[0], vertex.normal[1], vertex.normal[2]);
            EXPECT_GT(normal.dot(position - centre.cast<float>()), 0.0f) << "vertex " << v;
        }
        // And the drawn surface spans the particles' extent, as the component's readout has it
        // (every particle of a 3 x 2 x 4 lattice but the 2 x 1 x 3 inside is on the surface).
        const SoftBodyReadout& readout = scene.registry.get<ecs::SoftBody>(jelly).readout;
        EXPECT_LT((drawnBox.sizes() - readout.extent.cast<float>()).norm(), 1e-5f);
        Eigen::AlignedBox3d particleBox;
        for (const Vec3& p : particles) particleBox.extend(p);
        EXPECT_LT((drawnBox.min() - particleBox.min().cast<float>()).norm(), 1e-5f);
    }

    // Hidden through its material, it is not drawn.
    scene.registry.get<ecs::RenderMaterial>(jelly).visible = false;
    EXPECT_TRUE(drawing.draw(scene).instances.empty());
}

}  // namespace
}  // namespace substep
