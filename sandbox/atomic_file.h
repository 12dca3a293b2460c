#pragma once
/// An output file that appears whole or not at all: bytes go to a temporary file next to the
/// target, and only commit() renames it into place. DESIGN.md: bad input never leaves a
/// half-written output, so every file the `substep` command writes goes through this.

#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>

namespace substep {

/// An output could not be created, written or moved into place; what() names the file.
class OutputError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class AtomicFile {
  public:
    /// Creates the temporary file in the target's directory (a rename never crosses file
    /// systems that way). Throws OutputError when the directory is missing or unwritable, or
    /// when the target is a directory.
    explicit AtomicFile(std::string path);
    /// Discards the temporary file unless commit() succeeded.
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    /// Buffered write; failures are remembered and reported by commit().
    void write(std::string_view bytes);
    /// Flushes, closes and renames the temporary file onto the target. On failure the temporary
    /// file is removed and OutputError is thrown.
    void commit();
    /// Removes the temporary file; the target is left as it was.
    void discard() noexcept;

    const std::string& path() const { return path_; }
    const std::string& temporaryPath() const { return temporaryPath_; }

  private:
    std::string path_;
    std::string temporaryPath_;
    std::FILE* file_ = nullptr;
    bool committed_ = false;
};

}  // namespace substep
