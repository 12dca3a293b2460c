// Tests engine/scene/scene_loader.cpp: reading the file, the version, the top-level keys and
// their section readers in table order, and the error type.

#include "scene/scene.h"
#include "scene/scene_loader.h"

#include "scene_loader_test_support.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

namespace substep {
namespace {

using namespace test;

TEST(SceneLoader, MinimalSceneTakesTheDefaults) {
    const SceneDescription s = parseSceneText(scene(""), "scenes/minimal.json");
    EXPECT_EQ(s.name, "minimal");
    EXPECT_EQ(s.gravity, Vec3(0, -9.81, 0));
    EXPECT_DOUBLE_EQ(s.dt, 1.0 / 60.0);
    EXPECT_EQ(s.substeps, 20);
    EXPECT_EQ(s.iterations, 1);
    EXPECT_TRUE(s.bodies.empty());
    EXPECT_TRUE(s.joints.empty());
    EXPECT_FALSE(s.camera.has_value());
}

TEST(SceneLoader, FullSceneRoundTrips) {
    const SceneDescription s = loadSceneFile(kDataDir + "/full.json");
    EXPECT_EQ(s.name, "full");  // the file stem, not the "name" key
    EXPECT_EQ(s.gravity, Vec3(0, -10, 0.5));
    EXPECT_EQ(s.dt, 0.01);
    EXPECT_EQ(s.substeps, 40);
    EXPECT_EQ(s.iterations, 2);
    ASSERT_TRUE(s.camera.has_value());
    EXPECT_EQ(s.camera->position, Vec3(1, 2, 3));
    EXPECT_EQ(s.camera->target, Vec3(0, 1, 0));
    EXPECT_EQ(s.camera->fov, 0.9);

    ASSERT_EQ(s.bodies.size(), 7u);
    const BodyDef& ground = s.bodies[0].def;
    EXPECT_EQ(s.bodies[0].name, "ground");
    EXPECT_EQ(ground.type, BodyType::Static);
    EXPECT_EQ(ground.shape.type, ShapeType::Plane);
    EXPECT_EQ(ground.shape.normal, Vec3(0, 1, 0));  // normalised
    EXPECT_EQ(ground.shape.offset, -1.0);
    EXPECT_EQ(ground.staticFriction, 0.8);
    EXPECT_EQ(ground.dynamicFriction, 0.6);
    EXPECT_EQ(ground.restitution, 0.25);

    const BodyDef& ceiling = s.bodies[1].def;
    EXPECT_EQ(ceiling.type, BodyType::Static);
    EXPECT_EQ(ceiling.shape.type, ShapeType::Box);
    EXPECT_EQ(ceiling.shape.size, Vec3(1, 0.1, 1));
    EXPECT_EQ(ceiling.position, Vec3(0, 2, 0));
    EXPECT_FALSE(ceiling.collide);

    const BodyDef& box = s.bodies[2].def;
    EXPECT_EQ(s.bodies[2].name, "box");
    EXPECT_EQ(box.type, BodyType::Dynamic);
    EXPECT_EQ(box.shape.size, Vec3(0.2, 0.3, 0.4));
    EXPECT_EQ(box.mass, 2.5);
    EXPECT_EQ(box.position, Vec3(0, 1.5, 0));
    EXPECT_EQ(box.orientation.coeffs(), Quat::Identity().coeffs());  // [2,0,0,0] normalised
    EXPECT_EQ(box.velocity, Vec3(1, 2, 3));
    EXPECT_EQ(box.angularVelocity, Vec3(-1, 0, 4));
    EXPECT_EQ(box.staticFriction, 0.5);
    EXPECT_EQ(box.dynamicFriction, 0.3);
    EXPECT_EQ(box.restitution, 0.5);

    const BodyDef& ball = s.bodies[3].def;
    EXPECT_EQ(ball.shape.type, ShapeType::Sphere);
    EXPECT_EQ(ball.shape.radius, 0.1);
    EXPECT_EQ(ball.mass, 0.0);
    EXPECT_EQ(ball.density, 7800.0);

    const SceneBody& capsule = s.bodies[4];
    EXPECT_TRUE(capsule.name.empty());
    EXPECT_EQ(capsule.def.shape.type, ShapeType::Capsule);
    EXPECT_EQ(capsule.def.shape.radius, 0.05);
    EXPECT_EQ(capsule.def.shape.length, 0.4);
    EXPECT_NEAR(
        capsule.def.orientation.angularDistance(Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()))),
        0.0, 1e-12);

