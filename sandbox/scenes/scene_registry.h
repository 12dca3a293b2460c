#pragma once
/// The gallery of built-in scenes: one table, one builder per file in this folder.

#include "scene/scene.h"

#include <span>
#include <string_view>

namespace substep {

struct SceneEntry {
    std::string_view name;
    std::string_view description;
    SceneDescription (*build)();
};

/// Every built-in scene, in the order `substep scenes` lists them.
std::span<const SceneEntry> builtinScenes();

/// The entry named `name`, or nullptr.
const SceneEntry* findBuiltinScene(std::string_view name);

}  // namespace substep
