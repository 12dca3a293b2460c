// Tests engine/scene/scene_loader_soft_bodies.cpp: the `soft_bodies` key, every field of a box
// and a tyre with its default, the attachments to named bodies, and every error by JSON path.

#include "scene/scene_loader.h"

#include "scene_loader_test_support.h"

#include <gtest/gtest.h>

#include <string>

namespace substep {
namespace {

using namespace test;

const std::string kBox = R"("type": "box", "size": [0.4, 0.2, 0.3], "cells": [4, 2, 3])";
const std::string kTyre = R"("type": "tyre", "outer_radius": 0.3, "inner_radius": 0.2, "width": 0.1, "cells": [24, 2, 2])";
/// A static body "mount" and a dynamic body "rim"; then one soft body made of `members`.
std::string withSoft(const std::string& members) {
    return scene(R"("bodies": [{"name": "mount", "static": true, "shape": {"type": "box", "size": [1, 1, 1]}},
                               {"name": "rim", "shape": {"type": "cylinder", "radius": 0.2, "length": 0.1}}],
                    "soft_bodies": [{)" +
                 members + "}]");
}

TEST(SceneLoaderSoftBodies, BoxDefaults) {
    const SceneDescription s = parseSceneText(withSoft(kBox), "t.json");
    ASSERT_EQ(s.softBodies.size(), 1u);
    const SceneSoftBody& soft = s.softBodies[0];
    const SoftBodyDef& def = soft.def;
    EXPECT_TRUE(soft.name.empty());
    EXPECT_FALSE(soft.colour.has_value());
    EXPECT_EQ(def.type, SoftBodyType::Box);
    EXPECT_EQ(def.size, Vec3(0.4, 0.2, 0.3));
    EXPECT_EQ(def.cells, (std::array<int, 3>{4, 2, 3}));
    EXPECT_EQ(def.position, Vec3::Zero());
    EXPECT_TRUE(def.orientation.coeffs().isApprox(Quat::Identity().coeffs()));
    EXPECT_EQ(def.velocity, Vec3::Zero());
    EXPECT_EQ(def.angularVelocity, Vec3::Zero());
    EXPECT_EQ(def.density, 1000.0);
    EXPECT_EQ(def.compliance, 0.0);
    EXPECT_FALSE(def.preserveVolume);
    EXPECT_EQ(def.damping, 0.0);
    EXPECT_EQ(def.staticFriction, 0.5);
    EXPECT_EQ(def.dynamicFriction, 0.3);
    EXPECT_EQ(def.restitution, 0.0);
    EXPECT_EQ(def.particleRadius, 0.01);
    EXPECT_TRUE(def.collide);
    EXPECT_TRUE(def.attachments.empty());
    EXPECT_TRUE(soft.attachBodies.empty());
}

TEST(SceneLoaderSoftBodies, EveryFieldIsRead) {
    const SceneDescription s = parseSceneText(
        withSoft(kTyre + R"(, "name": "tyre", "position": [1, 2, 3], "orientation": [0, 0, 2, 0],
                 "velocity": [4, 5, 6], "angular_velocity": [0, 0, 7], "density": 1200,
                 "compliance": 2e-7, "volume_compliance": 1e-8, "damping": 5,
                 "friction": {"static": 0.9, "dynamic": 0.7}, "restitution": 0.25,
                 "particle_radius": 0.02, "collide": false,
                 "attach": [{"body": "rim", "particles": "inner", "compliance": 1e-6},
                            {"body": "mount", "particles": "below"}, {"body": "rim"}])"),
        "t.json");
    ASSERT_EQ(s.softBodies.size(), 1u);
    const SceneSoftBody& soft = s.softBodies[0];
    const SoftBodyDef& def = soft.def;
    EXPECT_EQ(soft.name, "tyre");
    EXPECT_EQ(def.type, SoftBodyType::Tyre);
    EXPECT_EQ(def.outerRadius, 0.3);
    EXPECT_EQ(def.innerRadius, 0.2);
    EXPECT_EQ(def.width, 0.1);
    EXPECT_EQ(def.cells, (std::array<int, 3>{24, 2, 2}));
    EXPECT_EQ(def.position, Vec3(1, 2, 3));
    EXPECT_TRUE(def.orientation.coeffs().isApprox(Quat(0, 0, 1, 0).coeffs()));  // normalised
    EXPECT_EQ(def.velocity, Vec3(4, 5, 6));
    EXPECT_EQ(def.angularVelocity, Vec3(0, 0, 7));
    EXPECT_EQ(def.density, 1200.0);
    EXPECT_EQ(def.compliance, 2e-7);
    EXPECT_TRUE(def.preserveVolume);
    EXPECT_EQ(def.volumeCompliance, 1e-8);
    EXPECT_EQ(def.damping, 5.0);
    EXPECT_EQ(def.staticFriction, 0.9);
    EXPECT_EQ(def.dynamicFriction, 0.7);
    EXPECT_EQ(def.restitution, 0.25);
    EXPECT_EQ(def.particleRadius, 0.02);
    EXPECT_FALSE(def.collide);
    ASSERT_EQ(def.attachments.size(), 3u);
    ASSERT_EQ(soft.attachBodies, (std::vector<std::string>{"rim", "mount", "rim"}));
    EXPECT_EQ(def.attachments[0].particles, SoftAttachmentParticles::Inner);
    EXPECT_EQ(def.attachments[0].compliance, 1e-6);
    EXPECT_EQ(def.attachments[1].particles, SoftAttachmentParticles::Below);
    EXPECT_EQ(def.attachments[1].compliance, 0.0);
    EXPECT_EQ(def.attachments[2].particles, SoftAttachmentParticles::All);
}

TEST(SceneLoaderSoftBodies, SectionShapeAndKeys) {
    EXPECT_TRUE(failsAt(scene(R"("soft_bodies": {})"), "soft_bodies", "must be an array of soft bodies"));
    EXPECT_TRUE(failsAt(scene(R"("soft_bodies": [1])"), "soft_bodies[0]", "must be a soft body object, got 1"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "colide": false)"), "soft_bodies[0].colide",
                        "did you mean \"collide\""));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "mass": 1)"), "soft_bodies[0].mass", "unknown key"));
    EXPECT_TRUE(failsAt(withSoft(R"("size": [1, 1, 1], "cells": [1, 1, 1])"), "soft_bodies[0].type",
                        "missing (required)"));
    EXPECT_TRUE(failsAt(withSoft(R"("type": "sphere")"), "soft_bodies[0].type", "unknown soft body type \"sphere\""));
    EXPECT_TRUE(failsAt(withSoft(R"("type": 3)"), "soft_bodies[0].type", "must be a string"));
    // A key of the other lattice type is a mistake.
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "width": 0.1)"), "soft_bodies[0].width", "a box soft body does not use width"));
    EXPECT_TRUE(failsAt(withSoft(kTyre + R"(, "size": [1, 1, 1])"), "soft_bodies[0].size", "a tyre soft body does not use size"));
}