    ASSERT_EQ(s.joints.size(), 6u);
    const SceneJoint& spring = s.joints[0];
    EXPECT_EQ(spring.name, "spring");
    EXPECT_EQ(spring.body0, "ceiling");
    EXPECT_EQ(spring.body1, "box");
    EXPECT_EQ(spring.def.type, JointType::Distance);
    EXPECT_EQ(spring.def.anchor0, Vec3(0, -0.05, 0));
    EXPECT_EQ(spring.def.anchor1, Vec3(0, 0.15, 0));
    EXPECT_EQ(spring.def.maxDistance, 0.5);
    EXPECT_EQ(spring.def.compliance, 0.01);
    EXPECT_EQ(spring.def.linearDamping, 0.1);
    EXPECT_EQ(spring.def.angularDamping, 0.2);
    EXPECT_TRUE(spring.def.collide);
    EXPECT_TRUE(spring.def.body0.isNull());  // ids are buildScene's job

    const SceneJoint& fixed = s.joints[1];
    EXPECT_TRUE(fixed.name.empty());
    EXPECT_EQ(fixed.def.type, JointType::Fixed);
    EXPECT_EQ(fixed.body0, "world");
    EXPECT_EQ(fixed.body1, "ball");
    EXPECT_EQ(fixed.def.anchor0, Vec3(1, 1.1, 0));
    EXPECT_FALSE(fixed.def.collide);
    EXPECT_EQ(fixed.def.axis0, Vec3::UnitY());
    EXPECT_FALSE(fixed.def.normal0.has_value());

    const SceneJoint& door = s.joints[2];
    EXPECT_EQ(door.def.type, JointType::Hinge);
    EXPECT_TRUE(door.body0.empty());
    EXPECT_EQ(door.def.axis0, Vec3(0, 0, 1));  // normalised
    EXPECT_EQ(door.def.axis1, Vec3(0, 0, 1));
    ASSERT_TRUE(door.def.normal0.has_value());
    EXPECT_TRUE(door.def.normal0->isApprox(Vec3(1, 0, 0)));  // made perpendicular to the axis
    EXPECT_EQ(*door.def.normal1, Vec3(1, 0, 0));
    ASSERT_TRUE(door.def.limits.has_value());
    EXPECT_EQ(door.def.limits->lower, -1.0);
    EXPECT_EQ(door.def.limits->upper, 1.5);
    EXPECT_EQ(door.def.limitCompliance, 0.001);
    EXPECT_EQ(door.def.targetAngle, 0.25);
    EXPECT_FALSE(door.def.targetVelocity.has_value());
    EXPECT_EQ(door.def.driveCompliance, 0.002);

    const SceneJoint& motor = s.joints[3];
    EXPECT_EQ(motor.def.targetVelocity, 3.5);
    EXPECT_FALSE(motor.def.targetAngle.has_value());
    // 3.1416 is pi rounded: accepted and clamped.
    EXPECT_EQ(motor.def.limits->lower, -M_PI);
    EXPECT_EQ(motor.def.limits->upper, M_PI);

    const SceneJoint& rail = s.joints[4];
    EXPECT_EQ(rail.def.type, JointType::Prismatic);
    EXPECT_EQ(rail.def.axis0, Vec3(1, 0, 0));
    EXPECT_EQ(rail.def.limits->lower, -0.5);
    EXPECT_EQ(rail.def.limits->upper, 2.0);
    EXPECT_EQ(rail.def.limitCompliance, 0.0001);
    EXPECT_EQ(rail.def.targetOffset, 0.75);
    EXPECT_EQ(rail.def.driveCompliance, 0.003);

    const SceneJoint& shoulder = s.joints[5];
    EXPECT_EQ(shoulder.def.type, JointType::Spherical);
    EXPECT_EQ(shoulder.def.swingLimit, 0.8);
    ASSERT_TRUE(shoulder.def.twistLimits.has_value());
    EXPECT_EQ(shoulder.def.twistLimits->lower, -0.3);
    EXPECT_EQ(shoulder.def.twistLimits->upper, 0.4);
    EXPECT_EQ(shoulder.def.limitCompliance, 0.004);
    EXPECT_EQ(shoulder.def.twistCompliance, 0.005);
}

