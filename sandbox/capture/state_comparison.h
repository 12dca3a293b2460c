#pragma once
/// Comparing a frame's state with its golden: every value against `|a − b| ≤ abs + rel·|b|`,
/// b the golden's, with the capture's tolerance or the body's or joint's own.

#include "capture/capture_script.h"
#include "capture/capture_state.h"

#include <string>
#include <vector>

namespace substep::capture {

struct StateDifference {
    std::string what;  ///< e.g. `bodies[3] "link2".position[1]`
    double golden = 0.0;
    double fresh = 0.0;
    double allowed = 0.0;  ///< abs + rel·|golden|
};

struct StateComparison {
    /// Non-empty when the two states do not list the same bodies, joints and soft bodies
    /// (counts or names); the values are not compared then.
    std::string structure;
    /// The values out of tolerance, in file order, at most kMaxListedDifferences of them.
    std::vector<StateDifference> differences;
    std::size_t outOfTolerance = 0;  ///< all of them, listed or not
    std::size_t compared = 0;        ///< values compared
    /// The one exceeding its allowance by the most (valid when outOfTolerance > 0).
    StateDifference worst;

    bool matches() const { return structure.empty() && outOfTolerance == 0; }
};

inline constexpr std::size_t kMaxListedDifferences = 500;

/// Compares `fresh` with `golden` under `check`'s tolerances.
StateComparison compareStates(const CaptureState& golden, const CaptureState& fresh,
                              const StateCheck& check);

}  // namespace substep::capture
