#include "capture/capture_script.h"

#include "capture/json_input.h"
#include "run_command.h"
#include "scene/scene_loader.h"
#include "scenes/scene_registry.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

namespace substep::capture {

namespace {

constexpr double kMaxTolerance = 1e300;
constexpr double kMaxCoordinate = 1e6;  // as scene files' positions

Tolerance readTolerance(const JsonAt& at) {
    Tolerance tolerance;
    if (at.has("abs")) tolerance.abs = at.member("abs").number(0.0, kMaxTolerance);
    if (at.has("rel")) tolerance.rel = at.member("rel").number(0.0, kMaxTolerance);
    return tolerance;
}

StateCheck readStateCheck(const JsonAt& at) {
    at.requireObject({"abs", "rel", "bodies", "joints"});
    StateCheck check{.tolerance = readTolerance(at)};
    for (const char* group : {"bodies", "joints"}) {
        if (!at.has(group)) continue;
        const JsonAt named = at.member(group);
        if (!named.value().is_object())
            named.fail("expected an object of names, each {\"abs\": A, \"rel\": R}");
        auto& target = std::string_view(group) == "bodies" ? check.bodies : check.joints;
        for (const auto& [name, value] : named.value().items()) {
            const JsonAt one = named.member(name);
            one.requireObject({"abs", "rel"});
            target[name] = readTolerance(one);
        }
    }
    return check;
}

Vec3 readVector(const JsonAt& at) {
    at.requireArray(3);
    return {at.element(0).number(-kMaxCoordinate, kMaxCoordinate),
            at.element(1).number(-kMaxCoordinate, kMaxCoordinate),
            at.element(2).number(-kMaxCoordinate, kMaxCoordinate)};
}

ImageCheck readImageCheck(const JsonAt& at) {
    at.requireObject({"size", "camera", "pixel_tolerance", "max_fraction"});
    ImageCheck check;
    if (at.has("size")) {
        const JsonAt size = at.member("size");
        size.requireArray(2);
        check.width = static_cast<int>(size.element(0).integer(1, kMaxCaptureImageSide));
        check.height = static_cast<int>(size.element(1).integer(1, kMaxCaptureImageSide));
    }
    if (at.has("camera")) {
        const JsonAt camera = at.member("camera");
        camera.requireObject({"position", "target", "fov"});
        SceneCamera sceneCamera;
        sceneCamera.position = readVector(camera.member("position"));
        sceneCamera.target = readVector(camera.member("target"));
        if (camera.has("fov")) sceneCamera.fov = camera.member("fov").number(0.01, 3.0);
        if ((sceneCamera.position - sceneCamera.target).norm() == 0.0) {
            camera.member("target").fail("must differ from the camera's position");
        }
        check.camera = sceneCamera;
    }
    if (at.has("pixel_tolerance"))
        check.pixelTolerance = static_cast<int>(at.member("pixel_tolerance").integer(0, 255));
    if (at.has("max_fraction")) check.maxFraction = at.member("max_fraction").number(0.0, 1.0);
    return check;
}

MetricBounds readMetrics(const JsonAt& at) {
    at.requireObject({"max_joint_error", "energy_drift", "penetration"});
    MetricBounds bounds;
    if (at.has("max_joint_error"))
        bounds.maxJointError = at.member("max_joint_error").number(0.0, kMaxTolerance);
    if (at.has("energy_drift"))
        bounds.energyDrift = at.member("energy_drift").number(0.0, kMaxTolerance);
    if (at.has("penetration"))
        bounds.penetration = at.member("penetration").number(0.0, kMaxTolerance);
    return bounds;
}

/// Names become folder names: letters, digits, `_`, `-`, `.`, not starting with `.`.
void checkName(const JsonAt& at, const std::string& name) {
    if (name.empty() || name.size() > 100) at.fail("must be 1 to 100 characters");
    if (name.front() == '.') at.fail("must not start with '.' (it names a folder)");
    for (const char c : name) {
        const bool allowed = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                             (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
        if (!allowed)
            at.fail("may hold only letters, digits, '_', '-' and '.' (it names a folder), got " +
                    jsonQuoted(name));
    }
}

std::string resolveScenePath(const JsonAt& at, const std::string& scene,
                             const std::string& scriptFile) {
    namespace fs = std::filesystem;
    if (scene.empty()) at.fail("must name a built-in scene or a scene file");
    if (findBuiltinScene(scene) != nullptr) return scene;
    const fs::path path = fs::path(scriptFile).parent_path() / scene;
    std::error_code error;
    if (!fs::is_regular_file(path, error)) {
        at.fail("no built-in scene " + jsonQuoted(scene) + " (see `substep scenes`) and no file " +
                path.string());
    }
    return path.string();
}

CaptureSpec readCapture(const JsonAt& at, const std::string& scriptFile) {
    at.requireObject({"name", "scene", "set", "substeps", "iterations", "dt", "frames", "state",
                      "image", "metrics"});
    CaptureSpec spec;
    spec.path = at.path();
    spec.name = at.member("name").string();
    checkName(at.member("name"), spec.name);
    spec.scene = at.member("scene").string();
    spec.scenePath = resolveScenePath(at.member("scene"), spec.scene, scriptFile);
    if (at.has("set")) {
        const JsonAt knobs = at.member("set");
        if (!knobs.value().is_object())
            knobs.fail("expected an object of knob values, e.g. {\"velocity_pass\": 0}");
        for (const auto& [name, value] : knobs.value().items()) {
            const JsonAt knob = knobs.member(name);
            const double number = knob.value().is_boolean() ? (knob.boolean() ? 1.0 : 0.0)
                                                            : knob.number(-1e300, 1e300);
            spec.knobs.emplace_back(name, number);
        }
    }
    if (at.has("substeps"))
        spec.substeps = static_cast<int>(at.member("substeps").integer(1, kMaxSubsteps));
    if (at.has("iterations"))
        spec.iterations = static_cast<int>(at.member("iterations").integer(1, kMaxIterations));
    if (at.has("dt")) {
        const JsonAt dt = at.member("dt");
        spec.dt = dt.number(0.0, kMaxTimeStep);
        if (*spec.dt <= 0.0) dt.fail("must be > 0 s");
        // A scene file's lower bound (scene_loader.h): below it the substep loses precision.
        if (*spec.dt < kMinTimeStep) {
            char got[32];
            std::snprintf(got, sizeof got, "%g", *spec.dt);
            dt.fail(std::string("must be at least 1e-06 s, got ") + got);
        }
    }
    const JsonAt frames = at.member("frames");
    frames.requireArray();
    if (frames.size() == 0 || frames.size() > kMaxCaptureFrames) {
        frames.fail("must list 1 to " + std::to_string(kMaxCaptureFrames) + " frame numbers");
    }
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const JsonAt frame = frames.element(i);
        const long long number = frame.integer(0, kMaxCaptureFrame);
        if (!spec.frames.empty() && number <= spec.frames.back()) {
            frame.fail("frames must increase, got " + std::to_string(number) + " after " +
                       std::to_string(spec.frames.back()));
        }
        spec.frames.push_back(number);
    }
    if (at.has("state")) spec.state = readStateCheck(at.member("state"));
    if (at.has("image")) spec.image = readImageCheck(at.member("image"));
    if (at.has("metrics")) spec.metrics = readMetrics(at.member("metrics"));
    if (!spec.state && !spec.image)
        at.fail("needs \"state\", \"image\" or both: there is nothing to compare");
    return spec;
}

std::string goldenFolderOf(const std::string& file) {
    std::filesystem::path path(file);
    if (path.extension() == ".json") path.replace_extension();
    return path.string() + ".golden";
}

}  // namespace

bool StateCheck::exact() const {
    if (!tolerance.exact()) return false;
    for (const auto& [name, one] : bodies)
        if (!one.exact()) return false;
    for (const auto& [name, one] : joints)
        if (!one.exact()) return false;
    return true;
}

CaptureScript parseCaptureScript(const std::string& file) {
    return parseCaptureScriptText(readTextFile(file), file);
}

CaptureScript parseCaptureScriptText(std::string_view text, const std::string& file) {
    const nlohmann::ordered_json document = parseJson(text, file);
    const JsonAt root(document, "", file);
    root.requireObject({"substep_capture", "description", "captures"});
    if (!root.has("substep_capture"))
        root.fail("missing \"substep_capture\": 1 (is this a capture script?)");
    root.member("substep_capture").integer(1, 1);
    if (root.has("description")) root.member("description").string();
    const JsonAt captures = root.member("captures");
    captures.requireArray();
    if (captures.size() == 0) captures.fail("must list at least one capture");

    CaptureScript script{.file = file, .goldenFolder = goldenFolderOf(file), .captures = {}};
    std::set<std::string> names;
    for (std::size_t i = 0; i < captures.size(); ++i) {
        CaptureSpec spec = readCapture(captures.element(i), file);
        if (!names.insert(spec.name).second) {
            captures.element(i).member("name").fail("duplicate capture name " +
                                                    jsonQuoted(spec.name));
        }
        script.captures.push_back(std::move(spec));
    }
    return script;
}

}  // namespace substep::capture
