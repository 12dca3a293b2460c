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

/// Parses `text` strictly (nothing may follow the document; comments are not JSON). Syntax
/// errors (with line and column), numbers that overflow a double or underflow to 0, duplicate
/// keys, objects of more than 1000 keys and nesting deeper than 64 levels throw SceneError at the
/// JSON path where they occur (`top level` for the document itself); `file` names the source.
Json readJsonDocument(std::string_view text, const std::string& file);

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
