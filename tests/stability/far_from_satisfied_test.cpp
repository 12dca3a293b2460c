// The known weak spot of the method (docs/STABILITY.md): hard joints that start far from
// satisfied resolve in one substep and may inject energy. Measures the energy after the first
// frame against before for the hinge, fixed, prismatic and spherical (with a swing limit) joints
// whose axes start 90°, 135° and 180° apart or whose anchors start 1 m apart, at 20 substeps.
// FIXED weak spot for all but one case: with exact rotations and a repair that sweeps until
// converged, the repair keeps the energy (asserted tightly, below).

#include "stability_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

namespace substep {

// GoogleTest prints the parameter in the test's name (found by argument-dependent lookup).
void PrintTo(JointType type, std::ostream* os);

namespace stability {
namespace {

const Vec3 kAnchor(0.0, 2.0, 0.0);
constexpr double kLength = 0.5;
constexpr double kMass = 2.0;
const Vec3 kSize(kLength, 0.1, 0.1);

enum class Start { Turned90, Turned135, Turned180, Apart1m };

const char* startName(Start s) {
    switch (s) {
        case Start::Turned90:
            return "turned_90";
        case Start::Turned135:
            return "turned_135";
        case Start::Turned180:
            return "turned_180";
        case Start::Apart1m:
            return "apart_1m";
    }
    return "";
}

const char* typeName(JointType t) {
    switch (t) {
        case JointType::Hinge:
            return "hinge";
        case JointType::Fixed:
            return "fixed";
        case JointType::Prismatic:
            return "prismatic";
        case JointType::Spherical:
            return "spherical_swing_limit";
        case JointType::Distance:
            return "distance";
    }
    return "";
}

/// A chain of `links` bars (0.5 m, 2 kg) hung from the world at kAnchor by the left end of the
/// first, each joined to the next end to end; satisfied, the chain lies straight along +x, level.
/// Hinge axes z, prismatic and spherical axes x (the spherical joints with a 0.5 rad swing cone),
/// fixed frames the identity. Started far from satisfied, every joint at once: each link turned
/// relative to the one before by 90°, 135° or 180° about an axis normal to the joint axis (so
/// the joint axes are that far apart), or every pair of anchors 1 m apart (along z).
struct FarRig {
    World world;

    FarRig(JointType type, Start start, int links, int substeps, bool repair)
        : world([&] {
              WorldSettings settings{.gravity = Vec3(0, -kG, 0), .substeps = substeps};
              if (!repair) settings.repairDistance = settings.repairAngle = 0.0;
              return settings;
          }()) {
        const double angle = start == Start::Turned90    ? kPi / 2
                             : start == Start::Turned135 ? 3 * kPi / 4
                             : start == Start::Turned180 ? kPi
                                                         : 0.0;
        const Vec3 axis = type == JointType::Hinge ? Vec3::UnitZ() : Vec3::UnitX();
        const Vec3 normal =
            type == JointType::Hinge ? Vec3(1, 2, 0).normalized() : Vec3(0, 2, 3).normalized();
        const Quat turn(Eigen::AngleAxisd(angle, normal));
        const Vec3 shift = start == Start::Apart1m ? Vec3(0, 0, 1) : Vec3::Zero();
        const Vec3 half(kLength / 2, 0, 0);
        BodyId previous;
        Vec3 end = kAnchor;  // the previous link's right end (or the world anchor)
        Quat orientation = Quat::Identity();
        for (int i = 0; i < links; ++i) {
            orientation = turn * orientation;
            const Vec3 left = end + shift;
            const BodyId bar = world.createBody({.shape = boxShape(kSize),
                                                 .mass = kMass,
                                                 .position = left + orientation * half,
                                                 .orientation = orientation,
                                                 .collide = false});  // a joint case: no contacts
            JointDef def{.type = type,
                         .body0 = previous,
                         .body1 = bar,
                         .anchor0 = i == 0 ? kAnchor : half,
                         .anchor1 = -half,
                         .axis0 = axis,
                         .axis1 = axis};
            if (type == JointType::Spherical) def.swingLimit = 0.5;
            world.createJoint(def);
            previous = bar;
            end = left + orientation * (2 * half);
        }
        // The lowest the links can hang: straight down from the anchor.
        for (int i = 0; i < links; ++i)
            floor_ += kMass * kG * (kAnchor.y() - kLength * (i + 0.5));
    }

    /// Kinetic plus potential energy above the lowest configuration (J).
    double energy() const { return world.energies().total() - floor_; }

