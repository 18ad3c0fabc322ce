// SPDX-License-Identifier: GPL-3.0-or-later
#include "os/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include "hyvox/errors.h"

namespace hyvox::os {
namespace {

std::string errnoText() { return std::strerror(errno); }

std::string folderOf(const std::string& path) {
    const auto slash = path.find_last_of('/');
    if (slash == std::string::npos) return ".";
    if (slash == 0) return "/";
    return path.substr(0, slash);
}

// Whether a failure to create a file says the path is unusable (the caller's mistake) rather
// than the system being out of something (disk space, quota, descriptors) or failing.
bool isPathError(int error) {
    switch (error) {
        case EACCES:
        case EPERM:
        case ENOENT:
        case ENOTDIR:
        case EROFS:
        case ENAMETOOLONG:
        case EISDIR:
        case ELOOP: return true;
        default: return false;
    }
}

std::string baseOf(const std::string& path) {
    const auto slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

namespace {

struct Destination {
    std::string target;   // the file replaced: the destination with a symlink resolved
    long keep_mode = -1;  // the replaced file's permission bits, or -1 for a new file
};

// The file a write to `destination` replaces, or InvalidInput when none could be written
// there (checkDestination in atomic_file.h says what is refused).
Destination inspectDestination(const std::string& destination) {
    if (destination.empty()) throw InvalidInput("the output path is empty");
    const std::string base = baseOf(destination);
    if (base.empty() || base == "." || base == "..")
        throw InvalidInput("the output path '" + destination + "' names a folder, not a file");
    Destination out{destination};
    struct stat st {};
    if (::lstat(destination.c_str(), &st) == 0) {
        // A symlink is followed: the file it names is replaced and the link stays (renaming
        // over the link itself would turn it into a regular file). A link to nothing is refused.
        if (S_ISLNK(st.st_mode)) {
            char* resolved = ::realpath(destination.c_str(), nullptr);
            if (!resolved || ::stat(resolved, &st) != 0) {
                std::free(resolved);
                throw InvalidInput("the output path '" + destination + "' is a symlink to nothing; refusing to write");
            }
            out.target = resolved;
            std::free(resolved);
        }
        if (S_ISDIR(st.st_mode)) throw InvalidInput("the output path '" + destination + "' is a folder");
        // A device, FIFO or socket would be replaced by a regular file (as root, -o /dev/null
        // would remove /dev/null): refused.
        if (!S_ISREG(st.st_mode))
            throw InvalidInput("the output path '" + destination +
                               "' is not a regular file (a device, FIFO or socket); refusing to replace it");
        out.keep_mode = st.st_mode & 0777;  // the replaced file's permissions (never set-id bits)
    }
    // Other failures to stat the folder (no permission) are left to creating the file, which
    // names the system's reason.
    const std::string folder = folderOf(out.target);
    struct stat folder_st {};
    const bool missing =
        ::stat(folder.c_str(), &folder_st) == 0 ? !S_ISDIR(folder_st.st_mode) : errno == ENOENT || errno == ENOTDIR;
    if (missing) throw InvalidInput("cannot write '" + destination + "': folder '" + folder + "' does not exist");
    return out;
}

}  // namespace

AtomicFile::AtomicFile(std::string destination, Durability durability)
    : destination_(std::move(destination)), durability_(durability) {
    Destination checked = inspectDestination(destination_);
    target_ = std::move(checked.target);
    keep_mode_ = checked.keep_mode;

    // Hidden, unique per process and call; O_EXCL so two writers never share a temporary. The
    // target's name is shortened in it, so a valid name of up to 255 bytes still has one.
    static std::atomic<unsigned> counter{0};
    const std::string folder = folderOf(target_);
    const std::string target_base = baseOf(target_).substr(0, 200);
    for (int attempt = 0; attempt < 100; ++attempt) {
        std::string candidate = folder + "/." + target_base + ".tmp-" + std::to_string(::getpid()) + "-" +
            std::to_string(counter.fetch_add(1));
        // 0666 and the umask give the permissions a plain fopen would give a new file.
        const int fd = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            const bool mode_kept = keep_mode_ < 0 || ::fchmod(fd, mode_t(keep_mode_)) == 0;
            const int error = errno;
            ::close(fd);
            if (!mode_kept) {
                std::remove(candidate.c_str());
                throw ResourceError("cannot write '" + destination_ +
                                    "': cannot keep its permissions: " + std::strerror(error));
            }
            temp_ = std::move(candidate);
            return;
        }
        const int error = errno;
        if (error == EEXIST) continue;
        const std::string message = "cannot write '" + destination_ + "': cannot create a file in folder '" + folder +
            "': " + std::strerror(error);
        if (isPathError(error)) throw InvalidInput(message);
        throw ResourceError(message);
    }
    throw ResourceError("cannot write '" + destination_ + "': no free temporary file name in '" + folder + "'");
}

AtomicFile::~AtomicFile() {
    if (!committed_ && !temp_.empty()) std::remove(temp_.c_str());
}

void AtomicFile::commit() {
    // Durable: the data on disk before the name points at it, so a power loss right after
    // cannot leave an empty destination (the reasons for not doing it by default: Durability).
    if (durability_ == Durability::Durable) syncPath(temp_, "the temporary");
    if (std::rename(temp_.c_str(), target_.c_str()) != 0)
        throw ResourceError("cannot write '" + destination_ + "': renaming the temporary failed: " + errnoText());
    committed_ = true;
    // ... and the rename itself (the folder's entry) on disk before commit() returns.
    if (durability_ == Durability::Durable) syncPath(folderOf(target_), "its folder");
}

void AtomicFile::syncPath(const std::string& path, const char* what) const {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        throw ResourceError("cannot write '" + destination_ + "': opening " + what +
                            " to sync it failed: " + errnoText());
    const bool synced = ::fsync(fd) == 0;
    const std::string sync_error = synced ? "" : errnoText();
    ::close(fd);
    if (!synced)
        throw ResourceError("cannot write '" + destination_ + "': fsync of " + what + " failed: " + sync_error);
}

void AtomicFile::writeWith(const std::function<void(std::ostream&)>& write) {
    {
        std::ofstream file;
        errno = 0;  // so a failure below never quotes an older error
        file.exceptions(std::ios::failbit | std::ios::badbit);
        try {
            file.open(temp_, std::ios::out | std::ios::binary | std::ios::trunc);
            write(file);
            file.close();
        } catch (const std::ios_base::failure&) {
            throw ResourceError("writing '" + destination_ +
                                "' failed: " + (errno ? std::strerror(errno) : "I/O error"));
        }
    }
    commit();
}

void checkDestination(const std::string& destination) { inspectDestination(destination); }

}  // namespace hyvox::os