TEST(SceneLoaderSoftBodies, Names) {
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "name": "")"), "soft_bodies[0].name", "must not be empty"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "name": "a,b")"), "soft_bodies[0].name", "CSV"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "name": "world")"), "soft_bodies[0].name", "reserved"));
    // Soft bodies' columns share the bodies' namespace (NAME.x).
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "name": "rim")"), "soft_bodies[0].name",
                        "duplicate body name \"rim\" (already used at bodies[1].name)"));
    EXPECT_TRUE(failsAt(scene(R"("soft_bodies": [{"name": "s", )" + kBox + R"(}, {"name": "s", )" + kBox + "}]"),
                        "soft_bodies[1].name", "duplicate soft body name \"s\" (already used at soft_bodies[0].name)"));
}

TEST(SceneLoaderSoftBodies, BoxSizesAndCells) {
    const auto box = [](const std::string& size, const std::string& cells) {
        return withSoft(R"("type": "box", "size": )" + size + R"(, "cells": )" + cells);
    };
    EXPECT_TRUE(failsAt(withSoft(R"("type": "box", "cells": [1, 1, 1])"), "soft_bodies[0].size", "missing (required)"));
    EXPECT_TRUE(failsAt(withSoft(R"("type": "box", "size": [1, 1, 1])"), "soft_bodies[0].cells", "missing (required)"));
    EXPECT_TRUE(failsAt(box("[1, 0, 1]", "[1, 1, 1]"), "soft_bodies[0].size[1]", "must be > 0, got 0"));
    EXPECT_TRUE(failsAt(box("[1, 1, 2e4]", "[1, 1, 1]"), "soft_bodies[0].size[2]", "must be <= 10000"));
    EXPECT_TRUE(failsAt(box("[1, 1]", "[1, 1, 1]"), "soft_bodies[0].size", "[x, y, z]"));
    EXPECT_TRUE(failsAt(box("[1, 1, 1]", "[1, 1]"), "soft_bodies[0].cells", "must be an array [nx, ny, nz]"));
    EXPECT_TRUE(failsAt(box("[1, 1, 1]", "3"), "soft_bodies[0].cells", "must be an array [nx, ny, nz]"));
    EXPECT_TRUE(failsAt(box("[1, 1, 1]", "[0, 1, 1]"), "soft_bodies[0].cells[0]", "must be an integer in [1, 64], got 0"));
    EXPECT_TRUE(failsAt(box("[1, 1, 1]", "[1, 65, 1]"), "soft_bodies[0].cells[1]", "must be an integer in [1, 64], got 65"));
    EXPECT_TRUE(failsAt(box("[1, 1, 1]", "[1, 1, 2.5]"), "soft_bodies[0].cells[2]", "integer"));
    EXPECT_NO_THROW(parseSceneText(box("[1, 1, 1]", "[64, 1, 64]"), "t.json"));
}

