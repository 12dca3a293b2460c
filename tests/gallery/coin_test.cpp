// Tests sandbox/scenes/coin.cpp (paper Fig. 15): the spun coin rolls on its rim like Euler's
// disk, its wobble (the precession of its axis) speeding up as it tilts down as steady rolling
// predicts, and it ends flat and at rest on the table.
//
// The reference, derived here independently of the scene: a coin of radius a, thickness t,
// moments A = m(3a² + t²)/12 (diameter) and C = m a²/2 (axis), rolling without slipping with
// its centre at rest and its face at angle α to the table. The contact point is at rest, so the
// angular velocity lies along ρ, the vector from the centre to the contact point, and
// precession of the axis e at rate Ω about the vertical (ė = Ω ẑ × e) fixes it to
// ω = −(Ω sin α / a) ρ. Its angular momentum L = −Ω sin α (A d − C (t/2a) e) (d the unit
// vector down the face towards the contact) turns with the frame: dL/dt = Ω ẑ × L, and equals
// the weight's torque about the centre, ρ × m g ẑ (the normal force is m g; friction vanishes
// with the centre at rest). Along the horizontal axis of the face:
//     Ω² sin α (A cos α − C (t/2a) sin α) = m g (a cos α − (t/2) sin α),
// for t = 0 the thin disc's Ω² = 4 g / (a sin α) (Moffatt 2000): Ω grows as α falls.

#include "scenes/live_scene.h"
#include "scenes/scene_registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace substep {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kG = 10.0;  // the paper's gravity

struct Sample {
    double tilt;        ///< face to table (rad)
    double precession;  ///< |Ω| (rad/s)
};

BodyId coinId(const SceneInstance& scene) {
    for (const auto& [name, id] : scene.namedBodyIds())
        if (name == "coin") return id;
    return {};
}

Vec3 coinAxis(const Body& coin) { return coin.userOrientation() * Vec3::UnitY(); }

Sample measure(const Body& coin) {
    const Vec3 e = coinAxis(coin);
    const double tilt = std::acos(std::min(1.0, std::abs(e.y())));
    // The azimuth of e about the vertical turns at (e_h × ė_h)·ŷ / |e_h|², ė = ω × e.
    const Vec3 edot = coin.omega.cross(e);
    const double horizontal2 = e.x() * e.x() + e.z() * e.z();
    const double rate = horizontal2 > 1e-12 ? (e.z() * edot.x() - e.x() * edot.z()) / horizontal2 : 0.0;
    return {tilt, std::abs(rate)};
}

/// Ω of steady rolling (file comment), for the coin's radius and thickness.
double steadyPrecession(double a, double t, double alpha) {
    const double s = std::sin(alpha), c = std::cos(alpha);
    const double perMassA = (3.0 * a * a + t * t) / 12.0;
    const double perMassC = 0.5 * a * a;
    return std::sqrt(kG * (a * c - 0.5 * t * s) / (s * (perMassA * c - perMassC * (t / (2.0 * a)) * s)));
}

class CoinScene : public testing::Test {
  protected:
    void SetUp() override {
        entry_ = findBuiltinScene("coin");
        ASSERT_NE(entry_, nullptr);
    }
    const SceneEntry* entry_ = nullptr;
};

TEST_F(CoinScene, TheThrowFollowsTheKnobs) {
    LiveScene scene(entry_->build(), entry_);
    ASSERT_NE(scene.script(), nullptr);
    ASSERT_TRUE(scene.script()->setKnob(scene.instance(), "spin", 45.0));
    ASSERT_TRUE(scene.script()->setKnob(scene.instance(), "tilt", 20.0));
    ASSERT_TRUE(scene.script()->setKnob(scene.instance(), "friction", 0.7));
    scene.restart();
    const Body& coin = scene.world().body(coinId(scene.instance()));
    EXPECT_NEAR(coin.omega.y(), 45.0, 1e-12);
    EXPECT_NEAR(measure(coin).tilt, 70.0 * kDegree, 1e-9);
    EXPECT_DOUBLE_EQ(coin.staticFriction, 0.7);
    // Standing on its lowest rim corner, touching the table top (y = 0).
    const double a = coin.shape.radius, t = coin.shape.length;
    EXPECT_NEAR(coin.userPosition().y(), a * std::sin(70.0 * kDegree) + 0.5 * t * std::cos(70.0 * kDegree), 1e-12);
    EXPECT_EQ(scene.description().substeps, 20);  // Table 1
    EXPECT_EQ(scene.description().iterations, 1);
}

TEST_F(CoinScene, WobblesFasterAsItTiltsDownAsSteadyRollingPredictsThenRestsFlat) {
    LiveScene scene(entry_->build(), entry_);
    const BodyId id = coinId(scene.instance());
    ASSERT_TRUE(scene.world().isValid(id));
    const double a = scene.world().body(id).shape.radius;
    const double t = scene.world().body(id).shape.length;

    std::vector<Sample> rolling;  // frames with the face between 3° and 40° off the table
    const int frames = static_cast<int>(std::lround(5.0 / scene.description().dt));
    for (int frame = 0; frame < frames; ++frame) {
        scene.step();
        ASSERT_TRUE(scene.world().isFinite());
        const Sample s = measure(scene.world().body(id));
        if (s.tilt > 3.0 * kDegree && s.tilt < 40.0 * kDegree) rolling.push_back(s);
    }
    ASSERT_GE(rolling.size(), 20u) << "the coin should roll on its rim for a while";

    // Every rolling frame within 15 % of the steady rate at its tilt, and their median within 5 %.
    std::vector<double> ratios;
    for (const Sample& s : rolling) {
        const double ratio = s.precession / steadyPrecession(a, t, s.tilt);
        EXPECT_NEAR(ratio, 1.0, 0.15) << "tilt " << s.tilt / kDegree << " deg";
        ratios.push_back(ratio);
    }
    std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
    EXPECT_NEAR(ratios[ratios.size() / 2], 1.0, 0.05);

    // The wobble speeds up as the tilt falls: mean Ω over tilt bands, steepest band last.
    const double bands[] = {40.0, 20.0, 10.0, 5.0, 3.0};
    double previous = 0.0;
    for (int b = 0; b + 1 < 5; ++b) {
        double sum = 0.0;
        int count = 0;
        for (const Sample& s : rolling)
            if (s.tilt < bands[b] * kDegree && s.tilt >= bands[b + 1] * kDegree) sum += s.precession, ++count;
        ASSERT_GT(count, 0) << "no frame between " << bands[b + 1] << " and " << bands[b] << " deg";
        const double mean = sum / count;
        EXPECT_GT(mean, 1.15 * previous) << "band " << bands[b + 1] << "-" << bands[b] << " deg";
        previous = mean;
    }
    // From about 76 rad/s at 40° to over 190 rad/s below 5°, as Ω ∝ 1/√sin α says.
    EXPECT_GT(previous, 190.0);

    // At rest, flat on the table: the face level, the centre half a thickness above the top.
    const Body& coin = scene.world().body(id);
    EXPECT_LT(measure(coin).tilt, 0.1 * kDegree);
    EXPECT_NEAR(coin.userPosition().y(), 0.5 * t, 2e-5);
    EXPECT_LT(coin.v.norm(), 1e-4);
    EXPECT_LT(coin.omega.norm(), 1e-2);
    EXPECT_LT(std::hypot(coin.userPosition().x(), coin.userPosition().z()), 0.1);
}

}  // namespace
}  // namespace substep
