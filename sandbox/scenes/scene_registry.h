#pragma once
/// The gallery of built-in scenes: one table, one builder per file in this folder.

#include "scenes/scene_script.h"

#include "scene/scene.h"

#include <span>
#include <string_view>

namespace substep {

/// A chain whose relative elongation measures a scene's error (paper Fig. 11, PEERS chain100):
/// the distance from a fixed anchor to a point on the chain's last body, against its rest value.
struct ChainMeasure {
    std::string_view endBody;          ///< named body at the free end; empty: no chain
    double anchor[3] = {0, 0, 0};      ///< world point the chain hangs from
    double endPoint[3] = {0, 0, 0};    ///< point on the end body, in its own frame
    double restLength = 0.0;           ///< anchor to end point at rest (m)
};

struct SceneEntry {
    std::string_view name;
    std::string_view description;
    SceneDescription (*build)();
    double paperMsPerFrame = 0.0;  ///< the paper's Table 1 figure (ms/frame); 0 where none
    /// Energy drift is reported relative to this (J); 0 means the scene's weight times 1 m.
    double energyScale = 0.0;
    ChainMeasure chain;
    /// Makes the scene's script (its per-frame hook, knobs and readouts); nullptr: none.
    SceneScriptFactory makeScript = nullptr;
};

/// Every built-in scene, in the order `substep scenes` lists them.
std::span<const SceneEntry> builtinScenes();

/// The entry named `name`, or nullptr.
const SceneEntry* findBuiltinScene(std::string_view name);

}  // namespace substep
