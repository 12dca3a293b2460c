#pragma once
/// All the outputs of one command, committed together: nothing appears unless every one of them
/// was written (DESIGN.md: bad input never leaves a partial output). `run --csv A --json B`
/// where B cannot be written leaves A as it was; an interrupted or failed `render` leaves none of
/// its PNGs. Used by run, bench, sweep, render and capture's report.

#include "atomic_file.h"

#include <memory>
#include <string>
#include <vector>

namespace substep {

class OutputTransaction {
  public:
    /// `inputs` are files the command reads (its scene): an output naming one of them, under
    /// any spelling or through a symlink, is refused.
    explicit OutputTransaction(std::vector<std::string> inputs = {});

    /// A new output for `option` (named in messages, e.g. "--csv"). Throws UsageError for an
    /// empty name, the same file as an earlier output or an input; OutputError when it cannot
    /// be created (AtomicFile). Removes stale temporaries of dead processes in its folder once.
    AtomicFile& add(const std::string& option, const std::string& path);

    /// Finishes every file (all write errors known), then renames each into place. On a failure
    /// in the first phase no target is touched and OutputError is thrown. A failed rename (rare:
    /// the folder was checked when the file was made) is reported after the others are placed.
    void commit();

    /// Drops every temporary file; the destructor does it too unless commit() succeeded.
    void discard() noexcept;

    std::size_t size() const { return files_.size(); }

  private:
    struct Entry {
        std::string option;
        std::string identity;  ///< the path with symlinks resolved, for comparisons
        std::unique_ptr<AtomicFile> file;
    };
    std::vector<std::string> inputIdentities_;
    std::vector<std::string> cleanedFolders_;
    std::vector<Entry> files_;
};

/// The path with `.`, `..` and symlinks resolved as far as it exists, for telling whether two
/// names are the same file.
std::string fileIdentity(const std::string& path);

}  // namespace substep
