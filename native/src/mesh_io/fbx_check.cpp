// SPDX-License-Identifier: GPL-3.0-or-later
// The binary FBX layout (as Blender's exporter and the FBX SDK write it): a 27-byte header
// ("Kaydara FBX Binary  ", 0x00 0x1A 0x00, uint32 version), then node records: end offset,
// property count, property bytes (uint32 each before version 7500, uint64 from it), a name
// length byte and the name, the properties, and child records closed by an all-zero record.
#include "mesh_io/fbx_check.h"

#include <zlib.h>

#include <cstring>
#include <string>

#include "os/mesh_file_error.h"

namespace hyvox::mesh_io {
namespace {

constexpr char kMagic[] = "Kaydara FBX Binary  ";
constexpr std::size_t kHeaderBytes = 27;
constexpr int kMaxDepth = 64;

class FbxChecker {
public:
    FbxChecker(const char* data, std::size_t size, const std::string& name, std::uint64_t max_bytes)
        : data_(data), size_(size), name_(name), max_bytes_(max_bytes) {}

    void check() {
        if (size_ >= 18 && std::memcmp(data_, "; FBX ", 6) == 0)
            fail("ASCII FBX is not read; export the file as binary FBX (as Blender and the FBX SDK write it)");
        if (size_ < kHeaderBytes || std::memcmp(data_, kMagic, 20) != 0 || data_[20] != 0 || data_[21] != 0x1A ||
            data_[22] != 0)
            fail("is not a binary FBX file (no 'Kaydara FBX Binary' header)");
        std::uint32_t version;
        std::memcpy(&version, data_ + 23, 4);
        if (version < 7000 || version >= 8000) fail("version " + std::to_string(version) + " (only FBX 7.x is read)");
        wide_ = version >= 7500;
        std::uint64_t at = kHeaderBytes;
        // The top-level records, closed by a null record; what follows (the footer) is not read.
        while (!record(at, size_, 0)) {}
    }

private:
    [[noreturn]] void fail(const std::string& what) const { os::failMeshFile(name_, "FBX " + what); }
    [[noreturn]] void failAt(std::uint64_t at, const std::string& what) const {
        fail("byte " + std::to_string(at) + ": " + what);
    }

    std::uint64_t field(std::uint64_t& at, std::uint64_t end) const {
        const std::size_t n = wide_ ? 8 : 4;
        if (end - at < n) failAt(at, "a record header runs past its end");
        std::uint64_t value = 0;
        std::memcpy(&value, data_ + at, n);  // little-endian, as on every host hyvox builds for
        at += n;
        return value;
    }

    template <typename T>
    T load(std::uint64_t at) const {
        T value;
        std::memcpy(&value, data_ + at, sizeof value);
        return value;
    }

    // The record at `at`, which must end by `end`; true for the null record that closes a list.
    bool record(std::uint64_t& at, std::uint64_t end, int depth) {
        if (depth > kMaxDepth) failAt(at, "records nested more than 64 deep");
        const std::uint64_t start = at;
        const std::uint64_t record_end = field(at, end), properties = field(at, end), property_bytes = field(at, end);
        if (at >= end) failAt(start, "a record header runs past its end");
        const std::uint8_t name_length = std::uint8_t(data_[at++]);
        if (record_end == 0) {
            if (properties || property_bytes || name_length) failAt(start, "a null record that is not all zeros");
            return true;
        }
        // Past its own header (or the subtractions below would wrap), and inside its parent.
        if (record_end < at || record_end > end)
            failAt(start,
                   "a record ends at " + std::to_string(record_end) + ", outside its parent (which ends at " +
                       std::to_string(end) + ") or inside its own header");
        if (name_length > record_end - at) failAt(start, "a record's name runs past its end");
        at += name_length;
        if (property_bytes > record_end - at) failAt(start, "a record's properties run past its end");
        const std::uint64_t properties_end = at + property_bytes;
        for (std::uint64_t p = 0; p < properties; ++p) property(at, properties_end);
        if (at != properties_end)
            failAt(start,
                   "a record's properties take " + std::to_string(at - (properties_end - property_bytes)) +
                       " bytes, its header says " + std::to_string(property_bytes));
        if (at < record_end) {
            while (!record(at, record_end, depth + 1)) {}
            if (at != record_end) failAt(start, "a record's children end before the record does");
        }
        return false;
    }

