// sandbox/view/view_session.cpp's substep stepping with sandbox/view/correction_layer.cpp: each
// substep stepped by hand lists what each constraint moved, largest first and named; the frame's
// last substep ends the frame, and a run stepped so (or finished mid-frame by a whole-frame
// step) draws the same state as one stepped whole frames; scrubbing back from mid-frame
// abandons the open frame; playing again stops the recording. The velocity pass and the soft
// bodies' stages are listed and drawn too (the RC car's tyres, a landing ball's bounce). In
// compare mode one substep keeps the two runs at the same moment, whatever their splits.

#include "scene_source.h"
#include "view/compare_session.h"
#include "view/correction_layer.h"
#include "view/view_session.h"

#include "ecs/components.h"
#include "physics/soft/soft_system.h"

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
    EXPECT_NE(session.first().corrections().front().describe().find("hinge joint 'hinge' moved 'bar'"),
              std::string::npos)
        << session.first().corrections().front().describe();
    session.playback().playing = true;
    session.advance(1.0 / 60.0);
    EXPECT_TRUE(session.first().corrections().empty());
    EXPECT_EQ(session.first().world().corrections(), nullptr)
        << "playing, the solve records nothing";
}

TEST(SubstepStepping, TheVelocityPassIsListedAndDrawn) {
    // spheres1000's spheres fall onto a pile: landings and slides change velocities.
    ViewSession run(resolveScene("spheres1000"), 16.0f / 9.0f);
    for (int frame = 0; frame < 40; ++frame) run.stepOnce();
    bool listed = false;
    for (int s = 0; s < run.world().settings().substeps && !listed; ++s) {
        run.stepSubstep();
        listed = !run.velocityChanges().empty();
    }
    ASSERT_TRUE(listed) << "a contact changed a velocity in one of the frame's substeps";
    const VelocityEntry& largest = run.velocityChanges().front();
    EXPECT_NE(largest.describe().find(" changed '"), std::string::npos) << largest.describe();
    for (std::size_t i = 1; i < run.velocityChanges().size(); ++i)
        EXPECT_GE(run.velocityChanges()[i - 1].size, run.velocityChanges()[i].size);
    const render::RenderScene drawn = run.draw(run.startCamera());
    std::size_t pink = 0;
    for (const render::DebugLine& line : drawn.lines)
        if (line.colour.isApprox(render::Colour(1.0f, 0.45f, 0.75f))) ++pink;
    EXPECT_GE(pink, 3u) << "at least one arrow of three strokes";
}

TEST(SubstepStepping, TheTyresCorrectionsAreListedAndDrawn) {
    ViewSession run(resolveScene("rc_car"), 16.0f / 9.0f);
    ViewSession whole(resolveScene("rc_car"), 16.0f / 9.0f);
    for (int frame = 0; frame < 20; ++frame) {
        run.stepOnce();
        whole.stepOnce();
    }
    run.stepSubstep();
    bool elements = false, attachments = false, rims = false;
    for (const SoftStageEntry& entry : run.softCorrections()) {
        EXPECT_GT(entry.moved, 0);
        EXPECT_GT(entry.largest, 0.0);
        elements |= entry.stage == SoftStage::Elements;
        attachments |= entry.stage == SoftStage::Attachments;
    }
    EXPECT_TRUE(elements) << "the tyres' elements correct every substep";
    EXPECT_TRUE(attachments) << "and their attachments to the rims";
    for (const CorrectionEntry& entry : run.corrections())
        rims |= entry.kind == ConstraintKind::SoftAttachments;
    EXPECT_TRUE(rims) << "the attachments move the rims too";
    ASSERT_FALSE(run.softCorrections().empty());
    EXPECT_NE(run.softCorrections().front().describe().find("soft elements of '"), std::string::npos)
        << run.softCorrections().front().describe();
    const render::RenderScene drawn = run.draw(run.startCamera());
    std::size_t sand = 0;
    for (const render::DebugLine& line : drawn.lines)
        if (line.colour.isApprox(softStageColour(SoftStage::Attachments))) ++sand;
    EXPECT_GE(sand, 3u);
    // Recorded stage by stage, the tyres solve as they do in one piece: the frame finished by
    // substeps is the whole frame, particles included.
    while (run.frameOpen()) run.stepSubstep();
    whole.stepOnce();
    EXPECT_TRUE(sameBits(stateBits(run), stateBits(whole)));
    const std::span<const Vec3> particles = run.world().softBodies()->particlePositions();
    const std::span<const Vec3> wholeParticles = whole.world().softBodies()->particlePositions();
    ASSERT_EQ(particles.size(), wholeParticles.size());
    EXPECT_EQ(std::memcmp(particles.data(), wholeParticles.data(), particles.size_bytes()), 0);
}