  private:
    double floor_ = 0.0;
};

struct FirstFrame {
    bool finite = true;
    double before = 0.0;     ///< J above the lowest configuration
    double after = 0.0;      ///< J, after the first frame
    double kinetic = 0.0;    ///< J, kinetic part after the first frame
    double largest = 0.0;    ///< J, the largest over 3 s
    double lastError = 0.0;  ///< m, joint error at 3 s
};

FirstFrame firstFrame(JointType type, Start start, int links, int substeps, bool repair) {
    FarRig rig(type, start, links, substeps, repair);
    FirstFrame r;
    r.before = rig.energy();
    for (int f = 1; f <= 180; ++f) {
        rig.world.step(kDt);
        if (!rig.world.isFinite()) {
            r.finite = false;
            return r;
        }
        if (f == 1) {
            r.after = rig.energy();
            r.kinetic = rig.world.energies().kinetic;
        }
        r.largest = std::max(r.largest, rig.energy());
    }
    r.lastError = rig.world.maxJointError();
    return r;
}

class FarFromSatisfiedTest : public ::testing::TestWithParam<JointType> {};

// One bar on the world and a chain of three, every start, at 20 substeps (the chain also at 5 and
// 80, to show how it scales with h), with the engine's repair pass (World::repairLargeViolations,
// the default) and without it (the paper's method): the energy above the lowest configuration
// before, after the first frame, its kinetic part, the largest over 3 s, and the joint error at
// 3 s. Measured (docs/STABILITY.md): without the repair, up to 6.6e4 fold (documented, not
// judged). With the repair, at 5, 20 and 80 substeps, every case ends the first frame at most
// 1.48 times its energy before (the swing-limited bar turned 180°: the repaired pose sits higher;
// chains at most 1.13) and never exceeds that over 3 s (on the older engine chains reached
// 16-2.3e4 fold). Asserted: after <= 1.6 x before, and the largest over 3 s <= 1.05 x
// max(before, after).
// ENGINE WEAK SPOT, still present: the prismatic chain with anchors 1 m apart gains x1.0 / x1.93
// / x3.3 in the first frame at 5 / 20 / 80 substeps and goes on gaining (largest over 3 s 134 J
// at 20, 1038 J = x23.5 at 80). Its present limit is asserted instead: first frame <= 5 x before,
// largest over 3 s <= 50 x before (without the repair: x1e3-1.7e4 in the first frame).
TEST_P(FarFromSatisfiedTest, EnergyAfterTheFirstFrame) {
    const JointType type = GetParam();
    for (const int links : {1, 3}) {
        for (const Start start :
             {Start::Turned90, Start::Turned135, Start::Turned180, Start::Apart1m}) {
            for (const int substeps : {5, 20, 80}) {
                if (links == 1 && substeps != 20) continue;
                for (const bool repair : {true, false}) {
                    const FirstFrame r = firstFrame(type, start, links, substeps, repair);
                    const std::string name = std::string(typeName(type)) + "_" +
                                             (links == 1 ? "bar_" : "chain3_") + startName(start) +
                                             "_" + std::to_string(substeps) +
                                             (repair ? "" : "_no_repair");
                    std::printf(
                        "[ measured ] far_%s: before %.3g J, after frame 1 %.4g J (x%.3g, kinetic "
                        "%.4g J), largest over 3 s %.4g J, joint error at 3 s %.3g m%s\n",
                        name.c_str(), r.before, r.after, r.after / r.before, r.kinetic, r.largest,
                        r.lastError, r.finite ? "" : ", NON-FINITE");
                    if (substeps == 20) report("far_" + name + "_energy_ratio", r.after / r.before);
                    EXPECT_TRUE(r.finite) << name;
                    // The paper's method (no repair) is documented, not judged.
                    if (!repair) continue;
                    const bool weakSpot = type == JointType::Prismatic && links == 3 &&
                                          start == Start::Apart1m;
                    if (weakSpot) {
                        EXPECT_LE(r.after, 5.0 * r.before) << name << " (present limit x5)";
                        EXPECT_LE(r.largest, 50.0 * r.before) << name << " (present limit x50)";
                    } else {
                        EXPECT_LE(r.after, 1.6 * r.before)
                            << name << " gains energy in the first frame (docs/STABILITY.md)";
                        EXPECT_LE(r.largest, 1.05 * std::max(r.before, r.after))
                            << name << " gains energy after the first frame";
                    }
                }
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Joints, FarFromSatisfiedTest,
                         ::testing::Values(JointType::Hinge, JointType::Fixed, JointType::Prismatic,
                                           JointType::Spherical),
                         [](const ::testing::TestParamInfo<JointType>& param) {
                             return std::string(typeName(param.param));
                         });

}  // namespace
}  // namespace stability

void PrintTo(JointType type, std::ostream* os) {
    *os << stability::typeName(type);
}

}  // namespace substep
