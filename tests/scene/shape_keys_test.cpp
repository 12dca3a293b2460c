// Tests engine/scene/scene_loader_shapes.cpp, the spline and heightfield shape keys: valid
// files build the shapes they describe, and every invalid value is reported at its JSON path.

#include "physics/collision/heightfield.h"
#include "physics/collision/spline_tube.h"
#include "scene/scene_loader.h"

#include <gtest/gtest.h>

#include <string>

namespace substep {
namespace {

/// A scene with one static body whose shape has the members `shape`.
std::string staticShape(const std::string& shape, const std::string& more = "") {
    return R"({"substep_scene": 1, "bodies": [{"static": true, "shape": {)" + shape + "}" +
           (more.empty() ? "" : ", " + more) + "}]}";
}

const std::string kSpline = R"("type": "spline", "radius": 0.01)";
const std::string kField = R"("type": "heightfield", "size": [4, 2])";

::testing::AssertionResult failsAt(const std::string& text, const std::string& path,
                                   const std::string& fragment) {
    try {
        parseSceneText(text, "t.json");
    } catch (const SceneError& error) {
        const std::string what = error.what();
        if (error.path() != path) {
            return ::testing::AssertionFailure() << "path \"" << error.path() << "\" in " << what;
        }
        if (what.rfind("t.json: " + path + ": ", 0) != 0 ||
            what.find(fragment) == std::string::npos) {
            return ::testing::AssertionFailure() << "message: " << what;
        }
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "no error";
}

TEST(ShapeKeys, SplineBuildsATube) {
    const SceneDescription s = parseSceneText(
        staticShape(kSpline + R"(, "points": [[0, 0, 0], [1, 0, 0], [1, 0, 1]], "closed": true)",
                    R"("position": [0, 1, 0])"),
        "t.json");
    const Shape& shape = s.bodies[0].def.shape;
    ASSERT_EQ(shape.type, ShapeType::Spline);
    ASSERT_TRUE(shape.spline);
    EXPECT_DOUBLE_EQ(shape.spline->radius, 0.01);
    EXPECT_TRUE(shape.spline->closed);
    EXPECT_FALSE(shape.spline->hollow);
    EXPECT_EQ(shape.spline->segments.size(), 3u);
    EXPECT_FALSE(shape.localBounds.isEmpty());
}

TEST(ShapeKeys, SplineDefaultsAndHollow) {
    const SceneDescription open =
        parseSceneText(staticShape(kSpline + R"(, "points": [[0, 0, 0], [1, 0, 0]])"), "t.json");
    EXPECT_FALSE(open.bodies[0].def.shape.spline->closed);
    EXPECT_FALSE(open.bodies[0].def.shape.spline->hollow);
    const SceneDescription pipe = parseSceneText(
        staticShape(kSpline + R"(, "points": [[0, 0, 0], [1, 0, 0]], "hollow": true)"), "t.json");
    EXPECT_TRUE(pipe.bodies[0].def.shape.spline->hollow);
}

TEST(ShapeKeys, SplineErrors) {
    const std::string two = R"(, "points": [[0, 0, 0], [1, 0, 0]])";
    EXPECT_TRUE(failsAt(staticShape(kSpline), "bodies[0].shape.points", "missing"));
    EXPECT_TRUE(failsAt(staticShape(kSpline + R"(, "points": [[0, 0, 0]])"),
                        "bodies[0].shape.points", "at least 2 points"));
    EXPECT_TRUE(failsAt(staticShape(kSpline + R"(, "points": 3)"), "bodies[0].shape.points",
                        "at least 2 points"));
    EXPECT_TRUE(failsAt(staticShape(kSpline + R"(, "points": [[0, 0, 0], [1, 0]])"),
                        "bodies[0].shape.points[1]", "3 numbers"));
    EXPECT_TRUE(failsAt(staticShape(kSpline + R"(, "points": [[0, 0, 0], [1, 2e6, 0]])"),
                        "bodies[0].shape.points[1][1]", "<= 1e+06"));
    EXPECT_TRUE(
        failsAt(staticShape(R"("type": "spline")" + two), "bodies[0].shape.radius", "missing"));
    EXPECT_TRUE(failsAt(staticShape(R"("type": "spline", "radius": -1)" + two),
                        "bodies[0].shape.radius", "> 0"));
    EXPECT_TRUE(failsAt(staticShape(kSpline + two + R"(, "closed": 1)"), "bodies[0].shape.closed",
                        "true or false"));
    EXPECT_TRUE(failsAt(staticShape(kSpline + two + R"(, "hollow": "yes")"),
                        "bodies[0].shape.hollow", "true or false"));
    EXPECT_TRUE(failsAt(staticShape(kSpline + two + R"(, "closed": true)"),
                        "bodies[0].shape.closed", "3 distinct points"));
    EXPECT_TRUE(failsAt(
        staticShape(kSpline + R"(, "points": [[0, 0, 0], [1, 0, 0], [0, 0, 0]], "closed": true)"),
        "bodies[0].shape.closed", "3 distinct points, got 2"));
    EXPECT_TRUE(failsAt(staticShape(kSpline + two + R"(, "radiuss": 1)"), "bodies[0].shape.radiuss",
                        "unknown key"));
    // Dynamic bodies cannot carry a spline.
    EXPECT_TRUE(failsAt(
        R"({"substep_scene": 1, "bodies": [{"mass": 1, "shape": {)" + kSpline + two + "}}]}",
        "bodies[0].shape.type", "static body"));
}

TEST(ShapeKeys, HeightfieldBuildsAGrid) {
    const SceneDescription s =
        parseSceneText(staticShape(kField + R"(, "heights": [[0, 1, 2], [3, 4, 5]])"), "t.json");
    const Shape& shape = s.bodies[0].def.shape;
    ASSERT_EQ(shape.type, ShapeType::Heightfield);
    ASSERT_TRUE(shape.heightfield);
    EXPECT_EQ(shape.heightfield->columns, 3);
    EXPECT_EQ(shape.heightfield->rows, 2);
    // Row 1, column 2: x = +2, z = +1.
    EXPECT_TRUE(shape.heightfield->vertex(2, 1).isApprox(Vec3(2, 5, 1)));
    EXPECT_TRUE(shape.localBounds.min.isApprox(Vec3(-2, 0, -1)));
    EXPECT_TRUE(shape.localBounds.max.isApprox(Vec3(2, 5, 1)));
}

TEST(ShapeKeys, HeightfieldErrors) {
    const std::string grid = R"(, "heights": [[0, 0], [0, 0]])";
    EXPECT_TRUE(failsAt(staticShape(kField), "bodies[0].shape.heights", "missing"));
    EXPECT_TRUE(failsAt(staticShape(kField + R"(, "heights": [[0, 0]])"), "bodies[0].shape.heights",
                        "at least 2 rows"));
    EXPECT_TRUE(failsAt(staticShape(kField + R"(, "heights": [[0, 0], 1])"),
                        "bodies[0].shape.heights[1]", "array of heights"));
    EXPECT_TRUE(failsAt(staticShape(kField + R"(, "heights": [[0], [0]])"),
                        "bodies[0].shape.heights[0]", "2 to 4096 heights, got 1"));
    EXPECT_TRUE(failsAt(staticShape(kField + R"(, "heights": [[0, 0, 0], [0, 0]])"),
                        "bodies[0].shape.heights[1]", "3 heights like row 0, got 2"));
    EXPECT_TRUE(failsAt(staticShape(kField + R"(, "heights": [[0, 0], [0, "x"]])"),
                        "bodies[0].shape.heights[1][1]", "must be a number"));
    EXPECT_TRUE(failsAt(staticShape(kField + R"(, "heights": [[0, 0], [0, 1e7]])"),
                        "bodies[0].shape.heights[1][1]", "<= 1e+06"));
    // Slopes: at most 1000 between neighbours along x (cells of 2 m here) and along z (cells of
    // 2 m): a rise of 2000 m is allowed, 2001 m is not, whichever way the neighbour lies.
    EXPECT_NO_THROW(parseSceneText(
        staticShape(kField + R"(, "heights": [[0, 2000, 0], [2000, 0, 2000]])"), "t.json"));
    EXPECT_TRUE(failsAt(staticShape(kField + R"(, "heights": [[0, 2001, 0], [0, 0, 0]])"),
                        "bodies[0].shape.heights[0][1]",
                        "differs by 2001 m from bodies[0].shape.heights[0][0], 2 m away: steeper "
                        "than a slope of 1000 (a sanity bound against absurd values)"));
    EXPECT_TRUE(failsAt(staticShape(kField + R"(, "heights": [[0, 0, 0], [0, 0, -2001]])"),
                        "bodies[0].shape.heights[1][2]", "from bodies[0].shape.heights[1][1]"));
    EXPECT_TRUE(failsAt(staticShape(kField + R"(, "heights": [[0, 0, 0], [2001, 0, 0]])"),
                        "bodies[0].shape.heights[1][0]",
                        "from bodies[0].shape.heights[0][0], 2 m away"));
    EXPECT_TRUE(
        failsAt(staticShape(R"("type": "heightfield")" + grid), "bodies[0].shape.size", "missing"));
    EXPECT_TRUE(failsAt(staticShape(R"("type": "heightfield", "size": [1, 0])" + grid),
                        "bodies[0].shape.size[1]", "> 0"));
    EXPECT_TRUE(failsAt(staticShape(R"("type": "heightfield", "size": [1, 2, 3])" + grid),
                        "bodies[0].shape.size", "[x, z]"));
    EXPECT_TRUE(failsAt(staticShape(kField + grid + R"(, "scale": 2)"), "bodies[0].shape.scale",
                        "unknown key"));
    EXPECT_TRUE(failsAt(R"({"substep_scene": 1, "bodies": [{"shape": {)" + kField + grid + "}}]}",
                        "bodies[0].shape.type", "static body"));
}

}  // namespace
}  // namespace substep
