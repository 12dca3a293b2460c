/// Scene files, the JSON layer of the loader (scene_loader_json.h): a SAX handler that builds the
/// document while knowing the JSON path of every value, and the text helpers of every message.

#include "scene/scene_loader_json.h"

#include "scene/scene_loader.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <utility>

namespace substep::scene_loader {

namespace {

constexpr std::size_t kMaxKeys = 1000;       // per JSON object
constexpr std::size_t kMaxElements = 100000;  // per JSON array: the longest the format has
constexpr std::size_t kMaxDepth = 64;         // JSON nesting
// The memory a value takes in the document (nlohmann::ordered_json on 64-bit Linux): its slot,
// the heap block of an array or object, an object member's key beside its value, the text of
// a string too long for the small-string buffer.
constexpr std::size_t kSlotBytes = 16;
constexpr std::size_t kContainerBytes = 48;
constexpr std::size_t kKeyBytes = 32;
constexpr std::size_t kSmallString = 15;

/// `512 MiB`, or bytes below a MiB.
std::string megabytes(std::size_t bytes) {
    return bytes >= (std::size_t{1} << 20) ? std::to_string(bytes >> 20) + " MiB"
                                           : std::to_string(bytes) + " bytes";
}

std::size_t stringHeapBytes(const std::string& text) {
    return text.size() > kSmallString ? text.size() + 1 : 0;
}

bool isIdentifier(std::string_view key) {
    if (key.empty() || std::isdigit(static_cast<unsigned char>(key[0]))) return false;
    return std::all_of(key.begin(), key.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    });
}

std::size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = above;
        }
    }
    return row[b.size()];
}

// Parsing: a SAX handler that builds the document while knowing the JSON path of every value,
// so syntax errors, overflowing numbers and duplicate keys are reported where they occur.

class DocumentBuilder {
  public:
    using number_integer_t = Json::number_integer_t;
    using number_unsigned_t = Json::number_unsigned_t;
    using number_float_t = Json::number_float_t;
    using string_t = Json::string_t;
    using binary_t = Json::binary_t;

    DocumentBuilder(Json& root, std::string_view text, const std::string& file,
                    ReadingChecks* checks, std::size_t maxBytes)
        : root_(root), text_(text), file_(file), checks_(checks), maxBytes_(maxBytes) {}

    bool null() { return add(Json(nullptr)); }
    bool boolean(bool value) { return add(Json(value)); }
    bool number_integer(number_integer_t value) { return add(Json(value)); }
    bool number_unsigned(number_unsigned_t value) { return add(Json(value)); }
    bool number_float(number_float_t value, const string_t& literal) {
        // strtod turns 1e-400 into 0 silently; a value the file did not say is an error.
        if (value == 0.0 && hasNonZeroMantissa(literal)) {
            const std::string number =
                literal.size() > 40 ? literal.substr(0, 37) + "..." : literal;
            fail(valuePath(),
                 "number " + number + " is too small to represent (it underflows to 0)");
        }
        return add(Json(value));
    }
    bool string(string_t& value) {
        account(stringHeapBytes(value));
        return add(Json(std::move(value)));
    }
    bool binary(binary_t&) { return false; }  // JSON text has no binary values

    bool start_object(std::size_t) { return open(Json::object()); }
    bool start_array(std::size_t) { return open(Json::array()); }
    bool end_object() { return close(); }
    bool end_array() { return close(); }

    bool key(string_t& key) {
        Frame& frame = stack_.back();
        // Key lookups in an ordered object are linear; no valid object comes near this many.
        if (frame.container->size() >= kMaxKeys) {
            fail(frame.path, "has more than " + std::to_string(kMaxKeys) + " keys");
        }
        if (frame.container->contains(key)) {
            fail(memberPath(frame.path, key),
                 "duplicate key (it is already given earlier in this object)");
        }
        account(kKeyBytes + stringHeapBytes(key));
        frame.key = key;
        frame.keyPending = true;
        if (checks_ != nullptr && stack_.size() == 1) checks_->topLevelKey(key);
        return true;
    }

