#pragma once
// Shared by the stability suite (docs/STABILITY.md): runs a case while watching it for
// non-finite state, energy gained and joint error, and sweeps the substep count to find where
// the case breaks (the smallest count from which on it holds).

#include "physics/world.h"

#include "physics_test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace substep::stability {

using test::kDt;
using test::kPi;
using test::report;

inline constexpr double kG = 9.81;
inline constexpr double kUnbounded = HUGE_VAL;

/// What a case must keep to hold. Unbounded where the measure does not apply (energy where
/// something drives the system).
struct Bounds {
    double energyGain = kUnbounded;  ///< J above the energy at the start
    double jointError = kUnbounded;  ///< m, largest positional joint error
    double measure = kUnbounded;     ///< the case's own measure (an angle, a rate error, ...)
};

/// What one run of a case showed, each the largest over the run's frame ends.
struct Outcome {
    bool finite = true;
    double energyGain = 0.0;  ///< E(t) − E(0), E = kinetic + potential + elastic (J)
    double jointError = 0.0;  ///< World::maxJointError (m)
    double measure = 0.0;     ///< the case's own measure

    bool holds(const Bounds& b) const {
        return finite && energyGain <= b.energyGain && jointError <= b.jointError &&
               measure <= b.measure;
    }
};

/// Steps `world` for `seconds` in frames of `dt` and keeps the largest energy gain, joint error
/// and `measure(t)` over the frame ends; stops at the first non-finite state.
template <class Measure>
Outcome watch(World& world, double seconds, double dt, Measure&& measure) {
    Outcome out;
    const double e0 = world.energies().total();
    const int frames = std::max(1, static_cast<int>(std::lround(seconds / dt)));
    for (int f = 1; f <= frames; ++f) {
        world.step(dt);
        if (!world.isFinite()) {
            out.finite = false;
            return out;
        }
        const double t = f * dt;
        out.energyGain = std::max(out.energyGain, world.energies().total() - e0);
        out.jointError = std::max(out.jointError, world.maxJointError());
        const double m = measure(t);
        out.measure = std::max(out.measure, std::isnan(m) ? kUnbounded : m);
    }
    return out;
}

inline Outcome watch(World& world, double seconds, double dt = kDt) {
    return watch(world, seconds, dt, [](double) { return 0.0; });
}

/// A whole case: builds its world at the given substep count and runs it.
using Case = std::function<Outcome(int substeps)>;

/// The outcomes of one case over a list of substep counts.
struct Sweep {
    std::vector<int> substeps;
    std::vector<Outcome> outcomes;
    /// Smallest count from which every larger count of the list holds; 0 when the largest fails.
    int holdsFrom = 0;

    const Outcome& at(int count) const {
        const auto it = std::find(substeps.begin(), substeps.end(), count);
        return outcomes[static_cast<size_t>(it - substeps.begin())];
    }
};

/// Prints one outcome as a "[ measured ]" line.
inline void print(const std::string& name, int substeps, const Outcome& o, const Bounds& b) {
    std::printf(
        "[ measured ] %s @ %d substeps: finite %s, energy gain %.3g J, joint error %.3g m, "
        "measure %.3g -> %s\n",
        name.c_str(), substeps, o.finite ? "yes" : "NO", o.energyGain, o.jointError, o.measure,
        o.holds(b) ? "holds" : "breaks");
}

/// Runs `run` at every count of `counts` (ascending), prints each outcome and records where
/// the case breaks as the property `<name>_holds_from_substeps`.
inline Sweep sweepSubsteps(const std::string& name, const std::vector<int>& counts,
                           const Bounds& bounds, const Case& run) {
    Sweep sweep;
    sweep.substeps = counts;
    for (const int n : counts) {
        sweep.outcomes.push_back(run(n));
        print(name, n, sweep.outcomes.back(), bounds);
    }
    for (size_t i = counts.size(); i-- > 0;) {
        if (!sweep.outcomes[i].holds(bounds)) break;
        sweep.holdsFrom = counts[i];
    }
    report(name + "_holds_from_substeps", sweep.holdsFrom);
    return sweep;
}

/// Substep length of the engine's default (20 substeps of a 1/60 s frame): the blow-up check
/// applies at it and below.
inline constexpr double kDefaultSubstep = kDt / 20;

/// The checks every case makes on its sweep, whatever its bounds:
/// - finite at every count;
/// - no blow-up at the default substep length or finer: energy gained at most 10 times the
///   case's energy `scale` (skipped when `scale` is 0, where something drives the system); where
///   a case is a documented weak spot, only from `blowUpFrom` substeps on (its present limit,
///   docs/STABILITY.md), coarser counts being measured and documented, not judged;
/// - where it breaks no later than `documented` (the value docs/STABILITY.md gives; 0 when the
///   case does not hold at any count of the list, which is then not checked).
inline void expectStable(const std::string& name, const Sweep& sweep, double scale, int documented,
                         double dt = kDt, int blowUpFrom = 0) {
    for (size_t i = 0; i < sweep.substeps.size(); ++i) {
        const int n = sweep.substeps[i];
        const Outcome& o = sweep.outcomes[i];
        EXPECT_TRUE(o.finite) << name << " @ " << n << " substeps: non-finite state";
        if (scale > 0.0 && dt / n <= kDefaultSubstep * (1.0 + 1e-9) && n >= blowUpFrom) {
            EXPECT_LE(o.energyGain, 10.0 * scale)
                << name << " @ " << n << " substeps blows up: energy gained " << o.energyGain
                << " J against " << scale << " J (docs/STABILITY.md)";
        }
    }
    if (documented > 0) {
        EXPECT_GT(sweep.holdsFrom, 0) << name << ": no longer holds at any count";
        EXPECT_LE(sweep.holdsFrom, documented) << name << ": holds only from " << sweep.holdsFrom
                                               << " substeps, documented " << documented;
    }
}

/// Angle (rad) of the user x axis of `body` about world y, from world x (right-hand rule).
inline double yawAngle(const Body& body) {
    const Vec3 x = test::userAxis(body, Vec3::UnitX());
    return std::atan2(-x.z(), x.x());
}

}  // namespace substep::stability