TEST(SceneLoader, UnreadableFileNamesTheFile) {
    try {
        loadSceneFile("/nonexistent/dir/missing.json");
        FAIL() << "no error";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "/nonexistent/dir/missing.json: cannot read: No such file or directory");
        EXPECT_EQ(e.file(), "/nonexistent/dir/missing.json");
        EXPECT_TRUE(e.path().empty());
    }
    try {
        loadSceneFile(kDataDir);
        FAIL() << "no error";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(kDataDir + ": cannot read: ", 0), 0u) << e.what();
    }
}

/// A temporary folder for files made at run time (a FIFO, a symlink), removed at the end.
struct ScratchFolder {
    std::filesystem::path path;
    ScratchFolder() {
        path = std::filesystem::temp_directory_path() /
               ("substep_loader_" + std::to_string(::getpid()));
        std::filesystem::create_directories(path);
    }
    ~ScratchFolder() { std::filesystem::remove_all(path); }
};

TEST(SceneLoader, NonRegularFilesAreRefusedWithoutReadingOrBlocking) {
    // Before: /dev/zero was read without end and a FIFO blocked forever; the alarm turns
    // either into a failure instead of a hang.
    ::alarm(20);
    const ScratchFolder scratch;
    const std::string fifo = (scratch.path / "scene.json").string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const std::string& path : {std::string("/dev/zero"), std::string("/dev/null"), fifo}) {
        try {
            loadSceneFile(path);
            ADD_FAILURE() << path << ": no error";
        } catch (const SceneError& e) {
            EXPECT_EQ(std::string(e.what()),
                      path + ": cannot read: not a regular file (a device, FIFO or socket); a "
                             "scene is a .json file");
        }
    }
    ::alarm(0);
}

TEST(SceneLoader, SymlinkToASceneIsFollowed) {
    const ScratchFolder scratch;
    const std::filesystem::path link = scratch.path / "link.json";
    std::filesystem::create_symlink(std::filesystem::absolute(kDataDir + "/full.json"), link);
    EXPECT_EQ(loadSceneFile(link.string()).substeps, 40);
}

TEST(SceneLoader, TimeStepIsBetweenAMicrosecondAndASecond) {
    EXPECT_TRUE(failsAt(scene(R"("dt": 1e-320)"), "dt", "must be >= 1e-06"));
    EXPECT_TRUE(failsAt(scene(R"("dt": 1e-7)"), "dt", "must be >= 1e-06"));
    EXPECT_TRUE(failsAt(scene(R"("dt": 0)"), "dt", "must be in (0, 1]"));
    EXPECT_TRUE(failsAt(scene(R"("dt": 1.5)"), "dt", "must be in (0, 1]"));
    EXPECT_EQ(parseSceneText(scene(R"("dt": 1e-6)"), "t.json").dt, 1e-6);
    EXPECT_EQ(parseSceneText(scene(R"("dt": 1)"), "t.json").dt, 1.0);
}

TEST(SceneLoader, TopLevel) {
    EXPECT_TRUE(failsAt("[1, 2]", "top level", "must be a JSON object, got an array"));
    EXPECT_TRUE(failsAt("{}", "substep_scene", "missing"));
    EXPECT_TRUE(failsAt(R"({"substep_scene": 2})", "substep_scene", "unsupported version 2"));
    EXPECT_TRUE(failsAt(R"({"substep_scene": "1"})", "substep_scene", "must be 1"));
    EXPECT_TRUE(failsAt(R"({"substep_scene": 1.5})", "substep_scene", "unsupported version 1.5"));
    // The version is checked before anything else.
    EXPECT_TRUE(
        failsAt(R"({"bogus": 1, "substep_scene": 3})", "substep_scene", "unsupported version 3"));
    EXPECT_TRUE(failsAt(scene(R"("gravty": [0, -10, 0])"), "gravty",
                        "unknown key (did you mean \"gravity\"?)"));
    EXPECT_TRUE(failsAt(scene(R"("zzz": 1)"), "zzz", "unknown key (expected substep_scene"));
    EXPECT_TRUE(failsAt(scene(R"("odd key": 1)"), R"(["odd key"])", "unknown key"));
    EXPECT_TRUE(failsAt(scene(R"("name": 3)"), "name", "must be a string, got 3"));
    EXPECT_TRUE(
        failsAt(scene(R"("description": ["x"])"), "description", "must be a string, got an array"));
}

