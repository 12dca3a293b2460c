/// Scene files (JSON, version 1) -> SceneDescription, validating everything. The rules and
/// bounds of the format are in docs/SCENE_FORMAT.md. The first problem found throws a SceneError
/// `FILE: JSON.PATH: what is wrong`.
///
/// The loader in layers, one file each:
///   scene_loader.cpp            this file: the file itself, the version and the world settings,
///                               then the section readers in table order
///   scene_loader_json.*         JSON text -> document, with the path of every value; message text
///   scene_loader_validator.*    bounds, typed reads (Validator), checked keys (ObjectReader)
///   scene_loader_sections.h     the table of top-level section readers, where a new key plugs in
///   scene_loader_bodies.cpp     `bodies`, with scene_loader_shapes.* for each body's `shape`
///   scene_loader_joints.cpp     `joints`
///   scene_loader_camera.cpp     `camera`

#include "scene/scene_loader.h"

#include "physics/joint_projection.h"

#include "scene/scene_loader_json.h"
#include "scene/scene_loader_sections.h"
#include "scene/scene_loader_validator.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace substep {

namespace {

std::string composeMessage(const std::string& file, const std::string& path,
                           const std::string& problem) {
    return path.empty() ? file + ": " + problem : file + ": " + path + ": " + problem;
}

}  // namespace

SceneError::SceneError(const std::string& file, const std::string& path, const std::string& problem)
    : std::runtime_error(composeMessage(file, path, problem)),
      file_(file),
      path_(path),
      problem_(problem) {}

namespace scene_loader {
namespace {

constexpr std::uintmax_t kMaxFileBytes = 256u << 20;  // 256 MiB

/// The top level: version, world settings, then each section present, in kSceneSections order.
SceneDescription readScene(const Validator& v, const Json& root) {
    const ObjectReader top(v, {root, ""}, "a JSON object");

    // The version decides how to read everything else, so it is checked first.
    const auto version = top.get("substep_scene");
    if (!version) {
        v.fail("substep_scene", "missing: a scene file starts with \"substep_scene\": 1");
    }
    if (!version->value.is_number() || version->value != 1) {
        v.fail(version->path, version->value.is_number()
                                  ? "unsupported version " + describe(version->value) +
                                        " (this build reads version 1)"
                                  : "must be 1, got " + describe(version->value));
    }
    std::vector<std::string> allowed = {
        "substep_scene", "name", "description", "gravity", "dt", "substeps", "iterations", "sleeping",
        "joint_projection"};
    for (const SceneSection& section : kSceneSections)
        allowed.emplace_back(section.key);
    top.allowOnly(allowed);

    SceneDescription scene;
    // Documented extension: a title and a description, for people reading the file.
    if (auto n = top.get("name")) v.string(*n);
    if (auto d = top.get("description")) v.string(*d);

    if (auto g = top.get("gravity")) scene.gravity = v.vec3(*g, within(kMaxGravity));
    if (auto dt = top.get("dt")) scene.dt = v.number(*dt, {.lo = 0, .hi = 1, .loOpen = true});
    if (auto s = top.get("substeps")) scene.substeps = v.integer(*s, 1, kMaxSubsteps);
    if (auto i = top.get("iterations")) scene.iterations = v.integer(*i, 1, kMaxIterations);
    if (auto s = top.get("sleeping")) scene.sleeping = v.boolean(*s);
    // Extension: where joint corrections take their directions from (WorldSettings).
    if (auto p = top.get("joint_projection")) {
        const std::string name = v.string(*p);
        const std::optional<JointProjection> projection = jointProjectionFromName(name);
        if (!projection) v.fail(p->path, "expected \"paper\" or \"start\", got \"" + name + "\"");
        scene.jointProjection = *projection;
    }

    SceneReading reading{v, scene, {}, {}};
    for (const SceneSection& section : kSceneSections) {
        if (auto node = top.get(section.key)) section.read(*node, reading);
    }
    return scene;
}

}  // namespace
}  // namespace scene_loader

SceneDescription parseSceneText(std::string_view text, const std::string& fileLabel) {
    if (std::all_of(text.begin(), text.end(),
                    [](char c) { return std::isspace(static_cast<unsigned char>(c)); })) {
        throw SceneError(fileLabel, "",
                         "the file is empty (a scene starts with {\"substep_scene\": 1})");
    }
    const scene_loader::Json root = scene_loader::readJsonDocument(text, fileLabel);
    SceneDescription scene = scene_loader::readScene(scene_loader::Validator(fileLabel), root);
    scene.name = std::filesystem::path(fileLabel).stem().string();
    return scene;
}

SceneDescription loadSceneFile(const std::string& path) {
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) {
        throw SceneError(path, "", "cannot read: is a directory, not a scene file");
    }
    const auto size = std::filesystem::file_size(path, error);
    if (!error && size > scene_loader::kMaxFileBytes) {
        throw SceneError(path, "", "cannot read: larger than 256 MiB, too large for a scene file");
    }
    errno = 0;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        const int code = errno;
        throw SceneError(
            path, "",
            std::string("cannot read: ") + (code != 0 ? std::strerror(code) : "failed to open"));
    }
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw SceneError(path, "", "cannot read: I/O error while reading");
    return parseSceneText(text.str(), path);
}

}  // namespace substep
