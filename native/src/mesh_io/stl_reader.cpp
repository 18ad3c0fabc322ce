// SPDX-License-Identifier: GPL-3.0-or-later
// Binary STL is told from ASCII by its content: many binary files start their free-form header
// with "solid" too, so the ASCII form is taken only when the first bytes after "solid" are all
// text (a binary header is followed by the count and float data, which are not).
#include "mesh_io/stl_reader.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "mesh_io/text_scanner.h"
#include "mesh_io/weld_vertices.h"
#include "os/mesh_file_error.h"

namespace hyvox::mesh_io {
namespace {

constexpr std::size_t kHeaderBytes = 84;  // 80 free bytes and the uint32 triangle count
constexpr std::size_t kRecordBytes = 50;  // normal, 3 corners (12 floats) and a uint16
constexpr std::uint64_t kInterruptEvery = 1 << 16;

bool isText(unsigned char c) { return c == '\n' || c == '\r' || c == '\t' || (c >= 0x20 && c < 0x7f); }

bool looksLikeAsciiStl(const char* data, std::size_t size) {
    std::size_t at = 0;
    while (at < size && (data[at] == ' ' || data[at] == '\t' || data[at] == '\r' || data[at] == '\n')) ++at;
    if (size - at < 5 || std::memcmp(data + at, "solid", 5) != 0) return false;
    const std::size_t probe = std::min<std::size_t>(size, at + 512);
    for (std::size_t i = at; i < probe; ++i)
        if (!isText(static_cast<unsigned char>(data[i]))) return false;
    return true;
}

Mesh readBinary(const char* data, std::size_t size, const std::string& name, Interrupter* interrupter) {
    if (size < kHeaderBytes)
        os::failMeshFile(name, "is " + std::to_string(size) + " bytes, shorter than a binary STL's 84-byte header");
    std::uint32_t count = 0;
    std::memcpy(&count, data + 80, 4);  // little-endian in the file, as on every host hyvox builds for
    const std::uint64_t expected = kHeaderBytes + std::uint64_t(count) * kRecordBytes;
    if (expected != size)
        os::failMeshFile(name,
                         "the binary STL header declares " + std::to_string(count) + " triangles (" +
                             std::to_string(expected) + " bytes) but the file has " + std::to_string(size) +
                             " bytes (truncated, or the count is wrong)");
    if (count == 0) os::failMeshFile(name, "contains no triangles");
    Mesh mesh;
    mesh.positions.resize(std::size_t(9) * count);
    mesh.triangles.resize(std::size_t(3) * count);
    const char* record = data + kHeaderBytes;
    for (std::uint64_t t = 0; t < count; ++t, record += kRecordBytes) {
        if (t % kInterruptEvery == 0) throwIfInterrupted(interrupter);
        std::memcpy(&mesh.positions[9 * t], record + 12, 36);
    }
    for (std::uint32_t c = 0; c < 3 * count; ++c) mesh.triangles[c] = c;
    return mesh;
}

class AsciiParser {
public:
    AsciiParser(const char* data, std::size_t size, const std::string& name, Interrupter* interrupter)
        : scanner_(data, data + size), name_(name), interrupter_(interrupter) {}

    Mesh parse() {
        std::string_view word;
        // solid NAME ... endsolid NAME, once or more.
        while (scanner_.word(word)) {
            if (word != "solid") fail("expected 'solid', found " + quoteWord(word));
            scanner_.nextLine();  // the solid's name, if any
            readFacets();
        }
        if (mesh_.triangles.empty()) os::failMeshFile(name_, "contains no triangles (no 'facet' in any solid)");
        return std::move(mesh_);
    }

private:
    [[noreturn]] void fail(const std::string& what) const {
        os::failMeshFile(name_, "line " + std::to_string(scanner_.line()) + ": " + what);
    }

    void expect(const char* keyword) {
        std::string_view word;
        if (!scanner_.word(word)) fail(std::string("the file ends where '") + keyword + "' was expected");
        if (word != keyword) fail(std::string("expected '") + keyword + "', found " + quoteWord(word));
    }

    float number() {
        std::string_view word;
        float value = 0;
        if (!scanner_.wordOnLine(word)) fail("a number is missing");
        if (!parseNumber(word, value)) fail(quoteWord(word) + " is not a number");
        return value;
    }

    void endOfLine() {
        std::string_view word;
        if (scanner_.wordOnLine(word)) fail("unexpected " + quoteWord(word) + " at the end of the line");
    }

    void readFacets() {
        std::string_view word;
        for (std::uint64_t facet = 0;; ++facet) {
            if (facet % kInterruptEvery == 0) throwIfInterrupted(interrupter_);
            if (!scanner_.word(word)) fail("the file ends inside a solid (no 'endsolid'): it is truncated");
            if (word == "endsolid") {
                scanner_.nextLine();  // its name, if any
                return;
            }
            if (word != "facet") fail("expected 'facet' or 'endsolid', found " + quoteWord(word));
            expect("normal");
            for (int a = 0; a < 3; ++a) number();
            endOfLine();
            expect("outer");
            expect("loop");
            const std::uint32_t first = std::uint32_t(mesh_.vertexCount());
            if (first > 0xFFFFFFFFu - 3) fail("more corners than 32-bit indices can number");
            for (int c = 0; c < 3; ++c) {
                expect("vertex");
                for (int a = 0; a < 3; ++a) mesh_.positions.push_back(number());
                endOfLine();
            }
            expect("endloop");
            expect("endfacet");
            mesh_.triangles.insert(mesh_.triangles.end(), {first, first + 1, first + 2});
        }
    }

    TextScanner scanner_;
    const std::string& name_;
    Interrupter* interrupter_;
    Mesh mesh_;
};

}  // namespace

Mesh readStl(const char* data, std::size_t size, const std::string& name, Interrupter* interrupter) {
    Mesh mesh = looksLikeAsciiStl(data, size) ? AsciiParser(data, size, name, interrupter).parse()
                                              : readBinary(data, size, name, interrupter);
    throwIfInterrupted(interrupter);
    weldIdenticalVertices(mesh);
    return mesh;
}

}  // namespace hyvox::mesh_io
