// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A temporary file beside a destination path, renamed over it on commit() and removed
// otherwise: readers of the destination never see a half-written file, and a failed write
// leaves an existing file untouched. The temporary is in the same folder so the rename
// stays on one file system (atomic on POSIX).
#include <string>

namespace hyvox::io {

class AtomicFile {
public:
    // Creates an empty, unique temporary file; throws InvalidInput when the destination's
    // folder is missing or not writable, or the destination is a folder.
    explicit AtomicFile(std::string destination);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    const std::string& tempPath() const { return temp_; }
    const std::string& destination() const { return destination_; }
    // Flushes the temporary to disk and renames it over the destination; throws ResourceError.
    void commit();

private:
    std::string destination_;
    std::string temp_;
    bool committed_ = false;
};

}  // namespace hyvox::io