    bool parse_error(std::size_t position, const std::string& lastToken,
                     const nlohmann::detail::exception& error) {
        if (error.id == 406) {
            // Number overflow: point at the start of the number.
            const std::size_t start =
                position >= lastToken.size() ? position - lastToken.size() : 0;
            const std::string number =
                lastToken.size() > 40 ? lastToken.substr(0, 37) + "..." : lastToken;
            fail(valuePath(), "number " + number + " overflows a double (" + location(start) + ")");
        }
        // Keep nlohmann's description, drop its prefix and location (ours counts the same way).
        std::string detail = error.what();
        if (const auto dash = detail.find(" - "); dash != std::string::npos) {
            detail = detail.substr(dash + 3);
        } else if (const auto bracket = detail.find("] "); bracket != std::string::npos) {
            detail = detail.substr(bracket + 2);
        }
        fail(valuePath(), "syntax error at " + location(position > 0 ? position - 1 : 0) + ": " +
                              shortenLastRead(detail));
    }

  private:
    struct Frame {
        Json* container;
        std::string path;
        std::string key;          // objects: the last key read
        bool keyPending = false;  // objects: its value has not been read yet
        std::size_t index = 0;    // arrays: the index of the next element
        const char* elements = "elements";  // arrays: what the elements are, for messages
    };

    /// What the elements of an array under `key` are called in "has more than N ..." (the
    /// spline's `points` keep the message their reader gives below the cap).
    static const char* elementsUnder(const std::string& key) {
        if (key == "bodies") return "bodies";
        if (key == "joints") return "joints";
        if (key == "soft_bodies") return "soft bodies";
        if (key == "points") return "points";
        return "elements";
    }

    /// Adds what a value takes in memory, failing once the document passes its bound.
    void account(std::size_t bytes) {
        bytes_ += bytes;
        if (bytes_ > maxBytes_) {
            fail("", "too large: the document would take more than " + megabytes(maxBytes_) +
                         " of memory once read (a 4096 x 4096 heightfield, the largest "
                         "thing a scene holds, takes 256 MiB)");
        }
    }

    [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
        throw SceneError(file_, path.empty() ? "top level" : path, problem);
    }

    /// Path of the value being read next.
    std::string valuePath() const {
        if (stack_.empty()) return "";
        const Frame& frame = stack_.back();
        if (frame.container->is_object()) {
            return frame.keyPending ? memberPath(frame.path, frame.key) : frame.path;
        }
        return elementPath(frame.path, frame.index);
    }

    /// `line L, column C` of a byte offset (columns count bytes, from 1).
    std::string location(std::size_t offset) const {
        offset = std::min(offset, text_.size());
        const std::size_t line = 1 + std::count(text_.begin(), text_.begin() + offset, '\n');
        const std::size_t lineStart = text_.rfind('\n', offset == 0 ? 0 : offset - 1);
        const std::size_t column =
            lineStart == std::string_view::npos || offset == 0 ? offset + 1 : offset - lineStart;
        return "line " + std::to_string(line) + ", column " + std::to_string(column);
    }

    /// nlohmann quotes the text it last read, which can be the rest of the file (an unclosed
    /// string) and can hold invalid UTF-8: keep its last 40 bytes, non-ASCII ones as \xNN.
    static std::string shortenLastRead(const std::string& detail) {
        const std::string marker = "last read: '";
        const std::size_t start = detail.find(marker);
        if (start == std::string::npos) return detail;
        const std::size_t tokenStart = start + marker.size();
        std::size_t tokenEnd = detail.find("'; expected", tokenStart);
        if (tokenEnd == std::string::npos) tokenEnd = detail.rfind('\'');
        if (tokenEnd == std::string::npos || tokenEnd < tokenStart) return detail;
        std::string token = detail.substr(tokenStart, tokenEnd - tokenStart);
        if (token.size() > 40) token = "..." + token.substr(token.size() - 40);
        std::string clean;
        for (const char c : token) {
            const auto byte = static_cast<unsigned char>(c);
            if (byte < 0x80) {
                clean += c;
            } else {
                static const char* hex = "0123456789ABCDEF";
                clean += {'\\', 'x', hex[byte >> 4], hex[byte & 15]};
            }
        }
        return detail.substr(0, tokenStart) + clean + detail.substr(tokenEnd);
    }

    static bool hasNonZeroMantissa(const std::string& literal) {
        for (char c : literal) {
            if (c == 'e' || c == 'E') break;
            if (c >= '1' && c <= '9') return true;
        }
        return false;
    }

    /// Stores a scalar (a complete value) and reports it when it is a top-level member's.
    bool add(Json&& value) {
        Json* slot = store(std::move(value));
        if (stack_.size() == 1) memberDone(*slot);
        return true;
    }

