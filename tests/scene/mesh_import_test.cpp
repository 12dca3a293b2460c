// Tests engine/scene/mesh_import.cpp and the mesh shape of engine/scene/scene_loader_shapes.cpp:
// hand-written mesh files (tests/data/scenes) load with the right vertices, volume and shape, and
// every bad mesh is a SceneError naming the file and the JSON path.

#include "scene/mesh_import.h"
#include "physics/collision/convex_hull.h"
#include "physics/mass_properties.h"
#include "scene/scene_loader.h"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <utility>

#ifndef SUBSTEP_TEST_DATA_DIR
#define SUBSTEP_TEST_DATA_DIR "tests/data/scenes"
#endif

namespace substep {
namespace {

const std::string kDataDir = SUBSTEP_TEST_DATA_DIR;

/// A scene text with one body whose shape is `shape` (JSON object members).
std::string withMeshBody(const std::string& shape, const std::string& body = "\"mass\": 1") {
    return R"({"substep_scene": 1, "bodies": [{"shape": {"type": "mesh", )" + shape + "}, " + body +
           "}]}";
}

/// Parses as if the text were a file in the test data folder (mesh files resolve there).
SceneDescription parseInDataDir(const std::string& text) {
    return parseSceneText(text, kDataDir + "/inline.json");
}

/// Passes when parsing throws a SceneError at `path` whose message contains `fragment`.
::testing::AssertionResult failsAt(const std::string& text, const std::string& path,
                                   const std::string& fragment) {
    try {
        parseInDataDir(text);
    } catch (const SceneError& error) {
        if (error.path() != path) {
            return ::testing::AssertionFailure() << "path " << error.path() << ": " << error.what();
        }
        if (std::string(error.what()).find(fragment) == std::string::npos) {
            return ::testing::AssertionFailure() << "message: " << error.what();
        }
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "no SceneError";
}

TEST(MeshImport, ObjCubeSplitByNormalsIsJoinedIntoAClosedMesh) {
    const MeshImport cube = importTriangleMesh(kDataDir + "/unit_cube.obj");
    ASSERT_TRUE(cube.ok()) << cube.error;
    EXPECT_EQ(cube.mesh.vertices.size(), 8u);
    EXPECT_EQ(cube.mesh.triangles.size(), 12u);  // six quads, triangulated
    const MassProperties unit = meshMassProperties(cube.mesh, 1.0);
    EXPECT_NEAR(unit.mass, 1.0, 1e-12);  // closed and outward: the cube's volume
    EXPECT_LT(unit.centerOfMass.norm(), 1e-12);
}

TEST(MeshImport, ScaleIsAppliedPerAxis) {
    const MeshImport cube = importTriangleMesh(kDataDir + "/unit_cube.obj", Vec3(2, 3, 0.5));
    ASSERT_TRUE(cube.ok()) << cube.error;
    EXPECT_NEAR(meshMassProperties(cube.mesh, 1.0).mass, 3.0, 1e-12);
    Aabb bounds;
    for (const Vec3& v : cube.mesh.vertices)
        bounds.grow(v);
    EXPECT_TRUE(bounds.max.isApprox(Vec3(1, 1.5, 0.25)));
}

TEST(MeshImport, StlTetrahedronHasTheRightVolume) {
    const MeshImport tetra = importTriangleMesh(kDataDir + "/tetrahedron.stl");
    ASSERT_TRUE(tetra.ok()) << tetra.error;
    EXPECT_EQ(tetra.mesh.vertices.size(), 4u);
    EXPECT_EQ(tetra.mesh.triangles.size(), 4u);
    EXPECT_NEAR(meshMassProperties(tetra.mesh, 1.0).mass, 1.0 / 6.0, 1e-12);
}

TEST(MeshImport, MissingOrEmptyFilesAreErrorsNamingTheFile) {
    const MeshImport missing = importTriangleMesh(kDataDir + "/no_such_mesh.obj");
    EXPECT_FALSE(missing.ok());
    EXPECT_NE(missing.error.find("no_such_mesh.obj"), std::string::npos) << missing.error;
    const MeshImport empty = importTriangleMesh(kDataDir + "/no_triangles.obj");
    EXPECT_FALSE(empty.ok());
    EXPECT_NE(empty.error.find("no triangles"), std::string::npos) << empty.error;
    EXPECT_TRUE(empty.mesh.vertices.empty());
    const MeshImport folder = importTriangleMesh(kDataDir);
    EXPECT_FALSE(folder.ok());
    // A device is not read (before: assimp read /dev/zero until memory ran out).
    const MeshImport device = importTriangleMesh("/dev/zero");
    EXPECT_FALSE(device.ok());
    EXPECT_EQ(device.error,
              "cannot read mesh file /dev/zero: not a regular file (a device, FIFO or socket)");
    // Not a mesh at all.
    const MeshImport json = importTriangleMesh(kDataDir + "/truncated.json");
    EXPECT_FALSE(json.ok());
}

TEST(MeshImport, TheBunnyAssetIsClosedAndItsHullEnclosesIt) {
    const MeshImport bunny = importTriangleMesh(kDataDir + "/../../../assets/meshes/bunny.obj");
    ASSERT_TRUE(bunny.ok()) << bunny.error;
    const TriangleMesh& mesh = bunny.mesh;
    // Closed: every edge borders exactly two triangles, once in each direction.
    std::map<std::pair<int, int>, int> directed;
    for (const auto& t : mesh.triangles) {
        for (int e = 0; e < 3; ++e)
            ++directed[{t[e], t[(e + 1) % 3]}];
    }
    for (const auto& [edge, count] : directed) {
        EXPECT_EQ(count, 1);
        EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
    }
    EXPECT_EQ(static_cast<int>(mesh.vertices.size()) - static_cast<int>(directed.size()) / 2 +
                  static_cast<int>(mesh.triangles.size()),
              2);  // a sphere's Euler characteristic
    // Outward winding gives a positive signed volume; the hull holds more than the mesh, its
    // centre of mass lies inside the hull, and the inertia is positive definite.
    double signedVolume = 0.0;
    for (const auto& t : mesh.triangles) {
        signedVolume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6;
    }
    EXPECT_GT(signedVolume, 0.0);
    const MassProperties solid = meshMassProperties(mesh, 1.0);
    EXPECT_NEAR(solid.mass, signedVolume, 1e-9 * signedVolume);
    const ConvexHull hull = buildConvexHull(mesh.vertices);
    const double hullVolume = meshMassProperties(hullTriangleMesh(hull), 1.0).mass;
    EXPECT_GT(hullVolume, solid.mass);
    EXPECT_LT(hullVolume, 2.0 * solid.mass);
    for (const HullFace& f : hull.faces)
        EXPECT_LT(f.normal.dot(solid.centerOfMass), f.offset);
    EXPECT_GT(principalFrame(solid.inertia).moments.minCoeff(), 0.0);
}

TEST(SceneLoaderMesh, ConvexMeshBodyWeighsAsItsScaledHull) {
    const SceneDescription scene = parseInDataDir(withMeshBody(
        R"("file": "unit_cube.obj", "scale": 0.5, "convex": true)", R"("density": 800)"));
    ASSERT_EQ(scene.bodies.size(), 1u);
    const Shape& shape = scene.bodies[0].def.shape;
    EXPECT_EQ(shape.type, ShapeType::Mesh);
    EXPECT_TRUE(shape.convex);
    ASSERT_TRUE(shape.hull);
    EXPECT_EQ(shape.hull->faces.size(), 6u);
    EXPECT_TRUE(shape.localBounds.max.isApprox(Vec3::Constant(0.25)));
    EXPECT_NEAR(shapeMassProperties(shape, 800).mass, 800 * 0.125, 1e-9);
}

TEST(SceneLoaderMesh, SceneFileFindsMeshesBesideIt) {
    const SceneDescription scene = loadSceneFile(kDataDir + "/mesh_convex.json");
    ASSERT_EQ(scene.bodies.size(), 2u);
    EXPECT_FALSE(scene.bodies[0].def.shape.convex);
    EXPECT_TRUE(scene.bodies[0].def.shape.meshCollider);  // static triangle mesh
    EXPECT_TRUE(scene.bodies[1].def.shape.hull);
}

TEST(SceneLoaderMesh, StaticNonConvexMeshIsATriangleMesh) {
    const SceneDescription scene =
        parseInDataDir(withMeshBody(R"("file": "tetrahedron.stl")", R"("static": true)"));
    const Shape& shape = scene.bodies[0].def.shape;
    EXPECT_EQ(shape.type, ShapeType::Mesh);
    EXPECT_FALSE(shape.convex);
    EXPECT_TRUE(shape.meshCollider);
    ASSERT_TRUE(shape.mesh);
    EXPECT_EQ(shape.mesh->triangles.size(), 4u);
}

TEST(SceneLoaderMesh, BadMeshesAreErrorsAtTheirPath) {
    EXPECT_TRUE(failsAt(withMeshBody(R"("file": "unit_cube.obj")"), "bodies[0].shape.type",
                        "a dynamic mesh must be convex"));
    EXPECT_TRUE(failsAt(withMeshBody(R"("file": "unit_cube.obj", "convex": false)"),
                        "bodies[0].shape.convex", "a dynamic mesh must be convex"));
    EXPECT_TRUE(failsAt(withMeshBody(R"("convex": true)"), "bodies[0].shape.file", "missing"));
    EXPECT_TRUE(
        failsAt(withMeshBody(R"("file": "", "convex": true)"), "bodies[0].shape.file", "empty"));
    EXPECT_TRUE(failsAt(withMeshBody(R"("file": 3, "convex": true)"), "bodies[0].shape.file",
                        "must be a string"));
    EXPECT_TRUE(failsAt(withMeshBody(R"("file": "missing.obj", "convex": true)"),
                        "bodies[0].shape.file", "missing.obj: no such file"));
    EXPECT_TRUE(failsAt(withMeshBody(R"("file": "no_triangles.obj", "convex": true)"),
                        "bodies[0].shape.file", "no_triangles.obj contains no triangles"));
    EXPECT_TRUE(failsAt(withMeshBody(R"("file": "flat_square.obj", "convex": true)"),
                        "bodies[0].shape.file", "enclose no volume"));
    EXPECT_TRUE(failsAt(withMeshBody(R"("file": "unit_cube.obj", "convex": true, "scale": 0)"),
                        "bodies[0].shape.scale", "must be > 0"));
    EXPECT_TRUE(
        failsAt(withMeshBody(R"("file": "unit_cube.obj", "convex": true, "scale": [1, -1, 1])"),
                "bodies[0].shape.scale[1]", "must be > 0"));
    EXPECT_TRUE(failsAt(withMeshBody(R"("file": "unit_cube.obj", "convex": "yes")"),
                        "bodies[0].shape.convex", "must be true or false"));
    EXPECT_TRUE(failsAt(withMeshBody(R"("file": "unit_cube.obj", "convex": true, "size": 1)"),
                        "bodies[0].shape.size", "unknown key"));
    // Density times the hull's volume above the mass bound.
    EXPECT_TRUE(failsAt(withMeshBody(R"("file": "unit_cube.obj", "convex": true, "scale": 1e4)",
                                     R"("density": 1000)"),
                        "bodies[0].density", "sanity bound"));
}

}  // namespace
}  // namespace substep
