#pragma once
/// Scene files, the section readers of the loader: one function per top-level key that holds
/// scene content (`bodies`, `joints`, `soft_bodies`, `camera`), each reading that key's value into the
/// SceneDescription being built. parseSceneText (scene_loader.cpp) checks the version and the
/// world settings, then calls the readers of kSceneSections in table order for the keys present.
///
/// Where a new top-level key plugs in (as `soft_bodies` did):
///  1. write scene_loader_soft_bodies.cpp defining
///     `void readSoftBodies(const Node& node, SceneReading& reading)`: it reads values through
///     the Validator and ObjectReader (scene_loader_validator.h), appends to `reading.scene`, and
///     may look up `reading.bodyNames` (readers listed after `bodies` see every body);
///  2. declare it below, add `{"soft_bodies", readSoftBodies}` to kSceneSections (which also
///     makes the key allowed at the top level), and list the .cpp in CMakeLists.txt;
///  3. document the key in docs/SCENE_FORMAT.md.
/// Internal to the scene library; the public entry points are in scene_loader.h.

#include "scene/scene.h"
#include "scene/scene_loader_validator.h"

#include <string>
#include <vector>

namespace substep::scene_loader {

/// A name given in the file and the JSON path where it was given (for "already used at ...").
struct NameAt {
    std::string name;
    std::string path;
};

/// What the section readers share while one file is read.
struct SceneReading {
    const Validator& validator;
    SceneDescription& scene;
    std::vector<NameAt> bodyNames;   ///< named bodies read so far, in file order
    std::vector<NameAt> jointNames;  ///< named joints read so far, in file order
};

/// Reads the value of one top-level key (`node`, at path `key`) into `reading`.
using SectionReader = void (*)(const Node& node, SceneReading& reading);

struct SceneSection {
    const char* key;
    SectionReader read;
};

/// `bodies`: an array of bodies (scene_loader_bodies.cpp).
void readBodies(const Node& node, SceneReading& reading);
/// `joints`: an array of joints between named bodies (scene_loader_joints.cpp).
void readJoints(const Node& node, SceneReading& reading);
/// `soft_bodies`: hexahedral soft bodies, attached to named bodies (scene_loader_soft_bodies.cpp).
void readSoftBodies(const Node& node, SceneReading& reading);
/// `camera`: the initial view (scene_loader_camera.cpp).
void readCamera(const Node& node, SceneReading& reading);

/// The section keys in reading order (a reader sees what earlier ones read: joints name bodies)
/// and in the order the "unknown key" message lists them after the world settings.
inline constexpr SceneSection kSceneSections[] = {
    {"bodies", readBodies},
    {"joints", readJoints},
    {"soft_bodies", readSoftBodies},
    {"camera", readCamera},
};

}  // namespace substep::scene_loader
