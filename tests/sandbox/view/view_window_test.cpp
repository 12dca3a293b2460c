// sandbox/view (view_app.cpp with input_queue.cpp): the real window under Xvfb, driven by
// xdotool as a user would. Key taps arrive through the input queue, so a tap of Space pauses and
// a second resumes even while each frame takes a tenth of a second or more (the full quality on
// Mesa's software rasteriser); F1 shows the controls over the view; P and Shift+P write PNGs in
// the working folder, of the window and of the view alone; Tab hides the panel. The window's
// title says when it is paused and at which frame, which is what the script reads back.

#include "../command_test_support.h"

#include "render/png_codec.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <regex>

namespace substep::command_test {
namespace {

bool haveXvfbAndXdotool() {
    return std::system("command -v xvfb-run >/dev/null 2>&1 && command -v xdotool >/dev/null 2>&1") == 0;
}

/// Helpers of every driving script: the window's id once it is mapped, waits on its title and on
/// files (each gives up after 60 s and says so), and a clean stop of the program.
constexpr const char* kScriptPrelude = R"sh(
set -u
"$SUBSTEP" "$@" >app.out 2>app.err &
app=$!
trap 'kill $app 2>/dev/null; wait $app 2>/dev/null' EXIT
win=$(timeout 60 xdotool search --sync --onlyvisible --name '^Substep - ' | head -n 1)
[ -n "$win" ] || { echo "NO WINDOW"; exit 1; }
xdotool mousemove --window "$win" 700 20 windowfocus "$win" 2>/dev/null
title() { xdotool getwindowname "$win"; }
wait_title() {  # a substring the title must come to contain ("" waits for none of "paused")
  for _ in $(seq 1 600); do
    t=$(title)
    if [ -n "$1" ]; then case "$t" in *"$1"*) echo "$t"; return 0;; esac
    else case "$t" in *paused*) ;; *) echo "$t"; return 0;; esac; fi
    sleep 0.1
  done
  echo "TIMEOUT waiting for '$1': $t"; exit 1
}
wait_files() {  # until N files match the glob
  for _ in $(seq 1 600); do
    [ "$(ls $2 2>/dev/null | wc -l)" -ge "$1" ] && { ls $2; return 0; }
    sleep 0.1
  done
  echo "TIMEOUT waiting for $1 of $2"; exit 1
}
pause_at_frame() {  # Space; says "paused <title>" and sets n to the frame it paused at
  xdotool key space
  local t
  t=$(wait_title 'paused at frame')
  n=$(echo "$t" | sed -n 's/.*paused at frame \([0-9]*\).*/\1/p')
  echo "paused $t"
}
shoot() {  # Shift+P (the view alone) once it has settled, until N shots are written
  sleep 0.5
  xdotool key shift+p
  wait_files "$1" 'substep_*_f*.png'
}
sleep 1
)sh";

class ViewWindowTest : public CommandTest {
  protected:
    /// Runs `body` after the prelude under xvfb-run with `arguments` for substep; its stdout.
    std::string drive(const std::string& arguments, const std::string& body) {
        const fs::path script = work().parent_path() / "drive.sh";
        {
            std::ofstream file(script);
            file << kScriptPrelude << body << "\necho DONE\n";
        }
        const fs::path out = work().parent_path() / "drive.out";
        const std::string command = "cd " + quoted(work().string()) + " && SUBSTEP=" + quoted(SUBSTEP_EXECUTABLE) +
                                    " timeout 300 xvfb-run -a -s '-screen 0 1600x1000x24' bash " +
                                    quoted(script.string()) + " " + arguments + " >" + quoted(out.string()) + " 2>&1";
        std::system(command.c_str());
        return readFile(out);
    }

    /// The view shots whose names start with `stem` (paused at frame N: stemN.png, stemN_2.png,
    /// ...), in taking order.
    std::vector<std::string> shotsOf(const std::string& stem) {
        std::vector<std::string> shots;
        for (const std::string& name : workEntries())
            if (name.rfind(stem, 0) == 0) shots.push_back(name);
        std::sort(shots.begin(), shots.end(), [](const std::string& a, const std::string& b) {
            return a.size() != b.size() ? a.size() < b.size() : a < b;
        });
        return shots;
    }

