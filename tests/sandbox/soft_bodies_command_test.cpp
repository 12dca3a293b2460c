// Tests the `substep` program on assets/scenes/soft_bodies.json (a soft box dropped on the ground,
// a soft tyre on a rigid rim swinging from a hinge) by running the built binary: `run --csv` has
// DESIGN.md's soft-body columns after the joint columns, and they read what physics says: the
// box's centre falls at g before it touches the ground, the tyre's volume is its lattice's, and
// the rim carrying its tyre swings with the period of the pair's combined inertia.

#include "command_test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace substep {
namespace {

using command_test::CommandTest;
using command_test::lines;
using command_test::quoted;
using command_test::readFile;
namespace fs = std::filesystem;

const fs::path kScene = fs::path(SUBSTEP_ASSETS) / "scenes" / "soft_bodies.json";
// The scene file's settings and bodies.
constexpr double kG = 9.81, kDt = 1.0 / 60.0, kSubsteps = 20.0, kDensity = 1000.0;
constexpr double kBoxY0 = 1.5, kBoxSize = 0.4, kParticleRadius = 0.01;
constexpr double kRimRadius = 0.2, kRimLength = 0.1;
constexpr double kTyreOuter = 0.3, kTyreInner = 0.2, kTyreWidth = 0.1;
constexpr int kTyreAround = 24;
constexpr double kPivotX = 1.2, kArm = 0.6, kAmplitude = 0.5;  // m, m, rad

/// The CSV as columns by name, one value per row.
std::map<std::string, std::vector<double>> readColumns(const std::string& text, std::vector<std::string>& header) {
    const std::vector<std::string> rows = lines(text);
    std::map<std::string, std::vector<double>> columns;
    header.clear();
    if (rows.empty()) return columns;
    std::istringstream names(rows[0]);
    for (std::string name; std::getline(names, name, ',');) header.push_back(name);
    for (std::size_t r = 1; r < rows.size(); ++r) {
        std::istringstream cells(rows[r]);
        std::size_t c = 0;
        for (std::string cell; std::getline(cells, cell, ',') && c < header.size(); ++c)
            columns[header[c]].push_back(std::stod(cell));
    }
    return columns;
}

class SoftBodiesCommand : public CommandTest {
  protected:
    std::map<std::string, std::vector<double>> run(double seconds, std::vector<std::string>& header) {
        const command_test::Result result =
            substep("run " + quoted(kScene.string()) + " --seconds " + std::to_string(seconds) + " --csv out.csv");
        EXPECT_EQ(result.exitCode, 0) << result.err;
        return readColumns(readFile(work() / "out.csv"), header);
    }
};

TEST_F(SoftBodiesCommand, SoftColumnsFollowTheJointColumns) {
    std::vector<std::string> header;
    run(0.1, header);
    const std::vector<std::string> soft = {"x", "y", "z", "vx", "vy", "vz", "ex", "ey", "ez", "volume"};
    std::vector<std::string> expected = {"axle.force", "axle.torque", "axle.error"};
    for (const char* name : {"jelly", "tyre"})
        for (const std::string& column : soft) expected.push_back(std::string(name) + "." + column);
    ASSERT_GE(header.size(), expected.size());
    EXPECT_EQ(std::vector<std::string>(header.end() - static_cast<std::ptrdiff_t>(expected.size()), header.end()),
              expected);
}

TEST_F(SoftBodiesCommand, TheBoxFallsAtGUntilItTouchesTheGround) {
    std::vector<std::string> header;
    const auto columns = run(1.0, header);
    const std::vector<double>& y = columns.at("jelly.y");
    const std::vector<double>& vy = columns.at("jelly.vy");
    const double h = kDt / kSubsteps;
    // Its particles (radius 1 cm) reach the ground after falling y0 − size/2 − radius.
    const double contact = std::sqrt(2.0 * (kBoxY0 - kBoxSize / 2.0 - kParticleRadius) / kG);
    int checked = 0;
    for (std::size_t frame = 0; frame < y.size(); ++frame) {
        const double t = static_cast<double>(frame) * kDt;
        if (t > contact - 2.0 * kDt) break;
        SCOPED_TRACE(frame);
        // y0 − g t²/2 within the discrete error g t h / 2 of symplectic Euler at substep h.
        EXPECT_LE(std::abs(y[frame] - (kBoxY0 - kG * t * t / 2.0)), kG * t * h / 2.0 + 1e-9);
        EXPECT_NEAR(y[frame], kBoxY0 - kG * t * t / 2.0 - kG * t * h / 2.0, 1e-9);
        EXPECT_NEAR(vy[frame], -kG * t, 1e-7);
        // Falling freely, it keeps its shape.
        EXPECT_NEAR(columns.at("jelly.ey")[frame], kBoxSize, 1e-9);
        EXPECT_NEAR(columns.at("jelly.volume")[frame], kBoxSize * kBoxSize * kBoxSize, 1e-9);
        ++checked;
    }
    EXPECT_GE(checked, 25);
    // Then it lands: it is never pushed through the ground, and comes to rest on it.
    for (double value : y) EXPECT_GT(value, kBoxSize / 4.0);
    EXPECT_NEAR(vy.back(), 0.0, 0.2);
}

TEST_F(SoftBodiesCommand, TheTyreSwingsOnItsRimWithTheCombinedInertia) {
    std::vector<std::string> header;
    const auto columns = run(4.0, header);
    // The lattice's volume: 24 trapezoidal sectors, a polygonal annulus (n/2) sin(2π/n) (R² − r²) w.
    const double tyreVolume = kTyreAround / 2.0 * std::sin(2.0 * M_PI / kTyreAround) *
                              (kTyreOuter * kTyreOuter - kTyreInner * kTyreInner) * kTyreWidth;
    EXPECT_NEAR(columns.at("tyre.volume")[0], tyreVolume, 1e-12);

    // A compound pendulum of rim and tyre (the tyre's inertia about its axis that of its annulus),
    // swinging 0.5 rad: T = 2π sqrt(I_pivot / (M g L)) (1 + θ²/16 + 11 θ⁴/3072).
    const double rimMass = kDensity * M_PI * kRimRadius * kRimRadius * kRimLength;
    const double tyreMass = kDensity * tyreVolume;
    const double mass = rimMass + tyreMass;
    const double inertia = rimMass * kRimRadius * kRimRadius / 2.0 +
                           tyreMass * (kTyreOuter * kTyreOuter + kTyreInner * kTyreInner) / 2.0 + mass * kArm * kArm;
    const double theta2 = kAmplitude * kAmplitude;
    const double period = 2.0 * M_PI * std::sqrt(inertia / (mass * kG * kArm)) * (1.0 + theta2 / 16.0 + 11.0 * theta2 * theta2 / 3072.0);

    // Half periods between the rim's crossings of the vertical below the pivot.
    const std::vector<double>& x = columns.at("rim.x");
    std::vector<double> crossings;
    for (std::size_t i = 1; i < x.size(); ++i) {
        const double a = x[i - 1] - kPivotX, b = x[i] - kPivotX;
        if ((a > 0.0) != (b > 0.0)) crossings.push_back((static_cast<double>(i - 1) + a / (a - b)) * kDt);
    }
    ASSERT_GE(crossings.size(), 4u);
    const double measured = 2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    EXPECT_NEAR(measured, period, 0.01 * period);

    // The tyre goes with its rim: its centre of mass stays on the rim's axis.
    const std::vector<double>& tx = columns.at("tyre.x");
    const std::vector<double>& ty = columns.at("tyre.y");
    const std::vector<double>& ry = columns.at("rim.y");
    for (std::size_t i = 0; i < tx.size(); ++i) EXPECT_LT(std::hypot(tx[i] - x[i], ty[i] - ry[i]), 0.005) << i;
}

TEST_F(SoftBodiesCommand, RendersTheSoftSurfaces) {
    const command_test::Result result =
        substep("render " + quoted(kScene.string()) + " --frames 0,30 --out png --size 64x48");
    if (result.exitCode != 0 && result.err.find("EGL") != std::string::npos) GTEST_SKIP() << result.err;
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_TRUE(fs::exists(work() / "png" / "frame_00030.png"));
}

}  // namespace
}  // namespace substep