TEST(SceneLoaderSoftBodies, TyreSizesAndCells) {
    const auto tyre = [](const std::string& outer, const std::string& inner, const std::string& cells) {
        return withSoft(R"("type": "tyre", "outer_radius": )" + outer + R"(, "inner_radius": )" + inner +
                        R"(, "width": 0.1, "cells": )" + cells);
    };
    EXPECT_TRUE(failsAt(withSoft(R"("type": "tyre", "inner_radius": 0.2, "width": 0.1, "cells": [3, 1, 1])"),
                        "soft_bodies[0].outer_radius", "missing (required)"));
    EXPECT_TRUE(failsAt(withSoft(R"("type": "tyre", "outer_radius": 0.3, "inner_radius": 0.2, "cells": [3, 1, 1])"),
                        "soft_bodies[0].width", "missing (required)"));
    EXPECT_TRUE(failsAt(tyre("0.3", "0", "[3, 1, 1]"), "soft_bodies[0].inner_radius", "must be > 0"));
    EXPECT_TRUE(failsAt(tyre("-1", "0.2", "[3, 1, 1]"), "soft_bodies[0].outer_radius", "must be > 0"));
    EXPECT_TRUE(failsAt(tyre("0.3", "0.3", "[3, 1, 1]"), "soft_bodies[0].inner_radius", "must be < outer_radius (0.3), got 0.3"));
    EXPECT_TRUE(failsAt(tyre("0.3", "0.2", "[2, 1, 1]"), "soft_bodies[0].cells[0]", "must be an integer in [3, 64], got 2"));
    EXPECT_TRUE(failsAt(tyre("0.3", "0.2", "[3, 0, 1]"), "soft_bodies[0].cells[1]", "must be an integer in [1, 64], got 0"));
    EXPECT_TRUE(failsAt(tyre("0.3", "0.2", "[3, 1, 65]"), "soft_bodies[0].cells[2]", "must be an integer in [1, 64], got 65"));
    EXPECT_NO_THROW(parseSceneText(tyre("0.3", "0.2", "[3, 1, 1]"), "t.json"));
}

TEST(SceneLoaderSoftBodies, AtMost100000ElementsPerScene) {
    // 64 x 64 x 24 = 98304 elements and 16 x 8 x 8 = 1024 more (99328) pass; another 1024
    // (100352) fail, at the body that crosses the bound.
    const std::string big = R"({"type": "box", "size": [1, 1, 1], "cells": [64, 64, 24]})";
    const std::string mid = R"({"type": "box", "size": [1, 1, 1], "cells": [16, 8, 8]})";
    EXPECT_NO_THROW(parseSceneText(scene(R"("soft_bodies": [)" + big + ", " + mid + "]"), "t.json"));
    EXPECT_TRUE(failsAt(scene(R"("soft_bodies": [)" + big + ", " + mid + ", " + mid + "]"),
                        "soft_bodies[2].cells", "100352 elements, above the sanity bound of 100000 per scene"));
}