TEST(SceneLoader, ArraysOfBodiesAndJoints) {
    EXPECT_TRUE(
        failsAt(scene(R"("bodies": {})"), "bodies", "must be an array of bodies, got an object"));
    EXPECT_TRUE(failsAt(scene(R"("bodies": [3])"), "bodies[0]", "must be a body object, got 3"));
    EXPECT_TRUE(failsAt(scene(R"("joints": 1)"), "joints", "must be an array of joints"));
    EXPECT_TRUE(
        failsAt(scene(R"("joints": [[]])"), "joints[0]", "must be a joint object, got an array"));
}

TEST(SceneLoader, TopLevelKeysAreListedInOrder) {
    // The world settings, then the section readers' keys in their table's order.
    EXPECT_TRUE(failsAt(scene(R"("zzz": 1)"), "zzz",
                        "unknown key (expected substep_scene, name, description, gravity, dt, "
                        "substeps, iterations, sleeping, joint_projection, restitution, soft_friction, soft_contacts, bodies, joints, soft_bodies or "
                        "camera)"));
}

TEST(SceneLoader, SleepingIsABooleanOffByDefault) {
    EXPECT_FALSE(parseSceneText(scene(""), "t.json").sleeping);
    EXPECT_TRUE(parseSceneText(scene(R"("sleeping": true)"), "t.json").sleeping);
    EXPECT_FALSE(parseSceneText(scene(R"("sleeping": false)"), "t.json").sleeping);
    EXPECT_TRUE(failsAt(scene(R"("sleeping": 1)"), "sleeping", "must be"));
    // The world built from the scene sleeps as asked.
    EXPECT_TRUE(buildScene(parseSceneText(scene(R"("sleeping": true)"), "t.json")).world().settings().sleeping);
    EXPECT_FALSE(buildScene(parseSceneText(scene(""), "t.json")).world().settings().sleeping);
}

TEST(SceneLoader, JointProjectionIsPaperOrStart) {
    EXPECT_EQ(parseSceneText(scene(""), "s.json").jointProjection, JointProjection::Paper);
    EXPECT_EQ(parseSceneText(scene(R"("joint_projection": "start")"), "s.json").jointProjection,
              JointProjection::Start);
    EXPECT_EQ(parseSceneText(scene(R"("joint_projection": "paper")"), "s.json").jointProjection,
              JointProjection::Paper);
    EXPECT_TRUE(failsAt(scene(R"("joint_projection": "Start")"), "joint_projection",
                        "expected \"paper\" or \"start\", got \"Start\""));
    EXPECT_TRUE(failsAt(scene(R"("joint_projection": 1)"), "joint_projection", "must be a string, got 1"));
}

TEST(SceneLoader, RestitutionIsSweptByDefaultOrThePapers) {
    EXPECT_TRUE(parseSceneText(scene(""), "s.json").sweptRestitution);
    EXPECT_TRUE(parseSceneText(scene(R"("restitution": "swept")"), "s.json").sweptRestitution);
    EXPECT_FALSE(parseSceneText(scene(R"("restitution": "paper")"), "s.json").sweptRestitution);
    EXPECT_TRUE(failsAt(scene(R"("restitution": "Paper")"), "restitution",
                        "expected \"swept\" or \"paper\", got \"Paper\""));
    // A coefficient belongs on a body; at the top it is an error, not a silent default.
    EXPECT_TRUE(failsAt(scene(R"("restitution": 0.5)"), "restitution", "must be a string, got 0.5"));
    // The world built from the scene uses what the file chose.
    EXPECT_FALSE(buildScene(parseSceneText(scene(R"("restitution": "paper")"), "t.json")).world().settings().sweptRestitution);
    EXPECT_TRUE(buildScene(parseSceneText(scene(R"("restitution": "swept")"), "t.json")).world().settings().sweptRestitution);
    EXPECT_TRUE(buildScene(parseSceneText(scene(""), "t.json")).world().settings().sweptRestitution);
}

