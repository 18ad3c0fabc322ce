// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A mesh file mapped into memory (read-only, pages taken straight from the page cache): no
// fresh memory to fault in and zero, and no copy: a fraction of the CPU that read() into a
// buffer costs (docs/why/startup.md).
//
// A mapped file that another process shortens while it is read would raise SIGBUS on the
// pages past its new end. While a MappedFile lives, a SIGBUS inside its mapping instead
// puts a page of zeros there and marks the file as changed: the reader finishes (or fails)
// on zeros, and readMesh reports "changed size while it was read", as for read().
#include <cstddef>
#include <string>
#include <vector>

namespace hyvox::os {

class MappedFile {
public:
    // Maps the regular file at `path` (InvalidInput as readFileBytes: missing, a folder, not
    // a regular file, more than max_bytes). An empty file maps to size() 0.
    MappedFile(const std::string& path, std::size_t max_bytes);
    ~MappedFile();
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;

    const char* data() const { return data_; }
    std::size_t size() const { return size_; }
    // True once a page past the file's end was read (the file shrank after it was mapped).
    bool changedWhileRead() const;

private:
    const char* data_ = nullptr;
    std::size_t size_ = 0;
    int slot_ = -1;           // its entry in the SIGBUS guard's table (-1: not mapped)
    std::vector<char> copy_;  // the bytes read instead, when every entry of the table is taken
};

}  // namespace hyvox::os