// (left substeps, right substeps)
class CompareSubsteps : public testing::TestWithParam<std::pair<int, int>> {};

TEST_P(CompareSubsteps, OneSubstepKeepsBothRunsAtTheSameMoment) {
    const auto [left, right] = GetParam();
    CompareSession session(resolveScene("pendulum3"), 16.0f / 9.0f);
    session.compare(CompareSplits{{{left, 1}, {right, 1}}});
    CompareSession whole(resolveScene("pendulum3"), 16.0f / 9.0f);
    whole.compare(CompareSplits{{{left, 1}, {right, 1}}});
    for (int frame = 0; frame < 5; ++frame) {
        session.stepOnce();
        whole.stepOnce();
    }
    whole.stepOnce();
    const int most = std::max(left, right);
    for (int press = 1; press <= most; ++press) {
        session.stepSubstep();
        for (std::size_t index = 0; index < 2; ++index) {
            const ViewSession& run = session.run(index);
            const int substeps = index == 0 ? left : right;
            // The substeps that end by the finest run's moment press / most.
            const int done = press * substeps / most;
            const int doneBefore = (press - 1) * substeps / most;
            EXPECT_EQ(session.steppedLastSubstep(index), done != doneBefore) << "run " << index << ", press " << press;
            if (press < most) {
                EXPECT_EQ(run.frame(), 5) << "run " << index << ", press " << press;
                EXPECT_EQ(run.frameOpen() ? run.frameSubstepsDone() : 0, done)
                    << "run " << index << ", press " << press;
            }
        }
    }
    // The frame ends in both runs together, each as its whole-frame step left it.
    for (std::size_t index = 0; index < 2; ++index) {
        EXPECT_EQ(session.run(index).frame(), 6) << index;
        EXPECT_FALSE(session.run(index).frameOpen()) << index;
        EXPECT_TRUE(sameBits(stateBits(session.run(index)), stateBits(whole.run(index)))) << index;
    }
    // Scrubbing moves both runs' timelines; resuming replays both byte for byte.
    session.scrubTo(3);
    EXPECT_EQ(session.run(0).frame(), 3);
    EXPECT_EQ(session.run(1).frame(), 3);
    session.stepOnce();
    session.stepOnce();
    session.stepOnce();
    for (std::size_t index = 0; index < 2; ++index)
        EXPECT_TRUE(sameBits(stateBits(session.run(index)), stateBits(whole.run(index)))) << index;
}

INSTANTIATE_TEST_SUITE_P(Splits, CompareSubsteps,
                         testing::Values(std::make_pair(20, 1), std::make_pair(1, 20), std::make_pair(20, 7),
                                         std::make_pair(6, 4)));

TEST(SubstepStepping, LengthsReadInTheirUnits) {
    EXPECT_EQ(formatLength(0.00042), "0.42 mm");
    EXPECT_EQ(formatLength(3.1e-6), "3.1 um");
    EXPECT_EQ(formatLength(1.5), "1.5 m");
    EXPECT_EQ(formatLength(2e-10), "0.2 nm");
}

}  // namespace
}  // namespace substep::view
