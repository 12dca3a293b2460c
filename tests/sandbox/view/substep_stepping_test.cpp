// sandbox/view/view_session.cpp's substep stepping with sandbox/view/correction_layer.cpp: each
// substep stepped by hand lists what each constraint moved, largest first and named; the frame's
// last substep ends the frame, and a run stepped so (or finished mid-frame by a whole-frame
// step) draws the same state as one stepped whole frames; scrubbing back from mid-frame
// abandons the open frame; playing again stops the recording.

#include "scene_source.h"
#include "view/compare_session.h"
#include "view/correction_layer.h"
#include "view/view_session.h"

#include "ecs/components.h"

#include <gtest/gtest.h>

#include <cstring>

namespace substep::view {
namespace {

/// The bodies' poses and velocities as the world has them, as raw doubles.
std::vector<double> stateBits(const ViewSession& session) {
    std::vector<double> out{session.simulatedTime()};
    for (const Body& b : session.world().bodies())
        out.insert(out.end(), {b.x.x(), b.x.y(), b.x.z(), b.q.w(), b.q.x(), b.q.y(), b.q.z(),
                               b.v.x(), b.v.y(), b.v.z(), b.omega.x(), b.omega.y(), b.omega.z()});
    return out;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

TEST(SubstepStepping, EachSubstepListsItsCorrectionsAndTheFrameEndsAsAWholeStepWould) {
    ViewSession whole(resolveScene("cradle"), 16.0f / 9.0f);
    ViewSession split(resolveScene("cradle"), 16.0f / 9.0f);
    for (int frame = 0; frame < 30; ++frame) {
        whole.stepOnce();
        split.stepOnce();
    }
    EXPECT_TRUE(split.corrections().empty()) << "nothing recorded before a substep is stepped";
    const int substeps = split.world().settings().substeps;
    ASSERT_GT(substeps, 2);
    whole.stepOnce();
    for (int s = 1; s < substeps; ++s) {
        split.stepSubstep();
        ASSERT_TRUE(split.frameOpen());
        EXPECT_EQ(split.frameSubstepsDone(), s);
        EXPECT_EQ(split.frame(), 30);
        EXPECT_EQ(split.correctionsSubstep(), s);
        ASSERT_FALSE(split.corrections().empty()) << "the cradle's strings correct every substep";
        for (std::size_t i = 1; i < split.corrections().size(); ++i)
            EXPECT_GE(split.corrections()[i - 1].size, split.corrections()[i].size)
                << "largest first";
    }
    const std::string largest = split.corrections().front().describe();
    EXPECT_NE(largest.find(" moved '"), std::string::npos) << largest;
    split.stepSubstep();  // the last substep ends the frame
    EXPECT_FALSE(split.frameOpen());
    EXPECT_EQ(split.frame(), 31);
    EXPECT_EQ(split.correctionsSubstep(), substeps);
    EXPECT_TRUE(sameBits(stateBits(split), stateBits(whole)));
    EXPECT_EQ(split.timeline().lastFrame(), 31) << "the frame is kept";

    // Mid-frame, a whole-frame step finishes the frame.
    split.stepSubstep();
    split.stepSubstep();
    split.stepOnce();
    whole.stepOnce();
    EXPECT_FALSE(split.frameOpen());
    EXPECT_TRUE(sameBits(stateBits(split), stateBits(whole)));

    // The arrows: drawn while corrections are listed.
    split.stepSubstep();
    const render::RenderScene drawn = split.draw(split.startCamera());
    std::size_t lime = 0;
    for (const render::DebugLine& line : drawn.lines)
        if (line.colour.isApprox(render::Colour(0.6f, 1.0f, 0.0f))) ++lime;
    EXPECT_GE(lime, 3u) << "at least one arrow of three strokes";

    // Back from mid-frame: the open frame is abandoned and the kept frame shown.
    ASSERT_TRUE(split.scrubTo(32));
    EXPECT_FALSE(split.frameOpen());
    EXPECT_TRUE(sameBits(stateBits(split), stateBits(whole)));
}

TEST(SubstepStepping, PlayingAgainStopsTheRecording) {
    CompareSession session(resolveScene("hinge_bar"), 16.0f / 9.0f);
    session.stepSubstep();
    EXPECT_FALSE(session.playback().playing) << "a substep pauses";
    ASSERT_FALSE(session.first().corrections().empty());
    EXPECT_NE(session.first().corrections().front().describe().find("hinge 'hinge' moved 'bar'"),
              std::string::npos)
        << session.first().corrections().front().describe();
    session.playback().playing = true;
    session.advance(1.0 / 60.0);
    EXPECT_TRUE(session.first().corrections().empty());
    EXPECT_EQ(session.first().world().corrections(), nullptr)
        << "playing, the solve records nothing";
}

TEST(SubstepStepping, LengthsReadInTheirUnits) {
    EXPECT_EQ(formatLength(0.00042), "0.42 mm");
    EXPECT_EQ(formatLength(3.1e-6), "3.1 um");
    EXPECT_EQ(formatLength(1.5), "1.5 m");
    EXPECT_EQ(formatLength(2e-10), "0.2 nm");
}

}  // namespace
}  // namespace substep::view