    /// The script's output lines by their first word ("paused ...", "back ..."); the last wins.
    static std::map<std::string, std::string> saidLines(const std::string& out) {
        std::map<std::string, std::string> said;
        for (const std::string& line : lines(out)) said[line.substr(0, line.find(' '))] = line;
        return said;
    }

    /// The frame in a title "Substep - cradle (paused at frame 42, t = ...)".
    static long long pausedFrame(const std::string& line) {
        std::smatch match;
        if (!std::regex_search(line, match, std::regex("paused at frame ([0-9]+)"))) return -1;
        return std::stoll(match[1]);
    }
};

TEST_F(ViewWindowTest, SpaceTapsPauseAndResumeAtALowFrameRate) {
    if (!haveXvfbAndXdotool()) GTEST_SKIP() << "needs xvfb-run and xdotool (tools/install-deps.sh)";
    // Full quality on a software rasteriser at this size: frames of 100 ms and more, so each tap
    // (press and release a few milliseconds apart) falls within one frame.
    const std::string out = drive("view cradle --size 1200x800 --quality full", R"sh(
xdotool key space
echo "first $(wait_title 'paused at frame')"
sleep 1
echo "still $(title)"
xdotool key space
echo "resumed $(wait_title '')"
sleep 1
xdotool key space
echo "second $(wait_title 'paused at frame')"
)sh");
    ASSERT_NE(out.find("DONE"), std::string::npos) << out;
    std::map<std::string, std::string> said = saidLines(out);
    const long long first = pausedFrame(said["first"]);
    ASSERT_GE(first, 0) << out;
    EXPECT_EQ(pausedFrame(said["still"]), first) << "a paused scene must not step: " << out;
    EXPECT_EQ(said["resumed"].find("paused"), std::string::npos) << out;
    EXPECT_GT(pausedFrame(said["second"]), first) << "resumed, the scene steps on: " << out;
}

TEST_F(ViewWindowTest, F1ShowsTheControlsAndScreenshotKeysWritePngs) {
    if (!haveXvfbAndXdotool()) GTEST_SKIP() << "needs xvfb-run and xdotool (tools/install-deps.sh)";
    const std::string out = drive("view cradle --size 1000x700", R"sh(
xdotool key space
wait_title 'paused at frame'
sleep 0.5
xdotool key p
wait_files 1 'substep_cradle_f*.png'
xdotool key F1
sleep 0.5
xdotool key p
wait_files 2 'substep_cradle_f*.png'
xdotool key F1 Tab
sleep 0.5
xdotool key p
wait_files 3 'substep_cradle_f*.png'
xdotool key Tab shift+p
wait_files 4 'substep_cradle_f*.png'
)sh");
    ASSERT_NE(out.find("DONE"), std::string::npos) << out;
    // Paused at frame N, every shot is named substep_cradle_fN[_k].png, in taking order.
    const std::vector<std::string> shots = shotsOf("substep_cradle_f");
    ASSERT_EQ(shots.size(), 4u) << out;
    const render::Image plain = render::decodePng(readFile(work() / shots[0]));
    const render::Image help = render::decodePng(readFile(work() / shots[1]));
    const render::Image hidden = render::decodePng(readFile(work() / shots[2]));
    const render::Image viewOnly = render::decodePng(readFile(work() / shots[3]));
    ASSERT_EQ(plain.width, 1000);
    ASSERT_EQ(plain.height, 700);
    EXPECT_EQ(viewOnly.width, 1000 - 380);  // the view beside the panel, without it
    EXPECT_EQ(viewOnly.height, 700);

    auto meanBrightness = [](const render::Image& image, int x0, int y0, int x1, int y1) {
        double sum = 0.0;
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
                const uint8_t* p = image.pixel(x, y);
                sum += (p[0] + p[1] + p[2]) / 3.0;
            }
        }
        return sum / ((x1 - x0) * (y1 - y0));
    };
    // The overlay is a dark table in the middle of the view (x 380..1000), over the sky and the
    // ground; the panel a dark column at the left, gone once Tab hides it.
    const double viewPlain = meanBrightness(plain, 600, 300, 780, 400);
    EXPECT_LT(meanBrightness(help, 600, 300, 780, 400), 0.6 * viewPlain) << "F1 must darken the view with its table";
    EXPECT_LT(meanBrightness(plain, 20, 300, 300, 400), 0.5 * meanBrightness(hidden, 20, 300, 300, 400))
        << "Tab must hide the panel";
    // Shift+P's picture is the view itself: its middle matches the window's view.
    EXPECT_NEAR(meanBrightness(viewOnly, 220, 300, 400, 400), viewPlain, 2.0);
}