TEST(SceneLoader, SoftFrictionIsPerParticleByDefaultOrOverThePatch) {
    EXPECT_FALSE(parseSceneText(scene(""), "s.json").softPatchFriction);
    EXPECT_TRUE(parseSceneText(scene(R"("soft_friction": "patch")"), "s.json").softPatchFriction);
    EXPECT_FALSE(parseSceneText(scene(R"("soft_friction": "particle")"), "s.json").softPatchFriction);
    EXPECT_TRUE(failsAt(scene(R"("soft_friction": "patches")"), "soft_friction",
                        "expected \"patch\" or \"particle\", got \"patches\""));
    EXPECT_TRUE(failsAt(scene(R"("soft_friction": true)"), "soft_friction", "must be a string, got true"));
    // The world built from the scene uses what the file chose.
    EXPECT_TRUE(buildScene(parseSceneText(scene(R"("soft_friction": "patch")"), "t.json")).world().settings().softPatchFriction);
    EXPECT_FALSE(buildScene(parseSceneText(scene(""), "t.json")).world().settings().softPatchFriction);

    EXPECT_FALSE(parseSceneText(scene(""), "s.json").softHeldContacts);
    EXPECT_TRUE(parseSceneText(scene(R"("soft_contacts": "held")"), "s.json").softHeldContacts);
    EXPECT_FALSE(parseSceneText(scene(R"("soft_contacts": "free")"), "s.json").softHeldContacts);
    EXPECT_TRUE(failsAt(scene(R"("soft_contacts": "hold")"), "soft_contacts",
                        R"(expected "held" or "free", got "hold")"));
    EXPECT_TRUE(failsAt(scene(R"("soft_contacts": 1)"), "soft_contacts", "must be a string, got 1"));
    EXPECT_TRUE(buildScene(parseSceneText(scene(R"("soft_contacts": "held")"), "t.json")).world().settings().softHeldContacts);
    EXPECT_FALSE(buildScene(parseSceneText(scene(""), "t.json")).world().settings().softHeldContacts);
}

TEST(SceneLoader, SectionsAreReadInTheirOrderNotTheFiles) {
    // Bodies before joints before camera, wherever the file puts them: a joint may name a body
    // given after it, and the first error reported is the earliest section's.
    const auto s = parseSceneText(
        R"({"substep_scene": 1, "camera": {"fov": 1},
            "joints": [{"type": "hinge", "body1": "late"}],
            "bodies": [{"name": "late", "shape": {"type": "sphere", "radius": 1}}]})",
        "t.json");
    ASSERT_EQ(s.joints.size(), 1u);
    EXPECT_EQ(s.joints[0].body1, "late");
    ASSERT_TRUE(s.camera.has_value());
    EXPECT_EQ(s.camera->fov, 1.0);
    const std::string badCamera = R"("camera": {"fov": 9})";
    const std::string badJoint = R"("joints": [{"type": "bogus"}])";
    const std::string badBody = R"("bodies": [{"shape": {"type": "sphere", "radius": -1}}])";
    EXPECT_TRUE(failsAt(scene(badCamera + ", " + badJoint + ", " + badBody),
                        "bodies[0].shape.radius", "must be > 0"));
    EXPECT_TRUE(
        failsAt(scene(badCamera + ", " + badJoint), "joints[0].type", "unknown joint type"));
    EXPECT_TRUE(failsAt(scene(badCamera), "camera.fov", "must be in (0, pi), got 9"));
}

TEST(SceneLoader, ErrorCarriesItsParts) {
    try {
        parseSceneText(withBody(R"("shape": {"type": "sphere", "radius": -1})"), "scenes/a.json");
        FAIL();
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "scenes/a.json: bodies[0].shape.radius: must be > 0, got -1");
        const auto* scene = dynamic_cast<const SceneError*>(&e);
        ASSERT_NE(scene, nullptr);
        EXPECT_EQ(scene->file(), "scenes/a.json");
        EXPECT_EQ(scene->path(), "bodies[0].shape.radius");
        EXPECT_EQ(scene->problem(), "must be > 0, got -1");
    }
}

TEST(SceneLoader, LoadsAFileWrittenAtRunTime) {
    const auto path =
        std::filesystem::temp_directory_path() / "substep_scene_loader_test_scene.json";
    {
        std::ofstream out(path);
        out << "\xEF\xBB\xBF" << scene(R"("substeps": 7)");  // a UTF-8 byte order mark is tolerated
    }
    const SceneDescription s = loadSceneFile(path.string());
    EXPECT_EQ(s.name, "substep_scene_loader_test_scene");
    EXPECT_EQ(s.substeps, 7);
    std::filesystem::remove(path);
}

}  // namespace
}  // namespace substep
