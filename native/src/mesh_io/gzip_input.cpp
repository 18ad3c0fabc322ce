// SPDX-License-Identifier: GPL-3.0-or-later
// zlib's inflate directly, not gzread: gzread reports a truncated stream as a plain end of
// file (the caller then parses the part it got), and it cannot be told to stop at a limit.
#include "mesh_io/gzip_input.h"

#include <zlib.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "os/file_bytes.h"
#include "os/mesh_file_error.h"

namespace hyvox::mesh_io {

std::uint64_t gzipOutputLimit(std::uint64_t compressed_bytes, std::uint64_t budget) {
    const std::uint64_t ratio_cap = compressed_bytes > budget / 100 ? budget : 100 * compressed_bytes;
    return std::min(budget, std::max<std::uint64_t>(256ull << 20, ratio_cap));
}

std::vector<char> gunzip(const std::vector<char>& input, const std::string& path, std::uint64_t max_output,
                         Interrupter* interrupter) {
    z_stream stream{};
    if (inflateInit2(&stream, 16 + MAX_WBITS) != Z_OK) os::failMeshFile(path, "cannot start gzip decompression");
    struct End {
        z_stream& s;
        ~End() { inflateEnd(&s); }
    } end{stream};

    std::vector<char> output;
    std::vector<char> chunk(1 << 20);
    const char* next = input.data();
    std::size_t left = input.size();
    for (;;) {
        // One chunk (1 MiB of output) per turn; progress is the compressed input used (below
        // 100: the reading goes on after decompression).
        throwIfInterrupted(interrupter, int(99 * (input.size() - left) / std::max<std::size_t>(input.size(), 1)));
        // zlib counts in 32-bit units: feed at most 1 GiB at a time.
        const uInt feed = uInt(std::min<std::size_t>(left, 1u << 30));
        stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(next));
        stream.avail_in = feed;
        stream.next_out = reinterpret_cast<Bytef*>(chunk.data());
        stream.avail_out = uInt(chunk.size());
        const int status = inflate(&stream, Z_NO_FLUSH);
        const std::size_t consumed = feed - stream.avail_in;
        next += consumed;
        left -= consumed;
        const std::size_t produced = chunk.size() - stream.avail_out;
        if (output.size() + produced > max_output)
            os::failMeshFile(path,
                             "decompresses to more than " + std::to_string(max_output >> 20) +
                                 " MiB, the limit for a file of this size (a damaged file or a gzip bomb)");
        // Grown by doubling, but never past the limit: a refused bomb never held more.
        if (output.size() + produced > output.capacity())
            output.reserve(std::size_t(
                std::min<std::uint64_t>(max_output, std::max(2 * output.capacity(), output.size() + produced))));
        output.insert(output.end(), chunk.data(), chunk.data() + produced);
        if (status == Z_STREAM_END) {
            if (left == 0) break;
            inflateReset(&stream);  // another gzip member follows (as `cat a.gz b.gz` makes)
            continue;
        }
        // Z_BUF_ERROR means no progress was possible: with all input used, the stream was cut.
        if (status == Z_OK || (status == Z_BUF_ERROR && (consumed > 0 || produced > 0))) continue;
        if (status == Z_BUF_ERROR)
            os::failMeshFile(
                path,
                "the gzip data ends early (the file is truncated after " + std::to_string(input.size()) + " bytes)");
        os::failMeshFile(path, std::string("is not valid gzip data: ") + (stream.msg ? stream.msg : "inflate failed"));
    }
    if (output.empty()) os::failMeshFile(path, "is empty after decompression");
    return output;
}

namespace {

// The compressed file itself is bounded by what it may expand to.
std::vector<char> readCompressed(const std::string& path, std::uint64_t max_output) {
    return os::readFileBytes(path,
                             std::size_t(std::min<std::uint64_t>(max_output, std::numeric_limits<std::size_t>::max())));
}

}  // namespace

std::vector<char> readGzipFile(const std::string& path, std::uint64_t max_output, Interrupter* interrupter) {
    return gunzip(readCompressed(path, max_output), path, max_output, interrupter);
}

std::vector<char> readGzipMeshFile(const std::string& path, std::uint64_t budget_bytes, Interrupter* interrupter) {
    const std::vector<char> input = readCompressed(path, budget_bytes);
    throwIfInterrupted(interrupter);
    return gunzip(input, path, gzipOutputLimit(input.size(), budget_bytes), interrupter);
}

}  // namespace hyvox::mesh_io
