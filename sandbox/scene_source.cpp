#include "scene_source.h"

#include "scene/scene_loader.h"
#include "scenes/scene_registry.h"

#include <filesystem>
#include <system_error>

namespace substep {

SceneSource resolveScene(const std::string& argument) {
    if (const SceneEntry* entry = findBuiltinScene(argument)) {
        return {.description = entry->build(), .label = argument, .builtin = true, .entry = entry};
    }

    namespace fs = std::filesystem;
    std::error_code error;
    const fs::file_status status = fs::status(argument, error);
    if (!fs::exists(status)) {
        // Something that looks like a path was meant as a file; anything else as a name.
        const bool looksLikePath =
            argument.find('/') != std::string::npos || fs::path(argument).extension() == ".json";
        if (looksLikePath) {
            throw UnknownSceneError(argument +
                                    ": no such scene file (`substep scenes` lists the built-in "
                                    "scenes)");
        }
        throw UnknownSceneError("unknown scene '" + argument +
                                "': not a built-in scene (see `substep scenes`) and no such file");
    }
    if (fs::is_directory(status)) {
        throw UnknownSceneError(argument + ": is a directory, not a scene file");
    }
    return {.description = loadSceneFile(argument), .label = argument, .builtin = false};
}

SceneInstance buildLabelledScene(const SceneDescription& description, const std::string& label) {
    try {
        return buildScene(description);
    } catch (const std::exception& error) {
        throw std::runtime_error(label + ": " + error.what());
    }
}

LiveScene startLabelledScene(const SceneSource& source, SceneDescription description) {
    try {
        return LiveScene(std::move(description), source.entry);
    } catch (const std::exception& error) {
        throw std::runtime_error(source.label + ": " + error.what());
    }
}

}  // namespace substep
