#pragma once
/// An output file that appears whole or not at all: bytes go to a temporary file next to the
/// target, and only commit() renames it into place. DESIGN.md: bad input never leaves a
/// half-written output, so every file the `substep` command writes goes through this.
///
/// Targets: a regular file (replaced) or a new name. A symlink is written through: the file it
/// points to is replaced and the link stays. Anything else (a directory, a device such as
/// /dev/null, a FIFO, a socket, a dangling symlink) is refused, so a device is never replaced.

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
    /// Creates the temporary file in the (resolved) target's directory (a rename never crosses
    /// file systems that way). Throws OutputError when the directory is missing or unwritable,
    /// or when the target is not a regular file or a new name.
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
    /// The first half of commit(): flushes and closes the temporary file, so every write error
    /// (a full disk) is known before any target is touched. On failure the temporary file is
    /// removed and OutputError is thrown. commit() after it only renames.
    void finish();
    /// Removes the temporary file; the target is left as it was.
    void discard() noexcept;
    /// discard() was called before a commit: the output is dropped.
    bool discarded() const { return discarded_; }

    /// The target as given.
    const std::string& path() const { return path_; }
    /// Where the bytes land: the target, or the file a symlink target points to.
    const std::string& resolvedPath() const { return resolvedPath_; }
    const std::string& temporaryPath() const { return temporaryPath_; }

  private:
    std::string path_;
    std::string resolvedPath_;
    std::string temporaryPath_;
    std::FILE* file_ = nullptr;
    bool committed_ = false;
    bool finished_ = false;
    bool discarded_ = false;
};

/// Removes `.NAME.tmp-PID-N` files in `directory` left by processes that no longer run (a
/// SIGKILL gives no chance to clean up). Files of running processes are left alone.
void removeStaleTemporaries(const std::string& directory) noexcept;

/// The file name with control characters escaped (`\n`, `\x1b`), so that a message naming it
/// stays one line.
std::string printableName(std::string_view name);

}  // namespace substep
