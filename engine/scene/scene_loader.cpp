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

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

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

/// Closes a descriptor on every way out of loadSceneFile.
struct FileCloser {
    int descriptor;
    ~FileCloser() { ::close(descriptor); }
};

/// The keys the top level may hold: the world settings, then the sections in table order.
std::vector<std::string> topLevelKeys() {
    std::vector<std::string> allowed = {
        "substep_scene", "name", "description", "gravity", "dt", "substeps", "iterations", "sleeping",
        "joint_projection", "restitution", "soft_friction", "soft_contacts"};
    for (const SceneSection& section : kSceneSections)
        allowed.emplace_back(section.key);
    return allowed;
}

/// `substep_scene` must be 1.
void checkVersion(const Validator& v, const Node& version) {
    if (!version.value.is_number() || version.value != 1) {
        v.fail(version.path, version.value.is_number()
                                 ? "unsupported version " + describe(version.value) +
                                       " (this build reads version 1)"
                                 : "must be 1, got " + describe(version.value));
    }
}

/// The top level's rules checked while the file is parsed, each with the message readScene
/// gives for it: a top level that is not an object, a wrong version, an unknown key (reported
/// once the version has been read and found right, as readScene checks the version first).
/// A large invalid file then fails where the parser meets its first problem.
class TopLevelChecks final : public ReadingChecks {
  public:
    explicit TopLevelChecks(const Validator& v) : v_(v), allowed_(topLevelKeys()) {}

    void documentStart(const Json& container) override {
        const ObjectReader top(v_, {container, ""}, "a JSON object");
    }

    void topLevelKey(const std::string& key) override {
        if (std::find(allowed_.begin(), allowed_.end(), key) != allowed_.end()) return;
        if (versionRight_) failUnknown(key);
        if (!firstUnknown_) firstUnknown_ = key;
    }

    void topLevelValue(const std::string& key, const Json& value) override {
        if (key != "substep_scene") return;
        checkVersion(v_, {value, "substep_scene"});
        versionRight_ = true;
        if (firstUnknown_) failUnknown(*firstUnknown_);
    }

  private:
    [[noreturn]] void failUnknown(const std::string& key) const {
        const Json empty = Json::object();
        ObjectReader(v_, {empty, ""}).failUnknown(key, allowed_);
    }

    const Validator& v_;
    std::vector<std::string> allowed_;
    bool versionRight_ = false;
    std::optional<std::string> firstUnknown_;
};

/// The top level: version, world settings, then each section present, in kSceneSections order.
SceneDescription readScene(const Validator& v, const Json& root) {
    const ObjectReader top(v, {root, ""}, "a JSON object");

    // The version decides how to read everything else, so it is checked first.
    const auto version = top.get("substep_scene");
    if (!version) {
        v.fail("substep_scene", "missing: a scene file starts with \"substep_scene\": 1");
    }
    checkVersion(v, *version);
    top.allowOnly(topLevelKeys());

    SceneDescription scene;
    // Documented extension: a title and a description, for people reading the file.
    if (auto n = top.get("name")) v.string(*n);
    if (auto d = top.get("description")) v.string(*d);

    if (auto g = top.get("gravity")) scene.gravity = v.vec3(*g, within(kMaxGravity));
    if (auto dt = top.get("dt")) {
        scene.dt = v.number(*dt, {.lo = 0, .hi = kMaxTimeStep, .loOpen = true, .least = kMinTimeStep});
    }
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
    // Extension: restitution by sweeps of two-body collisions, or the paper's Eq. 34 alone
    // (WorldSettings::sweptRestitution).
    if (auto r = top.get("restitution")) {
        const std::string name = v.string(*r);
        if (name != "swept" && name != "paper")
            v.fail(r->path, "expected \"swept\" or \"paper\", got \"" + name + "\"");
        scene.sweptRestitution = name == "swept";
    }
    // Extension: soft bodies' static friction judged over each contact patch, or per particle
    // (WorldSettings::softPatchFriction).
    if (auto f = top.get("soft_friction")) {
        const std::string name = v.string(*f);
        if (name != "patch" && name != "particle")
            v.fail(f->path, "expected \"patch\" or \"particle\", got \"" + name + "\"");
        scene.softPatchFriction = name == "patch";
    }
    // Extension: soft particles held by their contacts in the element projection, or free
    // (WorldSettings::softHeldContacts).
    if (auto c = top.get("soft_contacts")) {
        const std::string name = v.string(*c);
        if (name != "held" && name != "free")
            v.fail(c->path, "expected \"held\" or \"free\", got \"" + name + "\"");
        scene.softHeldContacts = name == "held";
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
    const scene_loader::Validator validator(fileLabel);
    scene_loader::TopLevelChecks checks(validator);
    const scene_loader::Json root = scene_loader::readJsonDocument(text, fileLabel, &checks);
    SceneDescription scene = scene_loader::readScene(validator, root);
    scene.name = std::filesystem::path(fileLabel).stem().string();
    return scene;
}

SceneDescription loadSceneFile(const std::string& path) {
    // O_NONBLOCK: opening a FIFO for reading must not wait for a writer; fstat then refuses it.
    // Only regular files are read, and never more than the cap: /dev/zero would read forever.
    const int descriptor = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (descriptor < 0) {
        const int code = errno;
        throw SceneError(path, "", std::string("cannot read: ") + std::strerror(code));
    }
    const scene_loader::FileCloser closer{descriptor};
    struct stat info {};
    if (::fstat(descriptor, &info) != 0) {
        const int code = errno;
        throw SceneError(path, "", std::string("cannot read: ") + std::strerror(code));
    }
    if (S_ISDIR(info.st_mode)) {
        throw SceneError(path, "", "cannot read: is a directory, not a scene file");
    }
    if (!S_ISREG(info.st_mode)) {
        throw SceneError(path, "",
                         "cannot read: not a regular file (a device, FIFO or socket); a scene "
                         "is a .json file");
    }
    if (static_cast<std::uintmax_t>(info.st_size) > scene_loader::kMaxFileBytes) {
        throw SceneError(path, "", "cannot read: larger than 256 MiB, too large for a scene file");
    }
    std::string text;
    // One byte more than fstat said, so that the read meeting the end needs no larger buffer
    // (growing a 250 MB text by doubling briefly held both copies).
    text.resize(static_cast<std::size_t>(info.st_size) + 1);
    std::size_t filled = 0;
    // The file may grow while it is read: the cap holds whatever fstat said.
    while (true) {
        if (filled == text.size()) {
            if (text.size() >= scene_loader::kMaxFileBytes + 1) break;
            text.resize(std::min<std::size_t>(std::max<std::size_t>(2 * text.size(), 4096),
                                              scene_loader::kMaxFileBytes + 1));
        }
        const ssize_t got = ::read(descriptor, text.data() + filled, text.size() - filled);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) {
            const int code = errno;
            throw SceneError(path, "", std::string("cannot read: ") + std::strerror(code));
        }
        if (got == 0) break;
        filled += static_cast<std::size_t>(got);
    }
    if (filled > scene_loader::kMaxFileBytes) {
        throw SceneError(path, "", "cannot read: larger than 256 MiB, too large for a scene file");
    }
    text.resize(filled);
    return parseSceneText(text, path);
}

}  // namespace substep
