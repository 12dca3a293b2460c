#include "atomic_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <utility>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace substep {

namespace {

std::string systemError(const std::string& path, const char* what, int error) {
    return path + ": " + what + " (" + std::strerror(error) + ")";
}

// Large enough that a CSV row per frame costs no system call of its own.
constexpr std::size_t kBufferBytes = std::size_t{1} << 20;

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
    namespace fs = std::filesystem;
    const fs::path target(path_);
    if (path_.empty() || !target.has_filename()) throw OutputError(path_ + ": not a file name");
    std::error_code error;
    if (fs::is_directory(target, error)) throw OutputError(path_ + ": is a directory");

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

void AtomicFile::commit() {
    if (committed_) return;
    if (file_ == nullptr) throw OutputError(path_ + ": output already discarded");
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
    if (std::rename(temporaryPath_.c_str(), path_.c_str()) != 0) {
        error = errno;
        discard();
        throw OutputError(systemError(path_, "cannot replace", error));
    }
    committed_ = true;
}

void AtomicFile::discard() noexcept {
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
