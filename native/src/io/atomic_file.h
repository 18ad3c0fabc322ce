// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A temporary file beside a destination path, renamed over it on commit() and removed
// otherwise: readers of the destination never see a half-written file, and a failed write
// leaves an existing file untouched. The temporary is in the same folder so the rename
// stays on one file system (atomic on POSIX). An existing destination must be a regular
// file (or a symlink to one: the file it names is replaced, the link kept); the new file
// gets the old one's permission bits.
#include <functional>
#include <ostream>
#include <string>

namespace hyvox::io {

class AtomicFile {
public:
    // Creates an empty, unique temporary file; throws InvalidInput when the destination's
    // folder is missing or not writable, or the destination is a folder, a device, FIFO or
    // socket, or a symlink to nothing, and ResourceError
    // when the system is out of a resource (disk space, quota, file descriptors, I/O error).
    explicit AtomicFile(std::string destination);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    // Opens the temporary as a binary stream that throws on failure, calls write(stream),
    // closes and checks the stream, then commit()s. A stream failure becomes ResourceError
    // ("writing '<destination>' failed: <errno text, or I/O error>"); anything else write
    // throws passes through unchanged. On any throw the destination is left as it was.
    void writeWith(const std::function<void(std::ostream&)>& write);

private:
    // Flushes the temporary to disk and renames it over the destination; throws ResourceError.
    void commit();

    std::string destination_;  // as the caller gave it (for messages)
    std::string target_;       // the file replaced: destination_ with a symlink resolved
    std::string temp_;
    long keep_mode_ = -1;      // the replaced file's permission bits, or -1 for a new file
    bool committed_ = false;
};

}  // namespace hyvox::io
