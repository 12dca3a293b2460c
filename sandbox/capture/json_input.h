#pragma once
/// Reading the capture command's JSON inputs (capture scripts, golden state files) so that every
/// problem is one message naming the file and the JSON path of the offending value
/// (`gallery.json: captures[0].frames[2]: must be larger than the frame before it, 40`), the way
/// scene files report theirs (DESIGN.md, exit code 2).

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>

namespace substep::capture {

/// Bad input: what() is `FILE: PATH: problem` (or `FILE: problem` for the file as a whole).
class InputError : public std::runtime_error {
  public:
    InputError(const std::string& file, const std::string& path, const std::string& problem);
};

/// The whole of `file`'s text. Throws InputError when it cannot be read.
std::string readTextFile(const std::string& file);

/// Parses JSON text. Syntax errors, overflowing numbers and duplicate keys throw InputError
/// naming `file` and the path where they occur.
nlohmann::ordered_json parseJson(std::string_view text, const std::string& file);

/// A value inside a parsed document together with its path, for checked reads.
class JsonAt {
  public:
    JsonAt(const nlohmann::ordered_json& value, std::string path, std::string file)
        : value_(value), path_(std::move(path)), file_(std::move(file)) {}

    const nlohmann::ordered_json& value() const { return value_; }
    const std::string& path() const { return path_; }

    /// Throws InputError at this value's path.
    [[noreturn]] void fail(const std::string& problem) const;

    /// Requires an object whose keys are all in `allowed` (an unknown key names itself).
    void requireObject(std::initializer_list<std::string_view> allowed) const;
    /// Requires an array of `size` elements (any size when size < 0).
    void requireArray(long long size = -1) const;

    bool has(std::string_view key) const;
    /// The member `key` (an object is required first); fails when missing.
    JsonAt member(std::string_view key) const;
    JsonAt element(std::size_t index) const;
    std::size_t size() const { return value_.size(); }

    /// A finite number in [lowest, highest].
    double number(double lowest, double highest) const;
    /// A whole number (written without fraction or exponent) in [lowest, highest].
    long long integer(long long lowest, long long highest) const;
    /// A string, or a boolean.
    std::string string() const;
    bool boolean() const;

  private:
    const nlohmann::ordered_json& value_;
    std::string path_;
    std::string file_;
};

/// `name` as JSON string text, for messages.
std::string jsonQuoted(std::string_view name);

}  // namespace substep::capture