TEST_F(ViewWindowTest, AClickSelectsTheBodyAndOutlinesIt) {
    if (!haveXvfbAndXdotool()) GTEST_SKIP() << "needs xvfb-run and xdotool (tools/install-deps.sh)";
    // hinge_bar's start camera frames the mount and the bar: the middle of the view (x 380..1000
    // beside the panel) is on the bar. The inspector's readout of it (mass 1 kg, the hinge's
    // 2 N m) is checked in process (body_inspector_test.cpp); here the click through the real
    // window selects it and the view outlines it in yellow.
    const std::string out = drive("view hinge_bar --size 1000x700", R"sh(
xdotool mousemove --window "$win" 690 350 key space
wait_title 'paused at frame'
shoot 1
xdotool click 1
shoot 2
)sh");
    ASSERT_NE(out.find("DONE"), std::string::npos) << out;
    const std::vector<std::string> shots = shotsOf("substep_hinge_bar_f");
    ASSERT_EQ(shots.size(), 2u) << out;
    const auto yellowPixels = [](const render::Image& image) {
        std::size_t count = 0;
        for (int y = 0; y < image.height; ++y) {
            for (int x = 0; x < image.width; ++x) {
                const uint8_t* p = image.pixel(x, y);
                if (p[0] > 200 && p[1] > 150 && p[1] < 240 && p[2] < 90) ++count;
            }
        }
        return count;
    };
    const std::size_t before = yellowPixels(render::decodePng(readFile(work() / shots[0])));
    const std::size_t after = yellowPixels(render::decodePng(readFile(work() / shots[1])));
    EXPECT_LT(before, 20u);
    EXPECT_GT(after, 300u) << "the selected bar's outline";
}

TEST_F(ViewWindowTest, ScrubbingBackTenFramesAndSteppingOnRedrawsTheSameState) {
    if (!haveXvfbAndXdotool()) GTEST_SKIP() << "needs xvfb-run and xdotool (tools/install-deps.sh)";
    // The cradle (a scripted scene) paused at frame N, its view shot; Left x 10 shows frame N-10
    // from the timeline; S x 10 steps anew from there (the kept later frames dropped) back to
    // frame N, whose view must be the same picture, pixel for pixel.
    const std::string out = drive("view cradle --size 1000x700", R"sh(
pause_at_frame
shoot 1
xdotool key --delay 30 Left Left Left Left Left Left Left Left Left Left
echo "back $(wait_title "paused at frame $((n - 10)),")"
xdotool key --delay 30 s s s s s s s s s s
echo "again $(wait_title "paused at frame $n,")"
shoot 2
)sh");
    ASSERT_NE(out.find("DONE"), std::string::npos) << out;
    const std::vector<std::string> shots = shotsOf("substep_cradle_f");
    ASSERT_EQ(shots.size(), 2u) << out;
    const render::Image first = render::decodePng(readFile(work() / shots[0]));
    const render::Image again = render::decodePng(readFile(work() / shots[1]));
    ASSERT_EQ(first.width, again.width);
    ASSERT_EQ(first.height, again.height);
    EXPECT_TRUE(first.rgba == again.rgba) << "the resumed run must redraw frame N as it was: " << out;
}

