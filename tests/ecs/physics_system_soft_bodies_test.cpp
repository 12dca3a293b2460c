// Tests engine/ecs/physics_system.cpp's soft bodies: SoftBody components become world soft bodies
// (after rigid bodies, since attachments name body entities), their readouts are written back
// after every step (the volume on demand: softBodyReadout), and destroy() removes them. Physics against closed forms: a free soft box
// falls at g (symplectic Euler's y0 − g t²/2 − g t h/2 exactly, with h the substep), rigidly
// (extent and volume kept); a hard attachment to a static body holds it where it was made.

#include "ecs/body_components.h"
#include "ecs/components.h"
#include "ecs/physics_system.h"
#include "ecs/registry.h"
#include "ecs/soft_body_component.h"
#include "physics/world.h"

#include <gtest/gtest.h>

#include <cmath>

namespace substep::ecs {
namespace {

constexpr double kG = 9.81;
constexpr double kDt = 1.0 / 60.0;
constexpr int kSubsteps = 20;

struct SoftScene {
    Registry registry;
    World world{WorldSettings{.gravity = Vec3(0, -kG, 0), .substeps = kSubsteps, .iterations = 1}};
    PhysicsSystem physics() { return PhysicsSystem(registry, world); }
    void run(int frames) {
        for (int frame = 0; frame < frames; ++frame) physics().step(kDt);
    }
};

SoftBodyDef softBox(const Vec3& position, const Vec3& size, std::array<int, 3> cells) {
    return SoftBodyDef{.type = SoftBodyType::Box, .size = size, .cells = cells, .position = position,
                       .compliance = 1e-6};
}

TEST(PhysicsSystemSoftBodies, AFreeSoftBoxFallsAtGAndItsReadoutFollows) {
    // Over sizes, cells and heights not tuned for: each box falls as a whole at g.
    struct Case {
        Vec3 position, size;
        std::array<int, 3> cells;
    };
    for (const Case& c : {Case{Vec3(0, 2, 0), Vec3(0.4, 0.4, 0.4), {4, 4, 4}},
                          Case{Vec3(3, 50, -1), Vec3(2.0, 0.1, 0.5), {7, 1, 3}}}) {
        SoftScene scene;
        const Entity box = scene.registry.create();
        scene.registry.emplace<SoftBody>(box, SoftBody{.def = softBox(c.position, c.size, c.cells)});
        scene.physics().sync();
        const SoftBody& soft = scene.registry.get<SoftBody>(box);
        ASSERT_TRUE(scene.world.isValid(soft.id));
        // Written at creation: the lattice's centre, its size, its volume.
        EXPECT_LT((soft.readout.centreOfMass - c.position).norm(), 1e-12);
        EXPECT_LT((soft.readout.extent - c.size).norm(), 1e-12);
        EXPECT_NEAR(soft.readout.volume, c.size.prod(), 1e-12 * c.size.prod());

        constexpr int kFrames = 30;
        scene.run(kFrames);
        const double t = kFrames * kDt, h = kDt / kSubsteps;
        // Symplectic Euler over n substeps: v = −g n h, y = y0 − g h² n (n + 1) / 2.
        // (v = Δx / h turns the positions' rounding at 50 m into ~1e-9 m/s.)
        EXPECT_NEAR(soft.readout.velocity.y(), -kG * t, 1e-7);
        EXPECT_NEAR(soft.readout.centreOfMass.y(), c.position.y() - kG * t * t / 2.0 - kG * t * h / 2.0, 1e-9);
        // Within the method's discrete error of the closed form y0 − g t²/2.
        EXPECT_LE(std::abs(soft.readout.centreOfMass.y() - (c.position.y() - kG * t * t / 2.0)), kG * t * h);
        EXPECT_NEAR(soft.readout.centreOfMass.x(), c.position.x(), 1e-12);
        EXPECT_NEAR(soft.readout.velocity.x(), 0.0, 1e-12);
        EXPECT_LT((soft.readout.extent - c.size).norm(), 1e-9);
        // The volume on demand (the step's readout leaves it out).
        EXPECT_NEAR(softBodyReadout(scene.world, soft).volume, c.size.prod(), 1e-9 * c.size.prod());
    }
}

TEST(PhysicsSystemSoftBodies, TheStepsReadoutLeavesTheVolumeToSoftBodyReadout) {
    // After a step the component's readout is the world's, bit for bit, but for the volume,
    // which is NaN (a reader who forgot it shows) until softBodyReadout computes it: a sheared
    // box of 2 x 1 x 3 cells whose volume is its rest volume to rounding, and after a squeeze
    // against the ground, less.
    SoftScene scene;
    const Entity floor = scene.registry.create();
    emplaceBody(scene.registry, floor,
                {.shape = boxShape(Vec3(4, 0.2, 4)), .type = BodyType::Static, .position = Vec3(0, -0.1, 0)});
    const Entity box = scene.registry.create();
    const Vec3 size(0.3, 0.2, 0.45);
    SoftBodyDef def = softBox(Vec3(0.1, 0.5, -0.2), size, {2, 1, 3});
    def.compliance = 1e-4;  // soft: it squashes where it lands
    scene.registry.emplace<SoftBody>(box, SoftBody{.def = def});
    scene.run(1);
    const SoftBody& soft = scene.registry.get<SoftBody>(box);
    ASSERT_TRUE(std::isnan(soft.readout.volume));
    const SoftBodyReadout whole = softBodyReadout(scene.world, soft);
    EXPECT_NEAR(whole.volume, size.prod(), 1e-9 * size.prod());
    const SoftBodyReadout direct = scene.world.softBodyReadout(soft.id);
    EXPECT_EQ(whole.volume, direct.volume);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_EQ(soft.readout.centreOfMass[axis], direct.centreOfMass[axis]);
        EXPECT_EQ(soft.readout.velocity[axis], direct.velocity[axis]);
        EXPECT_EQ(soft.readout.extent[axis], direct.extent[axis]);
    }
    EXPECT_EQ(soft.readout.mass, direct.mass);
    EXPECT_EQ(soft.readout.particles, 24);
    EXPECT_EQ(soft.readout.elements, 6);
    // Landed and squashed under its weight: the on-demand volume follows the current shape.
    scene.run(90);
    EXPECT_TRUE(std::isnan(soft.readout.volume));
    EXPECT_LT(softBodyReadout(scene.world, soft).volume, size.prod() * (1.0 - 1e-4));
    EXPECT_GT(softBodyReadout(scene.world, soft).volume, 0.5 * size.prod());
    // A destroyed soft body reads zeros, as writeBack writes them.
    scene.physics().destroy(box);
    EXPECT_EQ(softBodyReadout(scene.world, SoftBody{}).volume, 0.0);
}

TEST(PhysicsSystemSoftBodies, AHardAttachmentHoldsTheBoxAndWaitsForItsBody) {
    SoftScene scene;
    // The soft body's component comes first: it must wait for the body it attaches to.
    const Entity soft = scene.registry.create();
    SoftBodyDef def = softBox(Vec3(0, 1, 0), Vec3(0.3, 0.3, 0.3), {3, 3, 3});
    def.attachments.push_back({.particles = SoftAttachmentParticles::Below});
    const Entity mount = scene.registry.create();
    scene.registry.emplace<SoftBody>(soft, SoftBody{.def = def, .attachedBodies = {mount}});
    scene.physics().sync();
    EXPECT_TRUE(scene.registry.get<SoftBody>(soft).id.isNull()) << "created before the body it attaches to";

    // A static slab through the box's top layer of particles holds them.
    emplaceBody(scene.registry, mount,
                {.shape = boxShape(Vec3(1, 0.02, 1)), .type = BodyType::Static, .position = Vec3(0, 1.15, 0)});
    scene.run(60);
    const SoftBody& held = scene.registry.get<SoftBody>(soft);
    ASSERT_TRUE(scene.world.isValid(held.id));
    // Free, it would have fallen 4.9 m; held by its top, it hangs and sags under its weight.
    EXPECT_GT(held.readout.centreOfMass.y(), 0.9);
    EXPECT_LT(held.readout.centreOfMass.y(), 1.0);

    // Destroying the mount releases the box (the world drops the attachment): it falls.
    scene.physics().destroy(mount);
    const double before = held.readout.centreOfMass.y();
    scene.run(30);
    EXPECT_LT(held.readout.centreOfMass.y(), before - 1.0);
}

TEST(PhysicsSystemSoftBodies, APatchedSoftBodyChangesNothingAndLeavesNoBacklog) {
    SoftScene scene;
    const Entity box = scene.registry.create();
    scene.registry.emplace<SoftBody>(box, SoftBody{.def = softBox(Vec3(0, 1, 0), Vec3(0.2, 0.2, 0.2), {2, 2, 2})});
    scene.run(1);
    const SoftBodyId id = scene.registry.get<SoftBody>(box).id;
    scene.registry.patch<SoftBody>(box, [](SoftBody& soft) { soft.def.velocity = Vec3(0, 100, 0); });
    scene.run(1);
    EXPECT_EQ(scene.registry.get<SoftBody>(box).id, id);
    EXPECT_NEAR(scene.registry.get<SoftBody>(box).readout.velocity.y(), -kG * 2 * kDt, 1e-9);
    EXPECT_FALSE(scene.registry.findPool<SoftBody>()->anyChanged());
}

TEST(PhysicsSystemSoftBodies, DestroyRemovesTheSoftBody) {
    SoftScene scene;
    const Entity a = scene.registry.create();
    const Entity b = scene.registry.create();
    scene.registry.emplace<SoftBody>(a, SoftBody{.def = softBox(Vec3(0, 1, 0), Vec3(0.2, 0.2, 0.2), {2, 2, 2})});
    scene.registry.emplace<SoftBody>(b, SoftBody{.def = softBox(Vec3(2, 1, 0), Vec3(0.2, 0.2, 0.2), {2, 2, 2})});
    scene.run(1);
    const SoftBodyId idA = scene.registry.get<SoftBody>(a).id;
    ASSERT_TRUE(scene.world.isValid(idA));
    scene.physics().destroy(a);
    EXPECT_FALSE(scene.registry.isValid(a));
    EXPECT_FALSE(scene.world.isValid(idA));
    // The other keeps falling at g from where it was, its readout still written.
    scene.run(29);
    const SoftBody& left = scene.registry.get<SoftBody>(b);
    const double t = 30 * kDt, h = kDt / kSubsteps;
    EXPECT_NEAR(left.readout.centreOfMass.y(), 1.0 - kG * t * t / 2.0 - kG * t * h / 2.0, 1e-9);
    EXPECT_NEAR(left.readout.centreOfMass.x(), 2.0, 1e-12);
}

}  // namespace
}  // namespace substep::ecs