TEST(SceneLoaderSoftBodies, MaterialBounds) {
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "density": 0)"), "soft_bodies[0].density", "must be > 0"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "density": 2e6)"), "soft_bodies[0].density", "must be <= 1e+06"));
    // 1e6 kg/m³ over a 1e3 m³ box is 1e9 kg... and a 1.1e3 m³ box is past the mass bound.
    EXPECT_TRUE(failsAt(withSoft(R"("type": "box", "size": [11, 10, 10], "cells": [1, 1, 1], "density": 1e6)"),
                        "soft_bodies[0].density", "above the 1e+09 kg sanity bound"));
    EXPECT_TRUE(failsAt(withSoft(R"("type": "box", "size": [1e4, 1e4, 1e4], "cells": [1, 1, 1])"),
                        "soft_bodies[0].type", "above the 1e+09 kg sanity bound"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "compliance": -1e-7)"), "soft_bodies[0].compliance", "must be >= 0"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "compliance": 2e9)"), "soft_bodies[0].compliance", "must be <= 1e+09"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "volume_compliance": -1)"), "soft_bodies[0].volume_compliance", ">= 0"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "damping": -1)"), "soft_bodies[0].damping", "must be >= 0"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "damping": 1e7)"), "soft_bodies[0].damping", "must be <= 1e+06"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "friction": 0.5)"), "soft_bodies[0].friction", "must be an object"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "friction": {"kinetic": 0.5})"), "soft_bodies[0].friction.kinetic",
                        "unknown key"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "friction": {"static": -0.1})"), "soft_bodies[0].friction.static",
                        "must be >= 0"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "friction": {"dynamic": 1e4})"), "soft_bodies[0].friction.dynamic",
                        "must be <= 1000"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "restitution": 1.5)"), "soft_bodies[0].restitution", "must be in [0, 1], got 1.5"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "particle_radius": 0)"), "soft_bodies[0].particle_radius", "must be > 0"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "collide": "no")"), "soft_bodies[0].collide", "must be true or false"));
}

TEST(SceneLoaderSoftBodies, PoseAndVelocityBounds) {
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "position": [0, 2e6, 0])"), "soft_bodies[0].position[1]", "1e+06"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "position": [0, 1e999, 0])"), "soft_bodies[0].position[1]", ""));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "orientation": [0, 0, 0, 0])"), "soft_bodies[0].orientation", "zero"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "velocity": [0, 0, 2e5])"), "soft_bodies[0].velocity[2]", "1e+05"));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "angular_velocity": [2e5, 0, 0])"), "soft_bodies[0].angular_velocity[0]",
                        "1e+05"));
}

TEST(SceneLoaderSoftBodies, Attachments) {
    EXPECT_TRUE(failsAt(withSoft(kTyre + R"(, "attach": {"body": "rim"})"), "soft_bodies[0].attach",
                        "must be an array of attachments"));
    EXPECT_TRUE(failsAt(withSoft(kTyre + R"(, "attach": ["rim"])"), "soft_bodies[0].attach[0]", "must be an object"));
    EXPECT_TRUE(failsAt(withSoft(kTyre + R"(, "attach": [{"particles": "all"}])"), "soft_bodies[0].attach[0].body",
                        "missing (required)"));
    EXPECT_TRUE(failsAt(withSoft(kTyre + R"(, "attach": [{"body": "hub"}])"), "soft_bodies[0].attach[0].body",
                        "unknown body \"hub\""));
    EXPECT_TRUE(failsAt(withSoft(kTyre + R"(, "attach": [{"body": "world"}])"), "soft_bodies[0].attach[0].body",
                        "not to the world"));
    EXPECT_TRUE(failsAt(withSoft(kTyre + R"(, "attach": [{"body": "rim", "particles": "outer"}])"),
                        "soft_bodies[0].attach[0].particles", "must be \"all\", \"inner\" or \"below\""));
    EXPECT_TRUE(failsAt(withSoft(kBox + R"(, "attach": [{"body": "rim", "particles": "inner"}])"),
                        "soft_bodies[0].attach[0].particles", "a box has none"));
    EXPECT_TRUE(failsAt(withSoft(kTyre + R"(, "attach": [{"body": "rim", "compliance": -1}])"),
                        "soft_bodies[0].attach[0].compliance", "must be >= 0"));
    EXPECT_TRUE(failsAt(withSoft(kTyre + R"(, "attach": [{"body": "rim", "side": 1}])"),
                        "soft_bodies[0].attach[0].side", "unknown key"));
    // Bodies are read first wherever the file puts them, so an attachment finds a body given later.
    const SceneDescription s = parseSceneText(
        R"({"substep_scene": 1, "soft_bodies": [{"type": "box", "size": [1, 1, 1], "cells": [1, 1, 1],
            "attach": [{"body": "late"}]}], "bodies": [{"name": "late", "shape": {"type": "sphere", "radius": 1}}]})",
        "t.json");
    ASSERT_EQ(s.softBodies.size(), 1u);
    EXPECT_EQ(s.softBodies[0].attachBodies, std::vector<std::string>{"late"});
}

}  // namespace
}  // namespace substep
