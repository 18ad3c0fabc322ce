// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh_io/off_reader.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "mesh_io/text_scanner.h"
#include "os/mesh_file_error.h"

namespace hyvox::mesh_io {
namespace {

constexpr std::uint64_t kInterruptEvery = 1 << 16;

class OffParser {
public:
    OffParser(const char* data, std::size_t size, const std::string& name, Interrupter* interrupter)
        : data_(data), size_(size), scanner_(data, data + size), name_(name), interrupter_(interrupter) {}

    Mesh parse() {
        readHeader();
        readVertices();
        readFaces();
        std::string_view word;
        if (nextLineWord(word))
            fail("more after the " + std::to_string(faces_) + " faces the header declares: " + quoteWord(word) +
                 " (a wrong count, or pieces of another file)");
        if (endsInsideAWord(data_, data_ + size_)) fail(kCutInsideTheLastLine);
        if (mesh_.triangles.empty()) os::failMeshFile(name_, "contains no triangles (no face with 3 or more corners)");
        return std::move(mesh_);
    }

private:
    [[noreturn]] void fail(const std::string& what) const {
        os::failMeshFile(name_, "line " + std::to_string(scanner_.line()) + ": " + what);
    }

    // The first word of the next line that holds one (comments and blank lines skipped);
    // false at the end of the text.
    bool nextLineWord(std::string_view& word) {
        for (;;) {
            if (started_ && !scanner_.nextLine()) return false;
            started_ = true;
            if (scanner_.wordOnLine(word) && word[0] != '#') return true;
        }
    }

    // The next word on this line, comments ending it.
    bool wordOnLine(std::string_view& word) {
        if (!scanner_.wordOnLine(word)) return false;
        if (word[0] != '#') return true;
        while (scanner_.wordOnLine(word)) {}
        return false;
    }

    template <typename T>
    T number(std::string_view word, const char* what) const {
        T value{};
        if (!parseNumber(word, value)) fail(quoteWord(word) + " is not " + what);
        return value;
    }

    void readHeader() {
        std::string_view word;
        if (!nextLineWord(word)) os::failMeshFile(name_, "is empty");
        // The keyword: [ST][C][N][4][n]OFF. Only what a triangle mesh in 3D can hold is read.
        if (word.size() >= 3 && word.substr(word.size() - 3) == "OFF") {
            std::string_view prefix = word.substr(0, word.size() - 3);
            if (prefix.substr(0, 2) == "ST") {
                uvs_ = true;
                prefix.remove_prefix(2);
            }
            if (!prefix.empty() && prefix[0] == 'C') {
                colors_ = true;
                prefix.remove_prefix(1);
            }
            if (!prefix.empty() && prefix[0] == 'N') {
                normals_ = true;
                prefix.remove_prefix(1);
            }
            if (!prefix.empty())
                fail("the keyword " + quoteWord(word) +
                     " is an OFF of another dimension (4OFF, nOFF), which hyvox does not read");
            if (wordOnLine(word)) {
                if (word == "BINARY") fail("binary OFF is not read; write the file as ASCII OFF");
                fail("unexpected " + quoteWord(word) + " after the keyword");
            }
            if (!nextLineWord(word)) fail("the file ends before the vertex and face counts");
        }
        vertices_ = number<std::uint64_t>(word, "a vertex count");
        std::string_view faces, edges, extra;
        if (!wordOnLine(faces)) fail("the counts line needs the number of faces after the vertices");
        faces_ = number<std::uint64_t>(faces, "a face count");
        std::string_view last = faces;
        if (wordOnLine(edges)) {
            number<std::uint64_t>(edges, "an edge count");
            last = edges;
        }
        if (wordOnLine(extra)) fail("unexpected " + quoteWord(extra) + " after the counts");
        // A vertex line is at least "0 0 0\n", a face line "3 0 0 0\n": a count the bytes
        // left cannot hold is refused before anything is reserved for it.
        const std::uint64_t left = std::uint64_t(data_ + size_ - (last.data() + last.size()));
        const double need = 6.0 * double(vertices_) + 8.0 * double(faces_);
        if (need > double(left) + 1.0)
            fail("the counts declare " + std::to_string(vertices_) + " vertices and " + std::to_string(faces_) +
                 " faces, more than the " + std::to_string(left) +
                 " bytes after them can hold (the file is truncated or a count is wrong)");
        if (vertices_ > 0xFFFFFFFFull) fail("more vertices than 32-bit indices can number");
    }

