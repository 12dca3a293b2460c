#pragma once
/// Scene files, the JSON layer of the loader: reads JSON text into a document while knowing the
/// JSON path of every value, and the text helpers every message is made of (paths such as
/// `bodies[3].shape.radius`, values described as `the string "x"`, typo suggestions).
///
/// Internal to the scene library; the public entry points are in scene_loader.h. The layers:
/// this file, then the validator (scene_loader_validator.h), then one reader per top-level key
/// (scene_loader_sections.h), called by parseSceneText (scene_loader.cpp).

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace substep::scene_loader {

/// The document. Ordered, so that "unknown key" reports the first offender in file order.
using Json = nlohmann::ordered_json;

/// What a document may take in memory once read (estimated as the parser goes): a 4096 x 4096
/// heightfield, the largest array of numbers the format has, takes 256 MiB; a file of empty
/// arrays would take 20 times its size.
inline constexpr std::size_t kMaxDocumentBytes = std::size_t{512} << 20;

/// Checks of the format made while the document is read, before it is whole, so that a large
/// invalid file fails where the problem is met instead of after building all of it. The JSON
/// layer knows no keys: the loader (scene_loader.cpp) supplies these. Each throws SceneError.
class ReadingChecks {
  public:
    virtual ~ReadingChecks() = default;
    /// The document's outermost value has opened (`container` is the empty object or array).
    virtual void documentStart(const Json& container) = 0;
    /// A key of the top-level object has been read, before its value.
    virtual void topLevelKey(const std::string& key) = 0;
    /// The value of the top-level member `key` has been read whole.
    virtual void topLevelValue(const std::string& key, const Json& value) = 0;
};

/// Parses `text` strictly (nothing may follow the document; comments are not JSON). Syntax
/// errors (with line and column), numbers that overflow a double or underflow to 0, duplicate
/// keys, objects of more than 1000 keys, arrays of more than 100000 elements, nesting deeper
/// than 64 levels and a document that would take more than `maxBytes` of memory throw SceneError
/// at the JSON path where they occur (`top level` for the document itself), as soon as the
/// parser meets them; so do the failures of `checks` (optional). `file` names the source;
/// `maxBytes` lowers the memory bound (for tests).
Json readJsonDocument(std::string_view text, const std::string& file,
                      ReadingChecks* checks = nullptr, std::size_t maxBytes = kMaxDocumentBytes);

/// Shortest text that reads back as the same double.
std::string formatNumber(double value);

/// A string as a JSON literal (quoted and escaped), so messages stay on one line.
std::string jsonQuoted(std::string_view text);

/// `parent.key`, or `parent["odd key"]` for keys that are not identifiers. The root path is "".
std::string memberPath(const std::string& parent, std::string_view key);

/// `parent[index]`.
std::string elementPath(const std::string& parent, std::size_t index);

/// What a value is, for "must be X, got Y" (`null`, `-1`, `the string "x"`, `an array`).
std::string describe(const Json& value);

/// ` (did you mean "x"?)` when one candidate is a plausible typo of `word`, else "".
std::string suggestion(std::string_view word, const std::vector<std::string>& candidates);

/// `a, b or c` with `lastSeparator` = " or ".
std::string joinList(const std::vector<std::string>& items, const char* lastSeparator);

}  // namespace substep::scene_loader
