// Tests sandbox/scenes/bunny_chain.cpp (paper Figs. 10-11) and sandbox/scenes/asset_path.cpp:
// the bunnies weigh as their hull, the solver knob switches the split, and at one budget 20
// substeps x 1 iteration stretch the chain far less than 1 x 20.

#include "scenes/asset_path.h"
#include "scenes/live_scene.h"
#include "scenes/scene_registry.h"

#include "physics/collision/convex_hull.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace substep {
namespace {

const SceneEntry& bunnyChain() {
    const SceneEntry* entry = findBuiltinScene("bunny_chain");
    EXPECT_NE(entry, nullptr);
    return *entry;
}

BodyId bodyNamed(const SceneInstance& scene, const std::string& name) {
    for (const auto& [bodyName, id] : scene.namedBodyIds())
        if (bodyName == name) return id;
    return {};
}

/// Volume, first moment and ∫|x|² dV of a convex polyhedron by the divergence theorem over its
/// faces, each face fanned into triangles (independent of the tetrahedra of mass_properties):
///   V = 1/3 ∮ x·n dA,  ∫x dV = 1/2 ∮ (x_k² n_k) dA,  ∫|x|² dV = 1/5 ∮ |x|² (x·n) dA,
/// with x·n the face's plane offset on each face and exact quadratic integrals per triangle.
struct HullIntegrals {
    double volume = 0.0;
    Vec3 firstMoment = Vec3::Zero();
    double secondMoment = 0.0;  ///< ∫ |x|² dV about the origin
};

HullIntegrals integrateHull(const ConvexHull& hull) {
    HullIntegrals result;
    for (const HullFace& face : hull.faces) {
        const Vec3& a = hull.faceVertex(face, 0);
        for (int i = 1; i + 1 < face.vertexCount; ++i) {
            const Vec3& b = hull.faceVertex(face, i);
            const Vec3& c = hull.faceVertex(face, i + 1);
            const double area = 0.5 * (b - a).cross(c - a).norm();
            // ∫ f g dA over a triangle for linear f, g: A/12 (Σ f_i g_i + Σ_i Σ_j f_i g_j).
            const Vec3 squares = (a.cwiseProduct(a) + b.cwiseProduct(b) + c.cwiseProduct(c) +
                                  a.cwiseProduct(b) + b.cwiseProduct(c) + c.cwiseProduct(a)) *
                                 (area / 6.0);
            result.volume += face.offset * area / 3.0;
            result.firstMoment += 0.5 * squares.cwiseProduct(face.normal);
            result.secondMoment += face.offset * squares.sum() / 5.0;
        }
    }
    return result;
}

TEST(BunnyChain, BunniesWeighAsTheirHullAndShareOneShape) {
    SceneInstance scene = buildScene(bunnyChain().build());
    const Body& first = scene.world().body(bodyNamed(scene, "bunny1"));
    const Body& last = scene.world().body(bodyNamed(scene, "bunny100"));
    ASSERT_EQ(first.shape.type, ShapeType::Mesh);
    ASSERT_TRUE(first.shape.convex);
    ASSERT_TRUE(first.shape.hull);
    EXPECT_EQ(first.shape.hull.get(), last.shape.hull.get()) << "the mesh is loaded once per build";
    EXPECT_EQ(first.shape.mesh.get(), last.shape.mesh.get());

    const ConvexHull& hull = *first.shape.hull;
    const HullIntegrals integrals = integrateHull(hull);
    const double density = 1000.0;  // the scene's
    const double mass = density * integrals.volume;
    // A bunny 20 cm tall: its hull is well inside its bounding box and fills a good part of it.
    const Vec3 extent = hull.bounds.max - hull.bounds.min;
    EXPECT_NEAR(extent.y(), 0.2, 0.03);
    EXPECT_LT(integrals.volume, extent.prod());
    EXPECT_GT(integrals.volume, 0.3 * extent.prod());
    EXPECT_NEAR(first.mass, mass, 1e-9 * mass);

    // The centre of mass: the body's origin is its centre of mass, the user frame's origin the
    // mid-point of the anchors on the vertical through it.
    const Vec3 centroid = integrals.firstMoment / integrals.volume;
    const Vec3 centreOffset = first.x - first.userPosition();  // identity orientation at rest
    EXPECT_NEAR((centreOffset - centroid).norm(), 0.0, 1e-9);
    EXPECT_NEAR(centroid.x(), 0.0, 1e-9);
    EXPECT_NEAR(centroid.z(), 0.0, 1e-9);

    // The trace of the inertia about the centre of mass: 2 ρ ∫|x - c|² dV = 2 ρ (∫|x|² dV - V |c|²).
    const double trace = 2.0 * density * (integrals.secondMoment - integrals.volume * centroid.squaredNorm());
    EXPECT_NEAR(first.inertia.sum(), trace, 1e-9 * trace);
    std::printf("bunny: hull volume %.6g m^3, mass %.4g kg, centre of mass (%.4g, %.4g, %.4g) m, "
                "principal moments (%.4g, %.4g, %.4g) kg m^2\n",
                integrals.volume, mass, centroid.x(), centroid.y(), centroid.z(), first.inertia.x(),
                first.inertia.y(), first.inertia.z());
}

TEST(BunnyChain, SolverKnobSwitchesTheSplitAndStartLeavesItAlone) {
    const SceneEntry& entry = bunnyChain();
    LiveScene scene(entry.build(), &entry);
    ASSERT_NE(scene.script(), nullptr);
    EXPECT_EQ(scene.world().settings().substeps, 20);  // Table 1
    EXPECT_EQ(scene.world().settings().iterations, 1);
    const int expected[5][2] = {{20, 1}, {10, 2}, {5, 4}, {2, 10}, {1, 20}};
    for (int choice = 4; choice >= 0; --choice) {
        ASSERT_TRUE(scene.script()->setKnob(scene.instance(), "solver", choice));
        EXPECT_EQ(scene.world().settings().substeps, expected[choice][0]);
        EXPECT_EQ(scene.world().settings().iterations, expected[choice][1]);
        EXPECT_EQ(scene.world().settings().substeps * scene.world().settings().iterations, 20);
    }
    // start() (run on restart) leaves the solver settings to the caller.
    ASSERT_TRUE(scene.script()->setKnob(scene.instance(), "solver", 4));
    WorldSettings settings = scene.world().settings();
    settings.substeps = 7;
    settings.iterations = 3;
    scene.physics().setSettings(settings);
    scene.script()->start(scene.instance());
    EXPECT_EQ(scene.world().settings().substeps, 7);
    EXPECT_EQ(scene.world().settings().iterations, 3);
}

/// The chain's relative elongation (the scene's ChainMeasure), averaged over the last second of
/// `seconds`, with the solver knob at `choice`, hanging from rest (release_angle 0, as Fig. 11
/// measures it).
double settledElongation(int choice, double seconds) {
    const SceneEntry& entry = bunnyChain();
    LiveScene scene(entry.build(), &entry);
    EXPECT_TRUE(scene.script()->setKnob(scene.instance(), "release_angle", 0.0));
    scene.restart();  // the angle applies on restart
    EXPECT_TRUE(scene.script()->setKnob(scene.instance(), "solver", choice));
    const ChainMeasure& chain = entry.chain;
    const BodyId end = bodyNamed(scene.instance(), std::string(chain.endBody));
    const Vec3 anchor(chain.anchor[0], chain.anchor[1], chain.anchor[2]);
    const Vec3 endPoint(chain.endPoint[0], chain.endPoint[1], chain.endPoint[2]);
    const long long frames = std::lround(seconds / scene.description().dt);
    const long long averaged = std::lround(1.0 / scene.description().dt);
    double sum = 0.0;
    for (long long frame = 0; frame < frames; ++frame) {
        scene.step();
        if (frame < frames - averaged) continue;
        const Body& body = scene.world().body(end);
        const Vec3 point = body.userPosition() + body.userOrientation() * endPoint;
        sum += ((point - anchor).norm() - chain.restLength) / chain.restLength;
    }
    EXPECT_TRUE(scene.world().isFinite());
    return sum / static_cast<double>(averaged);
}

TEST(BunnyChain, TheChainAtRestMeasuresItsRestLength) {
    // Built hanging straight: every joint closed, so the measure reads 0 before any step.
    const SceneEntry& entry = bunnyChain();
    SceneInstance scene = buildScene(entry.build());
    const Body& body = scene.world().body(bodyNamed(scene, std::string(entry.chain.endBody)));
    const Vec3 point = body.userPosition() + body.userOrientation() * Vec3(0.0, -0.1, 0.0);
    EXPECT_NEAR((point - Vec3(0.0, entry.chain.anchor[1], 0.0)).norm(), entry.chain.restLength, 1e-9);
}

TEST(BunnyChain, SubstepsStretchTheChainLessThanIterationsAtOneBudget) {
    // Fig. 11: at a fixed budget, replacing iterations by substeps is by far the best choice.
    const char* names[5] = {"20 x 1", "10 x 2", "5 x 4", "2 x 10", "1 x 20"};
    double elongation[5];
    for (int choice = 0; choice < 5; ++choice) {
        elongation[choice] = settledElongation(choice, 5.0);
        std::printf("%-7s relative elongation %.3e\n", names[choice], elongation[choice]);
    }
    EXPECT_GT(elongation[0], 0.0);  // gravity stretches it a little
    EXPECT_LT(elongation[0] * 10.0, elongation[4]);
    // Each step towards more substeps helps.
    for (int choice = 0; choice + 1 < 5; ++choice) EXPECT_LT(elongation[choice], elongation[choice + 1]);
}

TEST(AssetPath, FindsTheBunnyAndNamesAMissingAsset) {
    EXPECT_TRUE(std::filesystem::is_regular_file(findAsset("meshes/bunny.obj")));
    try {
        findAsset("meshes/no_such_mesh.obj");
        ADD_FAILURE() << "a missing asset must throw";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find("meshes/no_such_mesh.obj"), std::string::npos) << error.what();
    }
}

}  // namespace
}  // namespace substep
