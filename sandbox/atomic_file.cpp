#include "atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <utility>

#include <fcntl.h>
#include <sys/stat.h>
#include <signal.h>
#include <unistd.h>

namespace substep {

namespace {

std::string systemError(const std::string& path, const char* what, int error) {
    return printableName(path) + ": " + what + " (" + std::strerror(error) + ")";
}

/// The PID in a temporary file's name `.NAME.tmp-PID-N`, or 0 when the name is not one.
pid_t temporaryOwner(const std::string& name) {
    if (name.size() < 2 || name[0] != '.') return 0;
    const std::size_t tag = name.rfind(".tmp-");
    if (tag == std::string::npos || tag == 0) return 0;
    const std::size_t dash = name.find('-', tag + 5);
    if (dash == std::string::npos || dash == tag + 5 || dash + 1 == name.size()) return 0;
    long long pid = 0;
    for (std::size_t i = tag + 5; i < dash; ++i) {
        if (name[i] < '0' || name[i] > '9' || pid > 1'000'000'000) return 0;
        pid = pid * 10 + (name[i] - '0');
    }
    for (std::size_t i = dash + 1; i < name.size(); ++i)
        if (name[i] < '0' || name[i] > '9') return 0;
    return static_cast<pid_t>(pid);
}

// Large enough that a CSV row per frame costs no system call of its own.
constexpr std::size_t kBufferBytes = std::size_t{1} << 20;

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
    namespace fs = std::filesystem;
    const std::string shown = printableName(path_);
    if (path_.empty() || !fs::path(path_).has_filename()) throw OutputError(shown + ": not a file name");
    std::error_code error;
    fs::path resolved(path_);
    const fs::file_status link = fs::symlink_status(resolved, error);
    if (fs::is_symlink(link)) {
        // Written through: the link is the user's way of naming the file it points to.
        resolved = fs::canonical(resolved, error);
        if (error) throw OutputError(shown + ": a symlink to nothing (" + error.message() + ")");
    }
    const fs::file_status status = fs::status(resolved, error);
    if (fs::is_directory(status)) throw OutputError(shown + ": is a directory");
    if (fs::exists(status) && !fs::is_regular_file(status)) {
        throw OutputError(shown +
                          ": not a regular file (a device, FIFO or socket); refusing to replace it");
    }
    resolvedPath_ = resolved.string();
    const fs::path target(resolvedPath_);

    // A hidden name next to the target, unique per process; O_EXCL never reuses a stranger's.
    const fs::path directory = target.parent_path();
    // (Appended piece by piece: GCC 12's -Wrestrict misfires on "." + std::string.)
    std::string stem = ".";
    stem += target.filename().string();
    stem += ".tmp-";
    stem += std::to_string(getpid());
    int descriptor = -1;
    for (int attempt = 0; attempt < 100 && descriptor < 0; ++attempt) {
        temporaryPath_ = (directory / (stem + "-" + std::to_string(attempt))).string();
        // 0666 under the umask: the file ends up with the permissions a plain fopen would give.
        descriptor = ::open(temporaryPath_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (descriptor < 0 && errno != EEXIST) break;
    }
    if (descriptor < 0) {
        const int openError = errno;
        temporaryPath_.clear();
        throw OutputError(systemError(path_, "cannot create file", openError));
    }
    file_ = ::fdopen(descriptor, "wb");
    if (file_ == nullptr) {
        const int openError = errno;
        ::close(descriptor);
        ::unlink(temporaryPath_.c_str());
        temporaryPath_.clear();
        throw OutputError(systemError(path_, "cannot create file", openError));
    }
    std::setvbuf(file_, nullptr, _IOFBF, kBufferBytes);
}

AtomicFile::~AtomicFile() {
    if (!committed_) discard();
}

void AtomicFile::write(std::string_view bytes) {
    if (file_ != nullptr && !bytes.empty()) std::fwrite(bytes.data(), 1, bytes.size(), file_);
}

void AtomicFile::finish() {
    if (finished_ || committed_) return;
    if (file_ == nullptr) throw OutputError(printableName(path_) + ": output already discarded");
    // Any buffered write error (a full disk) surfaces here, before the target is touched.
    const bool writeFailed = std::fflush(file_) != 0 || std::ferror(file_) != 0;
    int error = errno;
    const bool closeFailed = std::fclose(file_) != 0;
    if (!writeFailed && closeFailed) error = errno;
    file_ = nullptr;
    if (writeFailed || closeFailed) {
        discard();
        throw OutputError(systemError(path_, "cannot write", error));
    }
    finished_ = true;
}

void AtomicFile::commit() {
    if (committed_) return;
    finish();
    if (std::rename(temporaryPath_.c_str(), resolvedPath_.c_str()) != 0) {
        const int error = errno;
        discard();
        throw OutputError(systemError(path_, "cannot replace", error));
    }
    temporaryPath_.clear();
    committed_ = true;
}

void removeStaleTemporaries(const std::string& directory) noexcept {
    namespace fs = std::filesystem;
    std::error_code error;
    fs::directory_iterator entries(directory.empty() ? "." : directory, error);
    if (error) return;
    for (const fs::directory_entry& entry : entries) {
        const pid_t owner = temporaryOwner(entry.path().filename().string());
        // ESRCH: no such process. EPERM means it runs under another user: leave its file.
        if (owner <= 0 || owner == getpid() || ::kill(owner, 0) == 0 || errno != ESRCH) continue;
        if (!entry.is_regular_file(error)) continue;
        fs::remove(entry.path(), error);
    }
}

std::string printableName(std::string_view name) {
    std::string shown;
    shown.reserve(name.size());
    for (const char c : name) {
        const auto byte = static_cast<unsigned char>(c);
        if (c == '\n') {
            shown += "\\n";
        } else if (byte < 0x20 || byte == 0x7f) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
            shown += escaped;
        } else {
            shown += c;
        }
    }
    return shown;
}

void AtomicFile::discard() noexcept {
    if (!committed_) discarded_ = true;
    if (file_ != nullptr) {
        std::fclose(file_);
        file_ = nullptr;
    }
    if (!temporaryPath_.empty()) {
        ::unlink(temporaryPath_.c_str());
        temporaryPath_.clear();
    }
}

}  // namespace substep
