#include "capture/golden_files.h"

#include "atomic_file.h"
#include "capture/json_input.h"
#include "capture/state_file.h"
#include "render/png_codec.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

namespace substep::capture {

namespace fs = std::filesystem;

namespace {

std::string frameFile(long long frame, const char* extension) {
    char name[48];
    std::snprintf(name, sizeof name, "frame_%05lld.%s", frame, extension);
    return name;
}

/// The file's bytes, or nothing when it does not exist or cannot be read.
std::optional<std::string> readBytes(const std::string& path) {
    std::ifstream stream(path, std::ios::binary);
    if (!stream) return std::nullopt;
    std::ostringstream bytes;
    bytes << stream.rdbuf();
    return bytes.str();
}

std::string updateHint(const std::string& scriptFile) {
    return "run `substep capture " + scriptFile + " --update` to make it";
}

}  // namespace

const char* goldenChangeName(GoldenChange change) {
    switch (change) {
        case GoldenChange::Unchanged:
            return "unchanged";
        case GoldenChange::Added:
            return "added";
        case GoldenChange::Changed:
            return "changed";
    }
    return "";
}

std::string captureFolder(const std::string& goldenFolder, const std::string& capture) {
    return (fs::path(goldenFolder) / capture).string();
}

std::string stateFileName(long long frame) {
    return frameFile(frame, "json");
}

std::string imageFileName(long long frame) {
    return frameFile(frame, "png");
}

void requireGolden(const std::string& path, const std::string& scriptFile) {
    std::error_code error;
    if (!fs::is_regular_file(path, error))
        throw InputError(path, "", "no such golden; " + updateHint(scriptFile));
}

CaptureState readGoldenState(const std::string& path, const std::string& scriptFile) {
    requireGolden(path, scriptFile);
    try {
        return parseStateFile(readTextFile(path), path);
    } catch (const InputError& error) {
        throw std::runtime_error(std::string(error.what()) + " (a damaged golden? " +
                                 updateHint(scriptFile) + " again)");
    }
}

render::Image readGoldenImage(const std::string& path, const std::string& scriptFile) {
    requireGolden(path, scriptFile);
    const std::optional<std::string> bytes = readBytes(path);
    if (!bytes) throw InputError(path, "", "cannot be read");
    try {
        return render::decodePng(*bytes);
    } catch (const std::exception& error) {
        throw InputError(path, "",
                         std::string("cannot be decoded (") + error.what() +
                             "; a damaged golden? " + updateHint(scriptFile) + " again)");
    }
}

std::string readGoldenDigest(const std::string& path, const std::string& scriptFile) {
    requireGolden(path, scriptFile);
    const std::string text = readTextFile(path);
    if (text.rfind("fnv1a64 ", 0) != 0 || text.back() != '\n' ||
        std::count(text.begin(), text.end(), '\n') != 1) {
        throw InputError(path, "",
                         "not a digest line `fnv1a64 HEX frames A-B` (a damaged golden? " +
                             updateHint(scriptFile) + " again)");
    }
    return text;
}

GoldenChange writeGolden(const std::string& path, const std::string& bytes) {
    const std::optional<std::string> existing = readBytes(path);
    if (existing && *existing == bytes) return GoldenChange::Unchanged;
    std::error_code error;
    fs::create_directories(fs::path(path).parent_path(), error);
    AtomicFile file(path);
    file.write(bytes);
    file.commit();
    return existing ? GoldenChange::Changed : GoldenChange::Added;
}

std::vector<std::string> removeStaleGoldens(const std::string& folder,
                                            const std::vector<std::string>& keep) {
    std::vector<std::string> removed;
    std::error_code error;
    if (!fs::is_directory(folder, error)) return removed;
    std::vector<fs::path> candidates;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
        if (!entry.is_regular_file()) continue;
        const std::string name = entry.path().filename().string();
        const bool golden = name == kDigestFileName ||
                            (name.rfind("frame_", 0) == 0 && (entry.path().extension() == ".json" ||
                                                              entry.path().extension() == ".png"));
        if (golden && std::find(keep.begin(), keep.end(), name) == keep.end())
            candidates.push_back(entry.path());
    }
    std::sort(candidates.begin(), candidates.end());
    for (const fs::path& path : candidates) {
        if (fs::remove(path, error)) removed.push_back(path.string());
    }
    return removed;
}

}  // namespace substep::capture