    Json* store(Json&& value) {
        account(kSlotBytes);
        if (stack_.empty()) {
            root_ = std::move(value);
            return &root_;
        }
        Frame& frame = stack_.back();
        if (frame.container->is_object()) {
            Json& slot = (*frame.container)[frame.key];
            slot = std::move(value);
            frame.keyPending = false;
            return &slot;
        }
        if (frame.index >= kMaxElements) {
            fail(frame.path, "has more than " + std::to_string(kMaxElements) + " " +
                                 frame.elements + " (a sanity bound against absurd values)");
        }
        frame.container->push_back(std::move(value));
        ++frame.index;
        return &frame.container->back();
    }

    bool open(Json&& container) {
        if (stack_.size() >= kMaxDepth) {
            fail(valuePath(),
                 "nested too deeply (more than " + std::to_string(kMaxDepth) + " levels)");
        }
        std::string path = valuePath();
        const char* elements = "elements";
        if (!stack_.empty() && stack_.back().container->is_object()) {
            elements = elementsUnder(stack_.back().key);
        }
        account(kContainerBytes);
        Json* slot = store(std::move(container));
        stack_.push_back({slot, std::move(path), {}, false, 0, elements});
        if (checks_ != nullptr && stack_.size() == 1) checks_->documentStart(*slot);
        return true;
    }

    bool close() {
        const Json* done = stack_.back().container;
        stack_.pop_back();
        if (stack_.size() == 1) memberDone(*done);
        return true;
    }

    /// A value directly inside the outermost container is complete.
    void memberDone(const Json& value) {
        const Frame& top = stack_.front();
        if (checks_ != nullptr && top.container->is_object()) checks_->topLevelValue(top.key, value);
    }

    Json& root_;
    std::string_view text_;
    const std::string& file_;
    ReadingChecks* checks_;
    std::size_t maxBytes_;
    std::vector<Frame> stack_;
    std::size_t bytes_ = 0;  // what the document takes so far (estimated)
};

}  // namespace

std::string formatNumber(double value) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

std::string jsonQuoted(std::string_view text) {
    return Json(std::string(text)).dump(-1, ' ', false, Json::error_handler_t::replace);
}

std::string memberPath(const std::string& parent, std::string_view key) {
    if (!isIdentifier(key)) return parent + "[" + jsonQuoted(key) + "]";
    return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

std::string elementPath(const std::string& parent, std::size_t index) {
    return parent + "[" + std::to_string(index) + "]";
}

std::string describe(const Json& value) {
    switch (value.type()) {
        case Json::value_t::null:
            return "null";
        case Json::value_t::boolean:
            return value.get<bool>() ? "true" : "false";
        case Json::value_t::number_integer:
            return std::to_string(value.get<int64_t>());
        case Json::value_t::number_unsigned:
            return std::to_string(value.get<uint64_t>());
        case Json::value_t::number_float:
            return formatNumber(value.get<double>());
        case Json::value_t::string: {
            std::string text = value.get<std::string>();
            if (text.size() > 40) text = text.substr(0, 37) + "...";
            return "the string " + jsonQuoted(text);
        }
        case Json::value_t::array:
            return "an array";
        case Json::value_t::object:
            return "an object";
        default:
            return "an unsupported value";
    }
}

std::string suggestion(std::string_view word, const std::vector<std::string>& candidates) {
    const std::string* best = nullptr;
    std::size_t bestDistance = std::max<std::size_t>(2, word.size() / 3) + 1;
    for (const std::string& candidate : candidates) {
        const std::size_t distance = editDistance(word, candidate);
        if (distance < bestDistance) {
            bestDistance = distance;
            best = &candidate;
        }
    }
    return best ? " (did you mean " + jsonQuoted(*best) + "?)" : "";
}

std::string joinList(const std::vector<std::string>& items, const char* lastSeparator) {
    std::string out;
    for (std::size_t i = 0; i < items.size(); ++i) {
        if (i > 0) out += i + 1 == items.size() ? lastSeparator : ", ";
        out += items[i];
    }
    return out;
}

Json readJsonDocument(std::string_view text, const std::string& file, ReadingChecks* checks,
                      std::size_t maxBytes) {
    Json root;
    DocumentBuilder builder(root, text, file, checks, maxBytes);
    // strict: nothing may follow the document; comments are not JSON.
    Json::sax_parse(text, &builder, Json::input_format_t::json, true, false);
    return root;
}

}  // namespace substep::scene_loader