TEST_F(ViewWindowTest, LayerKeysAddBoxesCentresAndVelocitiesToTheViewAndTakeThemAway) {
    if (!haveXvfbAndXdotool()) GTEST_SKIP() << "needs xvfb-run and xdotool (tools/install-deps.sh)";
    // The cradle paused while its marbles swing (light quality, as Xvfb's software GL starts):
    // the view alone shot plain, with B (the broadphase's boxes), with B, M and V (centres of
    // mass and velocities too), and plain again once all three are toggled off.
    const std::string out = drive("view cradle --size 1000x700", R"sh(
sleep 1
xdotool key space
wait_title 'paused at frame'
shoot 1
xdotool key b
shoot 2
xdotool key m v
shoot 3
xdotool key b m v
shoot 4
)sh");
    ASSERT_NE(out.find("DONE"), std::string::npos) << out;
    const std::vector<std::string> shots = shotsOf("substep_cradle_f");
    ASSERT_EQ(shots.size(), 4u) << out;
    std::vector<render::Image> images;
    for (const std::string& shot : shots) images.push_back(render::decodePng(readFile(work() / shot)));
    const auto differing = [](const render::Image& a, const render::Image& b) {
        std::size_t count = 0;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x)
                for (int c = 0; c < 3; ++c)
                    if (std::abs(int(a.pixel(x, y)[c]) - int(b.pixel(x, y)[c])) > 24) {
                        ++count;
                        break;
                    }
        return count;
    };
    for (const render::Image& image : images) ASSERT_EQ(image.rgba.size(), images[0].rgba.size());
    EXPECT_GT(differing(images[0], images[1]), 300u) << "B draws boxes around the marbles and the frame";
    EXPECT_GT(differing(images[1], images[2]), 50u) << "M and V add centres and arrows";
    EXPECT_TRUE(images[0].rgba == images[3].rgba) << "toggled off, the view is as it was";
}

TEST_F(ViewWindowTest, SubstepKeysAdvanceTheSubstepCounterAndTheFinishedFrameIsTheWholeFrame) {
    if (!haveXvfbAndXdotool()) GTEST_SKIP() << "needs xvfb-run and xdotool (tools/install-deps.sh)";
    // The cradle paused at frame N (its view shot before any substep). Frame N stepped whole (S from N-1) is shot; then, from N-1
    // again, three substeps by hand (. . Shift+Right): the title counts "substep 3/", the view
    // draws the corrections' lime arrows; S finishes the frame, and frame N's view is the
    // whole-frame one pixel for pixel (both with the last substep's arrows, as recording was on).
    const std::string out = drive("view cradle --size 1000x700", R"sh(
pause_at_frame
shoot 1
xdotool key period
echo "one $(wait_title "paused at frame $n, substep 1/")"
xdotool key Left
wait_title "paused at frame $((n - 1)), t"
xdotool key s
echo "whole $(wait_title "paused at frame $n, t")"
shoot 2
xdotool key Left
wait_title "paused at frame $((n - 1)), t"
xdotool key --delay 30 period period shift+Right
echo "three $(wait_title "paused at frame $((n - 1)), substep 3/")"
shoot 3
xdotool key s
echo "finished $(wait_title "paused at frame $n, t")"
shoot 4
)sh");
    ASSERT_NE(out.find("DONE"), std::string::npos) << out;
    std::map<std::string, std::string> said = saidLines(out);
    const long long n = pausedFrame(said["paused"]);
    ASSERT_GT(n, 0) << out;
    EXPECT_NE(said["one"].find("substep 1/"), std::string::npos) << out;
    EXPECT_NE(said["three"].find("substep 3/"), std::string::npos) << out;
    const std::string stem = "substep_cradle_f";
    const fs::path plain = work() / (stem + std::to_string(n) + ".png");
    const fs::path whole = work() / (stem + std::to_string(n) + "_2.png");
    const fs::path middle = work() / (stem + std::to_string(n - 1) + ".png");
    const fs::path finished = work() / (stem + std::to_string(n) + "_3.png");
    ASSERT_TRUE(fs::exists(plain) && fs::exists(whole) && fs::exists(middle) && fs::exists(finished)) << out;
    const render::Image plainImage = render::decodePng(readFile(plain));
    const render::Image wholeImage = render::decodePng(readFile(whole));
    const render::Image middleImage = render::decodePng(readFile(middle));
    const render::Image finishedImage = render::decodePng(readFile(finished));
    EXPECT_TRUE(wholeImage.rgba == finishedImage.rgba) << "a frame finished after substeps is the whole frame";
    const auto limePixels = [](const render::Image& image) {
        std::size_t count = 0;
        for (int y = 0; y < image.height; ++y) {
            for (int x = 0; x < image.width; ++x) {
                const uint8_t* p = image.pixel(x, y);
                if (p[0] > 90 && p[0] < 210 && p[1] > 200 && p[2] < 80) ++count;
            }
        }
        return count;
    };
    EXPECT_GT(limePixels(middleImage), limePixels(plainImage) + 20) << "the corrections' arrows";
}