    void property(std::uint64_t& at, std::uint64_t end) {
        if (at >= end) failAt(at, "a property runs past its record's properties");
        const char type = data_[at++];
        auto need = [&](std::uint64_t n) {
            if (end - at < n) failAt(at, std::string("a '") + type + "' property runs past its record's properties");
        };
        switch (type) {
            case 'C':
                need(1);
                at += 1;
                return;
            case 'Y':
                need(2);
                at += 2;
                return;
            case 'I':
            case 'F':
                need(4);
                at += 4;
                return;
            case 'D':
            case 'L':
                need(8);
                at += 8;
                return;
            case 'S':
            case 'R': {
                need(4);
                const std::uint32_t length = load<std::uint32_t>(at);
                at += 4;
                need(length);
                at += length;
                return;
            }
            case 'f':
            case 'i': array(at, end, 4); return;
            case 'd':
            case 'l': array(at, end, 8); return;
            case 'b':
            case 'c': array(at, end, 1); return;
            default:
                failAt(at - 1, "a property of unknown type " + std::to_string(int(static_cast<unsigned char>(type))));
        }
    }

    void array(std::uint64_t& at, std::uint64_t end, std::uint64_t element) {
        if (end - at < 12) failAt(at, "an array property's header runs past its record");
        const std::uint32_t count = load<std::uint32_t>(at), encoding = load<std::uint32_t>(at + 4),
                            stored = load<std::uint32_t>(at + 8);
        const std::uint64_t header = at;
        at += 12;
        if (stored > end - at) failAt(header, "an array of " + std::to_string(stored) + " bytes runs past its record");
        const std::uint64_t bytes = std::uint64_t(count) * element;
        if (encoding == 0) {
            if (stored != bytes)
                failAt(header,
                       "an array of " + std::to_string(count) + " values holds " + std::to_string(stored) +
                           " bytes, not " + std::to_string(bytes));
        } else if (encoding == 1) {
            inflateExactly(data_ + at, stored, bytes, header);
        } else {
            failAt(header, "an array of unknown encoding " + std::to_string(encoding));
        }
        at += stored;
    }

    // The zlib stream must inflate to exactly `bytes` and end where its stored bytes do; it is
    // inflated through a small buffer, so a count that lies costs no memory.
    void inflateExactly(const char* in, std::uint32_t stored, std::uint64_t bytes, std::uint64_t header) const {
        if (bytes > max_bytes_) failAt(header, "an array larger than the memory budget");
        z_stream stream{};
        if (inflateInit(&stream) != Z_OK) failAt(header, "cannot start zlib");
        stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in));
        stream.avail_in = stored;
        char chunk[1 << 16];
        std::uint64_t produced = 0;
        int status = Z_OK;
        while (status == Z_OK && produced <= bytes) {
            stream.next_out = reinterpret_cast<Bytef*>(chunk);
            stream.avail_out = sizeof chunk;
            status = inflate(&stream, Z_NO_FLUSH);
            produced += sizeof chunk - stream.avail_out;
            if (status == Z_BUF_ERROR && stream.avail_in == 0) break;  // the stream ends early
        }
        const std::uint32_t left = stream.avail_in;
        inflateEnd(&stream);
        if (status != Z_STREAM_END || produced != bytes || left != 0)
            failAt(header, "a compressed array that does not inflate to its " + std::to_string(bytes) + " bytes");
    }

    const char* data_;
    std::size_t size_;
    const std::string& name_;
    std::uint64_t max_bytes_;
    bool wide_ = false;
};

}  // namespace

void checkFbxContainer(const char* data, std::size_t size, const std::string& name, std::uint64_t max_bytes) {
    FbxChecker(data, size, name, max_bytes).check();
}

}  // namespace hyvox::mesh_io