    void readVertices() {
        mesh_.positions.reserve(3 * vertices_);
        if (colors_) mesh_.colors.reserve(4 * vertices_);
        if (uvs_) mesh_.uvs.reserve(2 * vertices_);
        std::string_view word;
        for (std::uint64_t v = 0; v < vertices_; ++v) {
            if (v % kInterruptEvery == 0) throwIfInterrupted(interrupter_);
            if (!nextLineWord(word))
                fail("the file ends after " + std::to_string(v) + " of its " + std::to_string(vertices_) + " vertices");
            float values[12];
            int n = 0;
            do {
                if (n == 12) fail("a vertex line with more values than any OFF vertex has");
                values[n++] = number<float>(word, "a number");
            } while (wordOnLine(word));
            const int want = 3 + (normals_ ? 3 : 0);
            // Colours: 3 or 4 channels, integers 0..255 or numbers 0..1 (as Geomview reads them).
            const int channels = colors_ ? n - want - (uvs_ ? 2 : 0) : 0;
            if (n != want + (colors_ ? channels : 0) + (uvs_ ? 2 : 0) || (colors_ && channels != 3 && channels != 4))
                fail("vertex " + std::to_string(v) + " has " + std::to_string(n) +
                     " values; this OFF's vertices have " + std::to_string(want) +
                     (colors_ ? " and 3 or 4 colour channels" : "") + (uvs_ ? " and 2 texture coordinates" : ""));
            mesh_.positions.insert(mesh_.positions.end(), values, values + 3);
            if (colors_) {
                const float* c = values + want;
                const bool bytes = std::any_of(c, c + channels, [](float x) { return x > 1.0f; });
                float rgba[4] = {c[0], c[1], c[2], channels == 4 ? c[3] : 1.0f};
                for (float& x : rgba) x = bytes ? x / 255.0f : x;
                mesh_.colors.insert(mesh_.colors.end(), rgba, rgba + 4);
                mesh_.colors_alpha |= channels == 4;
            }
            if (uvs_) mesh_.uvs.insert(mesh_.uvs.end(), values + n - 2, values + n);
        }
    }

    void readFaces() {
        mesh_.triangles.reserve(3 * faces_);
        std::string_view word;
        std::vector<std::uint32_t> corners;
        for (std::uint64_t f = 0; f < faces_; ++f) {
            if (f % kInterruptEvery == 0) throwIfInterrupted(interrupter_);
            if (!nextLineWord(word))
                fail("the file ends after " + std::to_string(f) + " of its " + std::to_string(faces_) + " faces");
            const std::uint64_t n = number<std::uint64_t>(word, "a face's corner count");
            if (n < 3)
                fail("face " + std::to_string(f) + " has " + std::to_string(n) + " corners; a face needs at least 3");
            corners.clear();
            for (std::uint64_t c = 0; c < n; ++c) {
                if (!wordOnLine(word))
                    fail("face " + std::to_string(f) + " declares " + std::to_string(n) + " corners but lists " +
                         std::to_string(c));
                const std::uint64_t index = number<std::uint64_t>(word, "a vertex index");
                if (index >= vertices_)
                    fail("face " + std::to_string(f) + ": vertex index " + std::to_string(index) +
                         " names none of the " + std::to_string(vertices_) + " vertices");
                corners.push_back(std::uint32_t(index));
            }
            // A face colour (a colour-map index, or 3 or 4 channels) may follow; nothing more.
            int colour = 0;
            while (wordOnLine(word)) {
                number<float>(word, "a number");
                ++colour;
            }
            if (colour == 2 || colour > 4)
                fail("face " + std::to_string(f) + " has " + std::to_string(colour) +
                     " values after its corners; a face colour has 1, 3 or 4 (a corner count that is wrong?)");
            for (std::size_t c = 2; c < corners.size(); ++c)
                mesh_.triangles.insert(mesh_.triangles.end(), {corners[0], corners[c - 1], corners[c]});
        }
    }

    const char* data_;
    std::size_t size_;
    TextScanner scanner_;
    const std::string& name_;
    Interrupter* interrupter_;
    bool started_ = false;
    bool colors_ = false, normals_ = false, uvs_ = false;
    std::uint64_t vertices_ = 0, faces_ = 0;
    Mesh mesh_;
};

}  // namespace

Mesh readOff(const char* data, std::size_t size, const std::string& name, Interrupter* interrupter) {
    return OffParser(data, size, name, interrupter).parse();
}

}  // namespace hyvox::mesh_io
