// SPDX-License-Identifier: GPL-3.0-or-later
#include "os/file_bytes.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

#include "os/mesh_file_error.h"

namespace hyvox::os {
namespace {

// A descriptor closed on every path out.
struct Fd {
    int fd;
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
};

// O_NONBLOCK: opening a FIFO with no writer must not hang; it is refused just after.
Fd openRegular(const std::string& path, struct stat& st) {
    Fd file{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
    if (file.fd < 0) throw InvalidInput("cannot open mesh file '" + path + "': " + std::strerror(errno));
    if (::fstat(file.fd, &st) != 0) throw InvalidInput("cannot open mesh file '" + path + "': " + std::strerror(errno));
    if (S_ISDIR(st.st_mode)) throw InvalidInput("mesh path '" + path + "' is a folder, not a file");
    if (!S_ISREG(st.st_mode))
        throw InvalidInput("mesh path '" + path + "' is not a regular file (a device, FIFO or socket is not read)");
    return file;
}

std::vector<char> readUpTo(const Fd& file, const std::string& path, std::size_t n) {
    std::vector<char> bytes(n);
    std::size_t got = 0;
    while (got < n) {
        const ssize_t r = ::read(file.fd, bytes.data() + got, n - got);
        if (r < 0 && errno == EINTR) continue;
        if (r < 0) throw InvalidInput("cannot read mesh file '" + path + "': " + std::strerror(errno));
        if (r == 0) break;
        got += std::size_t(r);
    }
    bytes.resize(got);
    return bytes;
}

}  // namespace

std::uint64_t checkMeshFile(const std::string& path) {
    struct stat st {};
    const Fd file = openRegular(path, st);
    if (st.st_size == 0) throw InvalidInput("mesh file '" + path + "' is empty");
    return std::uint64_t(st.st_size);
}

std::vector<char> readFileBytes(const std::string& path, std::size_t max_bytes) {
    struct stat st {};
    const Fd file = openRegular(path, st);
    if (std::uint64_t(st.st_size) > max_bytes)
        failMeshFile(path,
                     "is " + std::to_string(st.st_size) + " bytes, more than the " + std::to_string(max_bytes) +
                         " this reader accepts");
    std::vector<char> bytes = readUpTo(file, path, std::size_t(st.st_size));
    if (bytes.size() != std::size_t(st.st_size)) failMeshFile(path, "changed size while it was read");
    return bytes;
}

std::vector<char> readFilePrefix(const std::string& path, std::size_t n) {
    struct stat st {};
    const Fd file = openRegular(path, st);
    return readUpTo(file, path, n);
}

}  // namespace hyvox::os
