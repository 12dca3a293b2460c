#pragma once
/// The SCENE argument of the `substep` command: a built-in scene name, else a path to a JSON
/// scene file.

#include "scenes/live_scene.h"

#include "scene/scene.h"

#include <stdexcept>
#include <string>

namespace substep {

/// SCENE is neither a built-in name nor an existing file; what() says so and points to
/// `substep scenes`.
class UnknownSceneError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

struct SceneSource {
    SceneDescription description;
    std::string label;  ///< the built-in name, or the file path as given
    bool builtin = false;
    const SceneEntry* entry = nullptr;  ///< the built-in scene's entry (its script); null for files
};

/// Resolves SCENE. Built-in names win, so a file that shares a name is reached as `./NAME`.
/// Throws UnknownSceneError, or SceneError (scene/scene_loader.h) for an unreadable or invalid
/// file.
SceneSource resolveScene(const std::string& argument);

/// buildScene(description), with `label` (a SceneSource's) named in whatever it throws: an
/// unknown body in a built-in scene reads "pendulum3: ...", not a bare message.
SceneInstance buildLabelledScene(const SceneDescription& description, const std::string& label);

/// The source's scene, running with its script: `description` is the source's, maybe with
/// edited solver settings. Errors are labelled as buildLabelledScene labels them.
LiveScene startLabelledScene(const SceneSource& source, SceneDescription description);
/// The same with the source's own description.
inline LiveScene startLabelledScene(const SceneSource& source) {
    return startLabelledScene(source, source.description);
}

}  // namespace substep
