#include "output_transaction.h"

#include "command_options.h"

#include <algorithm>
#include <filesystem>
#include <utility>

namespace substep {

std::string fileIdentity(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code error;
    const fs::path resolved = fs::weakly_canonical(fs::absolute(path, error), error);
    return error ? fs::path(path).lexically_normal().string() : resolved.string();
}

OutputTransaction::OutputTransaction(std::vector<std::string> inputs) {
    for (const std::string& input : inputs)
        inputIdentities_.push_back(fileIdentity(input));
}

AtomicFile& OutputTransaction::add(const std::string& option, const std::string& path) {
    if (path.empty()) throw UsageError(option + ": empty file name");
    const std::string identity = fileIdentity(path);
    const std::string shown = printableName(path);
    if (std::find(inputIdentities_.begin(), inputIdentities_.end(), identity) !=
        inputIdentities_.end()) {
        throw UsageError(option + " " + shown + ": is an input of this command; refusing to overwrite it");
    }
    for (const Entry& entry : files_) {
        if (entry.identity == identity) {
            throw UsageError(option + " " + shown + ": the same file as " + entry.option +
                             "; give each output its own file");
        }
    }
    const std::string folder = std::filesystem::path(identity).parent_path().string();
    if (std::find(cleanedFolders_.begin(), cleanedFolders_.end(), folder) == cleanedFolders_.end()) {
        removeStaleTemporaries(folder);
        cleanedFolders_.push_back(folder);
    }
    files_.push_back({option, identity, std::make_unique<AtomicFile>(path)});
    return *files_.back().file;
}

void OutputTransaction::commit() {
    try {
        for (Entry& entry : files_)
            if (!entry.file->discarded()) entry.file->finish();
    } catch (...) {
        discard();
        throw;
    }
    // Every byte is on disk; the renames cannot run out of space. A failure is reported after
    // the rest are placed, as the first one seen.
    std::string failure;
    for (Entry& entry : files_) {
        if (entry.file->discarded()) continue;  // dropped on purpose (sweep's failed plot)
        try {
            entry.file->commit();
        } catch (const OutputError& error) {
            if (failure.empty()) failure = error.what();
        }
    }
    files_.clear();
    if (!failure.empty()) throw OutputError(failure);
}

void OutputTransaction::discard() noexcept {
    for (Entry& entry : files_) entry.file->discard();
    files_.clear();
}

}  // namespace substep
