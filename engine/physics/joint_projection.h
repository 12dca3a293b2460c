#pragma once
/// JointProjection's names as scene files and the `substep` options spell them ("paper",
/// "start").

#include "physics/correction.h"

#include <optional>
#include <string_view>

namespace substep {

/// "paper" or "start".
inline const char* jointProjectionName(JointProjection projection) {
    return projection == JointProjection::Start ? "start" : "paper";
}

/// The projection a name spells; nothing for any other text.
inline std::optional<JointProjection> jointProjectionFromName(std::string_view name) {
    if (name == "paper") return JointProjection::Paper;
    if (name == "start") return JointProjection::Start;
    return std::nullopt;
}

}  // namespace substep