TEST_F(ViewWindowTest, TheCarsKeysSteerWhilePlayingAndStepSubstepsWhilePaused) {
    if (!haveXvfbAndXdotool()) GTEST_SKIP() << "needs xvfb-run and xdotool (tools/install-deps.sh)";
    // rc_car binds WASD and the arrows to its throttle and steering. Paused, Shift+Right steps a
    // substep (the title counts it) and Left scrubs back a frame, as in any scene; the view then
    // draws the tyres' particle corrections and the velocity pass's changes. Playing,
    // Shift+Right steers and leaves the run playing (it used to steer and step a substep).
    const std::string out = drive("view rc_car --size 1000x700", R"sh(
sleep 1
pause_at_frame
shoot 1
xdotool key shift+Right
echo "substep $(wait_title "paused at frame $n, substep 1/")"
shoot 2
xdotool key Left
echo "back $(wait_title "paused at frame $((n - 1)), t")"
xdotool key space
wait_title ''
xdotool keydown shift+Right
sleep 1
xdotool keyup shift+Right
sleep 0.5
echo "playing $(title)"
)sh");
    ASSERT_NE(out.find("DONE"), std::string::npos) << out;
    std::map<std::string, std::string> said = saidLines(out);
    const long long n = pausedFrame(said["paused"]);
    ASSERT_GT(n, 0) << out;
    EXPECT_NE(said["substep"].find("substep 1/"), std::string::npos) << out;
    EXPECT_EQ(pausedFrame(said["back"]), n - 1) << out;
    EXPECT_EQ(said["playing"].find("paused"), std::string::npos) << "Shift+Right steered, no substep: " << out;
    const fs::path plain = work() / ("substep_rc_car_f" + std::to_string(n) + ".png");
    const fs::path stepped = work() / ("substep_rc_car_f" + std::to_string(n) + "_2.png");
    ASSERT_TRUE(fs::exists(plain) && fs::exists(stepped)) << out;
    // Lime (the elements' particle arrows) and pink (the velocity pass's: the tyres' bounce
    // off the ground, the suspension's damping).
    const auto correctionPixels = [](const render::Image& image) {
        std::size_t count = 0;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                const uint8_t* p = image.pixel(x, y);
                const bool lime = p[0] > 90 && p[0] < 210 && p[1] > 200 && p[2] < 80;
                const bool pink = p[0] > 200 && p[1] > 60 && p[1] < 170 && p[2] > 140 && p[2] < 230;
                count += lime || pink;
            }
        return count;
    };
    const std::size_t before = correctionPixels(render::decodePng(readFile(plain)));
    const std::size_t after = correctionPixels(render::decodePng(readFile(stepped)));
    // Quiet, the step adds about 280 pixels; on a loaded machine the pause comes earlier in the
    // car's settling and the step has added as few as 150. Before the step, 1-5 pixels are of these colours.
    EXPECT_GT(after, before + 60) << "the tyres' and the velocity pass's arrows: " << before << " -> " << after;
}

TEST_F(ViewWindowTest, HelpListsTheControls) {
    const Result result = substep("view --help");
    EXPECT_EQ(result.exitCode, 0);
    for (const char* expected :
         {"Controls in the window", "Space", "F1", "Tab", "Ctrl + left drag", "--quality", "broadphase boxes",
          ". or Shift+Right"}) {
        EXPECT_NE(result.out.find(expected), std::string::npos) << expected << "\n" << result.out;
    }
}

}  // namespace
}  // namespace substep::command_test
