// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What the assimp reader process (assimp_reader_process.cpp) sends back on its standard
// output, and how the reading side (assimp_reader.cpp) decodes it. Both ends are one build
// on one machine, so values go in the machine's own byte order. The stream is a run of
// messages, each a tag byte and its payload:
//   'P' u8 percent                 assimp's progress (any number of these)
//   'E' u32 n, n bytes             the file could not be read: the reason, a whole message
//   'M' mesh                       the mesh (last)
// mesh: u64 vertices, u64 triangles, u8 flags (1 colours, 2 alpha, 4 uvs), u32 warnings and
// each as u32 n + n bytes; then positions (3 floats a vertex), triangles (3 u32), colours
// (4 floats a vertex) and uvs (2 floats a vertex) when flagged.
//
// The decoder trusts nothing it is sent: the process reading the file may have been led
// astray by it. Every size is checked against a byte limit before anything is allocated and
// every index against the vertex count.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "hyvox/mesh_io.h"

namespace hyvox::mesh_io::wire {

// The reader process's command line:
//   hyvox_assimp_reader PROTOCOL PARENT_PID MEMORY_LIMIT_BYTES EXTENSION PATH NAME
// PATH "-": the file's bytes come on standard input. NAME is the path quoted in errors.
// A reader of another build refuses a protocol not its own.
inline constexpr const char* kProtocol = "hyvox-assimp-reader-1";
// Its exit status when an allocation failed (the memory limit it was given was reached).
inline constexpr int kExitOutOfMemory = 3;
// Its exit status when started without a valid command line.
inline constexpr int kExitUsage = 2;

// Raised by the decoder; the reader turns it into an error naming the file.
struct StreamError {
    std::string what;
};

// The message bytes of a progress step, an error and a mesh.
std::string progressMessage(int percent);
std::string errorMessage(const std::string& what);
std::string meshMessage(const Mesh& mesh);

// Reads the stream as it arrives, in pieces of any size.
class Decoder {
public:
    // `max_mesh_bytes`: the largest mesh accepted (its arrays and warnings together).
    explicit Decoder(std::uint64_t max_mesh_bytes) : max_mesh_bytes_(max_mesh_bytes) {}

    // Takes the next bytes; throws StreamError for a stream no reader process writes.
    void feed(const char* data, std::size_t size);

    // The latest progress sent (-1 before any).
    int percent() const { return percent_; }
    // After the stream ended: the error sent, if one was.
    const std::optional<std::string>& error() const { return error_; }
    // After the stream ended: the mesh, checked (throws StreamError when the stream stopped
    // short of a whole mesh or error, or the mesh is not consistent).
    Mesh finish();

private:
    enum class State { Tag, Percent, ErrorSize, ErrorText, Header, WarningSize, WarningText, Arrays, Done };
    // Copies what `want` still needs from [data, data + size) into `into` (of `want` bytes);
    // true once it is complete. Advances data and size past what was taken.
    bool take(char* into, std::size_t want, const char*& data, std::size_t& size);
    void startArrays();
    void check(bool ok, const char* what) const {
        if (!ok) throw StreamError{what};
    }

    std::uint64_t max_mesh_bytes_;
    State state_ = State::Tag;
    std::size_t have_ = 0;  // bytes of the current field taken so far
    char scratch_[32];      // fixed-size fields
    int percent_ = -1;
    std::optional<std::string> error_;
    std::string text_;  // the error or warning being read
    std::uint32_t warnings_left_ = 0;
    std::uint8_t flags_ = 0;
    std::uint64_t vertices_ = 0, triangles_ = 0;
    std::uint64_t accepted_bytes_ = 0;  // of the mesh, counted against max_mesh_bytes
    // The arrays in the order sent, each as (destination, bytes).
    struct Array {
        char* data;
        std::size_t bytes;
    };
    Array arrays_[4]{};
    int array_count_ = 0, array_ = 0;
    Mesh mesh_;
};

}  // namespace hyvox::mesh_io::wire
