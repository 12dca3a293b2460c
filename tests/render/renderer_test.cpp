// Tests engine/render/renderer.cpp (with offscreen_target.cpp): frames drawn headless on EGL
// (OSMesa where EGL is missing) have the requested size, show the scene, and repeat exactly.

#include "render/offscreen_target.h"
#include "render/renderer.h"
#include "render_test_support.h"

#include <gtest/gtest.h>

namespace substep::render {
namespace {

/// A small still life: a box, a sphere and a capsule on the ground, with two debug lines.
RenderScene stillLife() {
    RenderScene scene;
    scene.camera = {.position = Vec3f(0.0f, 1.2f, 3.0f), .target = Vec3f(0.0f, 0.3f, 0.0f)};
    scene.ground = Ground{};
    scene.instances.push_back({.kind = ShapeKind::Box, .dimensions = Vec3f(0.4f, 0.4f, 0.4f),
                               .position = Vec3f(-0.7f, 0.2f, 0.0f), .colour = Colour(0.25f, 0.55f, 0.85f)});
    scene.instances.push_back({.kind = ShapeKind::Sphere, .dimensions = Vec3f::Constant(0.3f),
                               .position = Vec3f(0.0f, 0.3f, 0.0f), .colour = Colour(0.95f, 0.75f, 0.25f)});
    scene.instances.push_back({.kind = ShapeKind::Capsule, .dimensions = Vec3f(0.15f, 0.4f, 0.0f),
                               .position = Vec3f(0.7f, 0.35f, 0.0f), .colour = Colour(0.85f, 0.35f, 0.45f)});
    scene.lines.push_back({Vec3f(0.0f, 0.0f, 0.0f), Vec3f(0.0f, 1.0f, 0.0f), Colour(1.0f, 0.0f, 0.0f)});
    return scene;
}

Image draw(GlContext& context, const RenderScene& scene, PixelSize size) {
    const GlApi gl = context.loadApi();
    Renderer renderer(gl);
    OffscreenTarget target(gl, size);
    renderer.render(scene, target.target());
    return target.readPixels();
}

TEST(Renderer, ImageHasTheRequestedSize) {
    SUBSTEP_REQUIRE_CONTEXT(context);
    const Image image = draw(*context, stillLife(), {200, 90});
    EXPECT_EQ(image.width, 200);
    EXPECT_EQ(image.height, 90);
    EXPECT_EQ(image.rgba.size(), 200u * 90u * 4u);
}

TEST(Renderer, FrameShowsTheSceneNotJustSky) {
    SUBSTEP_REQUIRE_CONTEXT(context);
    const Image withShapes = draw(*context, stillLife(), {160, 120});
    RenderScene empty = stillLife();
    empty.instances.clear();
    empty.lines.clear();
    empty.ground.reset();
    const Image skyOnly = draw(*context, empty, {160, 120});

    EXPECT_GT(test::distinctColours(withShapes), 200u);
    // The shapes and the ground cover a good part of the frame.
    EXPECT_GT(test::fractionDiffering(withShapes, skyOnly, 16), 0.3);
    // The sphere's colour (warm yellow) is at the centre of the frame.
    const uint8_t* centre = withShapes.pixel(80, 60);
    EXPECT_GT(centre[0], centre[2] + 40) << "expected the yellow sphere at the image centre";
}

TEST(Renderer, SameSceneGivesTheSameBytes) {
    SUBSTEP_REQUIRE_CONTEXT(context);
    const RenderScene scene = stillLife();
    const GlApi gl = context->loadApi();
    Renderer renderer(gl);
    OffscreenTarget target(gl, {160, 120});
    renderer.render(scene, target.target());
    const Image first = target.readPixels();
    // A different frame in between must leave no trace (no state carried between frames).
    RenderScene other = scene;
    other.instances[1].position.x() += 0.5f;
    renderer.render(other, target.target());
    renderer.render(scene, target.target());
    const Image second = target.readPixels();
    EXPECT_TRUE(first.rgba == second.rgba);
}

TEST(Renderer, MovingAShapeChangesTheImage) {
    SUBSTEP_REQUIRE_CONTEXT(context);
    RenderScene scene = stillLife();
    const Image before = draw(*context, scene, {160, 120});
    scene.instances[0].position.y() += 0.5f;
    const Image after = draw(*context, scene, {160, 120});
    EXPECT_GT(test::fractionDiffering(before, after, 16), 0.01);
}

TEST(Renderer, MeshInstancesAreDrawn) {
    SUBSTEP_REQUIRE_CONTEXT(context);
    RenderScene scene = stillLife();
    scene.instances.clear();
    const Image empty = draw(*context, scene, {160, 120});
    // A tetrahedron as a mesh instance, shared by two instances (one instanced draw).
    auto tetrahedron = std::make_shared<MeshData>();
    const Vec3f corners[4] = {{0.4f, 0, 0}, {-0.3f, 0, 0.3f}, {-0.3f, 0, -0.3f}, {0, 0.5f, 0}};
    const uint32_t faces[12] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3};
    for (int f = 0; f < 4; ++f) {
        const Vec3f& a = corners[faces[3 * f]];
        const Vec3f& b = corners[faces[3 * f + 1]];
        const Vec3f& c = corners[faces[3 * f + 2]];
        const Vec3f n = (b - a).cross(c - a).normalized();
        for (const Vec3f* p : {&a, &b, &c}) {
            tetrahedron->indices.push_back(static_cast<uint32_t>(tetrahedron->vertices.size()));
            tetrahedron->vertices.push_back({{p->x(), p->y(), p->z()}, {n.x(), n.y(), n.z()}});
        }
    }
    scene.instances.push_back({.kind = ShapeKind::Mesh, .mesh = tetrahedron, .position = Vec3f(-0.5f, 0, 0)});
    scene.instances.push_back({.kind = ShapeKind::Mesh, .mesh = tetrahedron, .position = Vec3f(0.5f, 0, 0)});
    const Image withMeshes = draw(*context, scene, {160, 120});
    EXPECT_GT(test::fractionDiffering(withMeshes, empty, 16), 0.005);
}

TEST(OffscreenTarget, RejectsASizeTheDeviceCannotAllocate) {
    SUBSTEP_REQUIRE_CONTEXT(context);
    const GlApi gl = context->loadApi();
    EXPECT_THROW(OffscreenTarget(gl, {1 << 20, 16}), std::runtime_error);
    EXPECT_THROW(OffscreenTarget(gl, {0, 16}), std::runtime_error);
}

}  // namespace
}  // namespace substep::render
