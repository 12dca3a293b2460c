#include "capture/json_input.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

namespace substep::capture {

namespace {

std::string joinPath(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string typeName(const nlohmann::ordered_json& value) {
    if (value.is_number()) return "a number";
    if (value.is_string()) return "a string";
    if (value.is_boolean()) return "a boolean";
    if (value.is_array()) return "an array";
    if (value.is_object()) return "an object";
    return "null";
}

/// Tracks the JSON path while nlohmann parses, so duplicate keys and syntax errors name where.
class PathTracker {
  public:
    explicit PathTracker(const std::string& file) : file_(file) {}

    bool onEvent(nlohmann::ordered_json::parse_event_t event,
                 const nlohmann::ordered_json& parsed) {
        using Event = nlohmann::ordered_json::parse_event_t;
        switch (event) {
            case Event::object_start:
            case Event::array_start: {
                const std::string path = childPath();
                frames_.push_back({.object = event == Event::object_start, .path = path});
                break;
            }
            case Event::object_end:
            case Event::array_end:
                frames_.pop_back();
                break;
            case Event::key: {
                Frame& frame = frames_.back();
                frame.key = parsed.get<std::string>();
                if (!frame.keys.insert(frame.key).second) {
                    throw InputError(file_, joinPath(frame.path, frame.key),
                                     "duplicate key (it is already given earlier in this object)");
                }
                break;
            }
            case Event::value:
                childPath();
                break;
        }
        return true;
    }

    /// The path of the value being read now.
    std::string currentPath() const {
        if (frames_.empty()) return "";
        const Frame& frame = frames_.back();
        if (frame.object) return frame.key.empty() ? frame.path : joinPath(frame.path, frame.key);
        return frame.path + "[" + std::to_string(frame.index < 0 ? 0 : frame.index) + "]";
    }

  private:
    struct Frame {
        bool object = false;
        std::string path;
        std::string key;
        long long index = -1;
        std::set<std::string> keys;
    };

    /// The path of a value that starts now; in an array it is the next element.
    std::string childPath() {
        if (frames_.empty()) return "";
        Frame& frame = frames_.back();
        if (frame.object) return joinPath(frame.path, frame.key);
        ++frame.index;
        return frame.path + "[" + std::to_string(frame.index) + "]";
    }

    const std::string& file_;
    std::vector<Frame> frames_;
};

std::string lineAndColumn(std::string_view text, std::size_t byte) {
    byte = std::min(byte, text.size());
    std::size_t line = 1;
    std::size_t lineStart = 0;
    for (std::size_t i = 0; i < byte; ++i) {
        if (text[i] == '\n') {
            ++line;
            lineStart = i + 1;
        }
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(byte - lineStart + 1);
}

}  // namespace

InputError::InputError(const std::string& file, const std::string& path, const std::string& problem)
    : std::runtime_error(file + ": " + (path.empty() ? "" : path + ": ") + problem) {}

std::string readTextFile(const std::string& file) {
    std::error_code error;
    if (std::filesystem::is_directory(file, error))
        throw InputError(file, "", "is a folder, not a file");
    std::ifstream stream(file, std::ios::binary);
    if (!stream) throw InputError(file, "", "cannot be read");
    std::ostringstream text;
    text << stream.rdbuf();
    if (stream.bad()) throw InputError(file, "", "cannot be read");
    return text.str();
}

nlohmann::ordered_json parseJson(std::string_view text, const std::string& file) {
    PathTracker tracker(file);
    try {
        return nlohmann::ordered_json::parse(
            text.begin(), text.end(),
            [&](int, nlohmann::ordered_json::parse_event_t event, nlohmann::ordered_json& parsed) {
                return tracker.onEvent(event, parsed);
            });
    } catch (const nlohmann::ordered_json::parse_error& error) {
        // Keep nlohmann's description without its "[json.exception...] " prefix and location.
        std::string detail = error.what();
        if (const auto dash = detail.find(": "); dash != std::string::npos)
            detail = detail.substr(dash + 2);
        if (detail.size() > 160) detail = detail.substr(0, 157) + "...";
        const std::string where = lineAndColumn(text, error.byte > 0 ? error.byte - 1 : 0);
        const std::string path = tracker.currentPath();
        if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) {
            throw InputError(file, "", "is empty (or truncated): no JSON in it");
        }
        throw InputError(file, path, "not valid JSON at " + where + ": " + detail);
    } catch (const nlohmann::ordered_json::exception& error) {
        // 406: a number too large for a double (1e999); the tracker is at its key or element.
        std::string detail = error.what();
        if (const auto bracket = detail.find("] "); bracket != std::string::npos)
            detail = detail.substr(bracket + 2);
        throw InputError(file, tracker.currentPath(),
                         (error.id == 406 ? "number out of range: " : "not valid JSON: ") + detail);
    }
}

void JsonAt::fail(const std::string& problem) const {
    throw InputError(file_, path_.empty() ? "top level" : path_, problem);
}

void JsonAt::requireObject(std::initializer_list<std::string_view> allowed) const {
    if (!value_.is_object()) fail("expected an object, got " + typeName(value_));
    for (const auto& [key, member] : value_.items()) {
        bool known = false;
        for (const std::string_view name : allowed)
            known = known || name == key;
        if (!known) {
            std::string list;
            for (const std::string_view name : allowed)
                list += (list.empty() ? "" : ", ") + std::string(name);
            throw InputError(file_, joinPath(path_, key),
                             "unknown key (expected one of: " + list + ")");
        }
    }
}

void JsonAt::requireArray(long long size) const {
    if (!value_.is_array()) fail("expected an array, got " + typeName(value_));
    if (size >= 0 && static_cast<long long>(value_.size()) != size) {
        fail("expected " + std::to_string(size) + " elements, got " +
             std::to_string(value_.size()));
    }
}

bool JsonAt::has(std::string_view key) const {
    return value_.is_object() && value_.contains(key);
}

JsonAt JsonAt::member(std::string_view key) const {
    if (!value_.is_object()) fail("expected an object, got " + typeName(value_));
    const auto found = value_.find(key);
    if (found == value_.end()) fail("missing key " + jsonQuoted(key));
    return JsonAt(*found, joinPath(path_, key), file_);
}

JsonAt JsonAt::element(std::size_t index) const {
    return JsonAt(value_.at(index), path_ + "[" + std::to_string(index) + "]", file_);
}

double JsonAt::number(double lowest, double highest) const {
    if (!value_.is_number()) fail("expected a number, got " + typeName(value_));
    const double value = value_.get<double>();
    if (!std::isfinite(value) || value < lowest || value > highest) {
        std::ostringstream message;
        message << "must be between " << lowest << " and " << highest << ", got " << value_.dump();
        fail(message.str());
    }
    return value;
}

long long JsonAt::integer(long long lowest, long long highest) const {
    if (!value_.is_number_integer())
        fail("expected a whole number, got " +
             (value_.is_number() ? value_.dump() : typeName(value_)));
    const bool negative = value_.is_number_unsigned() ? false : value_.get<long long>() < 0;
    const bool tooLarge =
        value_.is_number_unsigned() &&
        value_.get<unsigned long long>() > static_cast<unsigned long long>(highest);
    const long long value = tooLarge ? highest : value_.get<long long>();
    if (tooLarge || value < lowest || value > highest || (negative && lowest >= 0)) {
        fail("must be a whole number from " + std::to_string(lowest) + " to " +
             std::to_string(highest) + ", got " + value_.dump());
    }
    return value;
}

std::string JsonAt::string() const {
    if (!value_.is_string()) fail("expected a string, got " + typeName(value_));
    return value_.get<std::string>();
}

bool JsonAt::boolean() const {
    if (!value_.is_boolean()) fail("expected true or false, got " + typeName(value_));
    return value_.get<bool>();
}

std::string jsonQuoted(std::string_view name) {
    return nlohmann::json(std::string(name)).dump();
}

}  // namespace substep::capture
