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

namespace hyvox::os {

// What commit() promises beyond "readers never see a half-written file".
//
// Atomic (the default): the temporary is renamed over the destination, nothing is synced.
// If hyvox is killed or crashes at any point, the destination is the old file or the whole
// new one: the rename is one step, and what was written is in the kernel's page cache,
// which outlives the process. Only a power loss or kernel crash within the next few seconds
// (before the kernel writes the cache back) can lose the new file; on ext4 (auto_da_alloc)
// a rename over an existing file even starts writing the new data out. This is what OpenVDB's
// own writer (no sync at all: it writes straight to the path), Blender's .blend save
// (temporary + rename, no fsync: neither binary imports fsync) and the cuda_voxelizer peer
// do; an fsync costs as much wall time as a whole small voxelization (docs/why/vdb-output.md).
//
// Durable (WriteOptions::durable, the durable_write option): fsync the temporary before the rename and the folder
// after it, so that once commit() returns the new file survives a power loss too. (A failed
// sync of the folder is reported although the new file is already in place.)
enum class Durability { Atomic, Durable };

// Throws InvalidInput when no AtomicFile could replace `destination` (the checks its
// constructor makes, without creating anything): see hyvox::checkOutputPath.
void checkDestination(const std::string& destination);

class AtomicFile {
public:
    // Creates an empty, unique temporary file; throws InvalidInput when the destination's
    // folder is missing or not writable, or the destination is a folder, a device, FIFO or
    // socket, or a symlink to nothing, and ResourceError
    // when the system is out of a resource (disk space, quota, file descriptors, I/O error).
    explicit AtomicFile(std::string destination, Durability durability = Durability::Atomic);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    // Opens the temporary as a binary stream that throws on failure, calls write(stream),
    // closes and checks the stream, then commit()s. A stream failure becomes ResourceError
    // ("writing '<destination>' failed: <errno text, or I/O error>"); anything else write
    // throws passes through unchanged. On any throw the destination is left as it was.
    void writeWith(const std::function<void(std::ostream&)>& write);

private:
    // Renames the temporary over the destination (Durable: syncing the file before and its
    // folder after); throws ResourceError.
    void commit();
    void syncPath(const std::string& path, const char* what) const;  // fsync, or ResourceError

    std::string destination_;  // as the caller gave it (for messages)
    std::string target_;       // the file replaced: destination_ with a symlink resolved
    std::string temp_;
    long keep_mode_ = -1;  // the replaced file's permission bits, or -1 for a new file
    Durability durability_;
    bool committed_ = false;
};

}  // namespace hyvox::os
