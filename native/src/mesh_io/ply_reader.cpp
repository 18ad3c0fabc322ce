// SPDX-License-Identifier: GPL-3.0-or-later
// The PLY reader: the header is parsed first into elements and properties; the body is then
// walked record by record through a "source" (binary or ascii) that throws on short or bad
// data, and the element loop adds where that happened. Before an element is read, its
// declared count is compared with the bytes left, so a 200-byte file declaring 2^64
// vertices is refused before any allocation.
#include "mesh_io/ply_reader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "hyvox/zero_page_allocator.h"
#include "mesh_io/text_scanner.h"
#include "os/mesh_file_error.h"

namespace hyvox::mesh_io {
namespace {

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };
enum class Type { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };

std::size_t sizeOf(Type type) {
    switch (type) {
        case Type::Int8:
        case Type::Uint8: return 1;
        case Type::Int16:
        case Type::Uint16: return 2;
        case Type::Int32:
        case Type::Uint32:
        case Type::Float32: return 4;
        case Type::Float64: return 8;
    }
    return 1;
}

bool isInteger(Type type) { return type != Type::Float32 && type != Type::Float64; }

// Both spellings the PLY world uses ("uchar" and "uint8", ...).
bool parseType(std::string_view word, Type& type) {
    static const struct {
        const char* name;
        Type type;
    } kTypes[] = {
        {"char", Type::Int8},     {"int8", Type::Int8},       {"uchar", Type::Uint8},    {"uint8", Type::Uint8},
        {"short", Type::Int16},   {"int16", Type::Int16},     {"ushort", Type::Uint16},  {"uint16", Type::Uint16},
        {"int", Type::Int32},     {"int32", Type::Int32},     {"uint", Type::Uint32},    {"uint32", Type::Uint32},
        {"float", Type::Float32}, {"float32", Type::Float32}, {"double", Type::Float64}, {"float64", Type::Float64}};
    for (const auto& t : kTypes)
        if (word == t.name) {
            type = t.type;
            return true;
        }
    return false;
}

// The largest value of an integer type: integer colour channels are scaled by it to 0..1.
double integerMax(Type type) {
    switch (type) {
        case Type::Int8: return 127;
        case Type::Uint8: return 255;
        case Type::Int16: return 32767;
        case Type::Uint16: return 65535;
        case Type::Int32: return 2147483647.0;
        case Type::Uint32: return 4294967295.0;
        default: return 1;
    }
}

struct Property {
    std::string name;
    bool list = false;
    Type count_type = Type::Uint8;  // lists only
    Type type = Type::Float32;      // the scalar's type, or the list entries' type
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
};

struct Header {
    Format format = Format::Ascii;
    std::vector<Element> elements;
    std::size_t body_offset = 0;  // the byte after the end_header line
    std::size_t body_line = 0;    // the body's first line number (ascii)
};

// Thrown by the sources below; the element loop turns it into an InvalidInput that says
// which record of which element was being read.
struct RecordError {
    std::string what;
};

Header readHeader(const char* data, std::size_t size, const std::string& name) {
    Header header;
    std::size_t pos = 0, line_number = 0;
    bool line_cut = false;  // the last line read ended with the file, not with a newline
    auto nextLine = [&](std::string_view& line) {
        if (pos >= size) return false;
        const void* newline = std::memchr(data + pos, '\n', size - pos);
        line_cut = !newline;
        const std::size_t end = newline ? std::size_t(static_cast<const char*>(newline) - data) : size;
        line = std::string_view(data + pos, end - pos);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        pos = newline ? end + 1 : size;
        ++line_number;
        return true;
    };
    auto fail = [&](const std::string& what) {
        os::failMeshFile(name, what + " (header line " + std::to_string(line_number) + ")");
    };

    std::string_view line;
    if (!nextLine(line) || line != "ply") os::failMeshFile(name, "not a PLY file (the first line is not 'ply')");
    bool have_format = false;
    for (;;) {
        // A header line the file cuts short is reported as that, not as whatever it now reads as.
        if (!nextLine(line) || (line_cut && line != "end_header"))
            os::failMeshFile(name, "the PLY header has no 'end_header' line (the file ends inside the header)");
        TextScanner words(line.data(), line.data() + line.size());
        std::string_view keyword;
        if (!words.wordOnLine(keyword)) continue;  // blank lines are harmless
        if (keyword == "end_header") break;
        if (keyword == "comment" || keyword == "obj_info") continue;
        std::string_view a, b, c, extra;
        if (keyword == "format") {
            if (!words.wordOnLine(a) || !words.wordOnLine(b) || words.wordOnLine(extra))
                fail("'format' needs a format and a version");
            if (a == "ascii")
                header.format = Format::Ascii;
            else if (a == "binary_little_endian")
                header.format = Format::BinaryLittleEndian;
            else if (a == "binary_big_endian")
                header.format = Format::BinaryBigEndian;
            else
                fail("unknown PLY format " + quoteWord(a));
            if (b != "1.0") fail("unsupported PLY version " + quoteWord(b) + " (1.0 is read)");
            have_format = true;
        } else if (keyword == "element") {
            Element element;
            if (!words.wordOnLine(a) || !words.wordOnLine(b) || words.wordOnLine(extra))
                fail("'element' needs a name and a count");
            if (!parseNumber(b, element.count))
                fail("element " + quoteWord(a) + " has count " + quoteWord(b) +
                     ", not a whole number from 0 to 2^64-1");
            element.name = std::string(a);
            header.elements.push_back(std::move(element));
        } else if (keyword == "property") {
            if (header.elements.empty()) fail("a property before any element");
            Property property;
            if (!words.wordOnLine(a)) fail("'property' needs a type and a name");
            if (a == "list") {
                property.list = true;
                if (!words.wordOnLine(b) || !words.wordOnLine(c) || !words.wordOnLine(a) || words.wordOnLine(extra))
                    fail("'property list' needs a count type, an entry type and a name");
                if (!parseType(b, property.count_type) || !isInteger(property.count_type))
                    fail("list count type " + quoteWord(b) + " is not an integer type");
                if (!parseType(c, property.type)) fail("unknown property type " + quoteWord(c));
            } else {
                if (!parseType(a, property.type)) fail("unknown property type " + quoteWord(a));
                if (!words.wordOnLine(a) || words.wordOnLine(extra)) fail("'property' needs a type and a name");
            }
            property.name = std::string(a);
            header.elements.back().properties.push_back(std::move(property));
        } else {
            fail("unknown header keyword " + quoteWord(keyword));
        }
    }
    if (!have_format) os::failMeshFile(name, "the PLY header has no 'format' line");
    header.body_offset = pos;
    header.body_line = line_number + 1;
    return header;
}

// Binary records: fixed-size values read with memcpy (the body has no alignment), swapped
// for the other byte order.
class BinarySource {
public:
    BinarySource(const char* begin, const char* end, bool swap) : pos_(begin), end_(end), swap_(swap) {}

    std::size_t remaining() const { return std::size_t(end_ - pos_); }
    const char* end() const { return end_; }
    double scalar(Type type) {
        const std::size_t n = sizeOf(type);
        if (remaining() < n) throw RecordError{"the file ends"};
        unsigned char bytes[8];
        std::memcpy(bytes, pos_, n);
        pos_ += n;
        if (swap_)
            for (std::size_t i = 0; i < n / 2; ++i) std::swap(bytes[i], bytes[n - 1 - i]);
        switch (type) {
            case Type::Int8: return double(static_cast<std::int8_t>(bytes[0]));
            case Type::Uint8: return double(bytes[0]);
            case Type::Int16: return load<std::int16_t>(bytes);
            case Type::Uint16: return load<std::uint16_t>(bytes);
            case Type::Int32: return load<std::int32_t>(bytes);
            case Type::Uint32: return load<std::uint32_t>(bytes);
            case Type::Float32: return load<float>(bytes);
            case Type::Float64: return load<double>(bytes);
        }
        return 0;
    }

    // Skips n values of a list, after checking they are there (n may be 4 billion).
    void skip(Type type, std::uint64_t n) {
        if (n > remaining() / sizeOf(type)) throw RecordError{"the file ends"};
        pos_ += n * sizeOf(type);
    }

    std::string where() const { return ""; }

    // Fast paths for the records almost every binary PLY holds, in the host's byte order.
    // Each reads records while they are exactly of that form and valid, and stops before the
    // first that is not: the general per-value path then reads that one (and reports any
    // error in it), so both paths accept and refuse the same files.

    // Vertices of `stride` bytes whose x, y, z are float32 at byte offsets xyz[0..2] and, when
    // `rgba` is non-null, whose colour channels are uint8 at rgba[0..3] (rgba[3] < 0: no alpha,
    // 1). Channels are converted as the per-value path converts them: byte / 255 in double.
    std::uint64_t vertexRecords(std::uint64_t count, std::size_t stride, const std::size_t xyz[3], const int* rgba,
                                std::vector<float>& positions, std::vector<float>& colors) {
        if (swap_) return 0;
        const std::uint64_t n = std::min<std::uint64_t>(count, remaining() / stride);
        const std::size_t first = positions.size(), first_color = colors.size();
        positions.resize(first + 3 * n);
        if (rgba) colors.resize(first_color + 4 * n);
        float* to = positions.data() + first;
        float* color = rgba ? colors.data() + first_color : nullptr;
        for (std::uint64_t i = 0; i < n; ++i, pos_ += stride, to += 3) {
            for (int a = 0; a < 3; ++a) std::memcpy(to + a, pos_ + xyz[a], sizeof(float));
            if (!rgba) continue;
            for (int c = 0; c < 4; ++c, ++color)
                *color = rgba[c] < 0 ? 1.0f : float(double(static_cast<unsigned char>(pos_[rgba[c]])) / 255.0);
        }
        return n;
    }

    // Faces of one list: a uint8 count of 3, then three 32-bit indices below vertex_count
    // (signed ones are negative when they are at least 2^31 as unsigned, so one unsigned
    // compare refuses both while vertex_count < 2^31).
    std::uint64_t triangles(std::uint64_t count, std::uint32_t vertex_count, std::vector<std::uint32_t>& out) {
        constexpr std::size_t kRecord = 1 + 3 * sizeof(std::uint32_t);
        if (swap_ || vertex_count >= (1u << 31)) return 0;
        const std::uint64_t n = std::min<std::uint64_t>(count, remaining() / kRecord);
        const std::size_t first = out.size();
        out.resize(first + 3 * n);
        std::uint32_t* to = out.data() + first;
        std::uint64_t f = 0;
        for (; f < n; ++f, pos_ += kRecord, to += 3) {
            std::uint32_t i[3];
            std::memcpy(i, pos_ + 1, sizeof i);
            if (static_cast<unsigned char>(pos_[0]) != 3 || i[0] >= vertex_count || i[1] >= vertex_count ||
                i[2] >= vertex_count)
                break;
            std::memcpy(to, i, sizeof i);
        }
        out.resize(first + 3 * f);
        return f;
    }

private:
    template <typename T>
    static double load(const unsigned char* bytes) {
        T value;
        std::memcpy(&value, bytes, sizeof value);
        return double(value);
    }

    const char* pos_;
    const char* end_;
    bool swap_;
};

// Ascii records: whitespace-separated words, each parsed strictly as the property's type.
class AsciiSource {
public:
    AsciiSource(const char* begin, const char* end, std::size_t first_line)
        : scanner_(begin, end, first_line), begin_(begin), end_(end) {}

    std::size_t remaining() const { return std::size_t(end_ - begin_) - consumed_; }
    const char* end() const { return end_; }

    double scalar(Type type) {
        std::string_view word;
        if (!scanner_.word(word)) throw RecordError{"the file ends"};
        consumed_ = std::size_t(word.data() + word.size() - begin_);
        if (isInteger(type)) {
            std::int64_t value = 0;
            if (!parseNumber(word, value) || value < minOf(type) || value > double(integerMax(type)))
                throw RecordError{quoteWord(word) + " is not a value of type " + typeName(type)};
            return double(value);
        }
        double value = 0;
        if (!parseNumber(word, value)) throw RecordError{quoteWord(word) + " is not a number"};
        return value;
    }

    void skip(Type type, std::uint64_t n) {
        for (std::uint64_t i = 0; i < n; ++i) scalar(type);
    }

    std::string where() const { return ", line " + std::to_string(scanner_.line()); }

private:
    static double minOf(Type type) {
        switch (type) {
            case Type::Int8: return -128;
            case Type::Int16: return -32768;
            case Type::Int32: return -2147483648.0;
            default: return 0;
        }
    }
    static std::string typeName(Type type) {
        switch (type) {
            case Type::Int8: return "char (-128..127)";
            case Type::Uint8: return "uchar (0..255)";
            case Type::Int16: return "short";
            case Type::Uint16: return "ushort";
            case Type::Int32: return "int";
            case Type::Uint32: return "uint";
            default: return "float";
        }
    }

    TextScanner scanner_;
    const char* begin_;
    const char* end_;
    std::size_t consumed_ = 0;
};

// An index as the file wrote it: 12, -1, 3.5 (never 300 digits).
std::string formatIndex(double i) {
    if (i == std::floor(i) && std::fabs(i) < 1e15) return std::to_string(std::int64_t(i));
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", i);
    return text;
}

int findProperty(const Element& element, std::initializer_list<const char*> names) {
    for (const char* n : names)
        for (std::size_t p = 0; p < element.properties.size(); ++p)
            if (element.properties[p].name == n && !element.properties[p].list) return int(p);
    return -1;
}

class BodyReader {
public:
    BodyReader(const Header& header, const std::string& name, Mesh& mesh, Interrupter* interrupter)
        : header_(header), name_(name), mesh_(mesh), interrupter_(interrupter) {}

    template <class Source>
    void read(Source& source) {
        const Element* vertices = nullptr;
        for (const Element& e : header_.elements)
            if (e.name == "vertex" && !vertices) vertices = &e;
        if (!vertices) os::failMeshFile(name_, "the PLY header declares no 'vertex' element");
        if (vertices->count > std::numeric_limits<std::uint32_t>::max())
            os::failMeshFile(
                name_,
                "declares " + std::to_string(vertices->count) + " vertices; at most 4294967295 fit 32-bit indices");
        vertex_count_ = vertices->count;
        bool faces_read = false;
        for (const Element& e : header_.elements) {
            checkRoom(e, source);
            if (&e == vertices) {
                readVertices(e, source);
            } else if (e.name == "face" && !faces_read) {
                readFaces(e, faceListIndex(e), source);
                faces_read = true;
            } else {
                skipElement(e, source);
            }
        }
        // Records the header does not count (a count lowered by damage, pieces of another file)
        // would be dropped without a word: only whitespace may follow the last element.
        const char* rest = source.end() - source.remaining();
        const char* other =
            std::find_if(rest, source.end(), [](char c) { return !std::isspace(static_cast<unsigned char>(c)); });
        if (other != source.end())
            os::failMeshFile(name_,
                             std::to_string(source.end() - rest) +
                                 " bytes follow the last element the header declares (" + header_.elements.back().name +
                                 "): a count is wrong, or the file holds pieces of another");
        if (std::is_same_v<Source, AsciiSource> && endsInsideAWord(source.end() - 1, source.end()))
            os::failMeshFile(name_, kCutInsideTheLastLine);
    }

private:
    // The bytes one record needs at least (1 per binary list count: a face with too few indices
    // is then reported as such); a declared count that cannot fit is refused here,
    // before the reader reserves memory for it or loops over it.
    template <class Source>
    void checkRoom(const Element& e, const Source& source) const {
        if (e.count == 0 || e.properties.empty()) return;
        std::uint64_t min_bytes = 0;
        for (std::size_t p = 0; p < e.properties.size(); ++p) {
            const Property& property = e.properties[p];
            // An ascii word needs a character and a separator; a list at least its count.
            if (std::is_same_v<Source, AsciiSource>)
                min_bytes += 2;
            else
                min_bytes += property.list ? sizeOf(property.count_type) : sizeOf(property.type);
        }
        const std::uint64_t room = (std::uint64_t(source.remaining()) + 1) / min_bytes;  // +1: no final newline
        if (e.count > room)
            os::failMeshFile(name_,
                             "the header declares " + std::to_string(e.count) + " '" + e.name + "' elements but the " +
                                 std::to_string(source.remaining()) + " bytes after it hold at most " +
                                 std::to_string(room) + " (the file is truncated or the count is wrong)");
    }

    int faceListIndex(const Element& e) const {
        for (const char* n : {"vertex_indices", "vertex_index"})
            for (std::size_t p = 0; p < e.properties.size(); ++p)
                if (e.properties[p].name == n) {
                    if (!e.properties[p].list)
                        os::failMeshFile(name_, "the face property '" + std::string(n) + "' is not a list");
                    return int(p);
                }
        os::failMeshFile(name_, "the 'face' element has no 'vertex_indices' list");
    }

    [[noreturn]] void failRecord(const Element& e, std::uint64_t index, const std::string& what,
                                 const std::string& where) const {
        os::failMeshFile(name_,
                         e.name + " " + std::to_string(index) + " of " + std::to_string(e.count) + where + ": " + what);
    }

    template <class Source>
    std::uint64_t listCount(const Property& property, Source& source) {
        const double n = source.scalar(property.count_type);
        if (n < 0) throw RecordError{"list '" + property.name + "' has a negative length"};
        return std::uint64_t(n);
    }

    template <class Source>
    void readVertices(const Element& e, Source& source) {
        const int x = findProperty(e, {"x"}), y = findProperty(e, {"y"}), z = findProperty(e, {"z"});
        for (const auto& [slot, axis] : {std::pair{x, "x"}, {y, "y"}, {z, "z"}})
            if (slot < 0) os::failMeshFile(name_, "the vertex element has no '" + std::string(axis) + "' property");
        const int r = findProperty(e, {"red", "r", "diffuse_red"}),
                  g = findProperty(e, {"green", "g", "diffuse_green"}),
                  b = findProperty(e, {"blue", "b", "diffuse_blue"}), a = findProperty(e, {"alpha", "a"});
        int u = -1, v = -1;
        for (const auto& [un, vn] :
             {std::pair{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}}) {
            u = findProperty(e, {un});
            v = findProperty(e, {vn});
            if (u >= 0 && v >= 0) break;
        }
        const bool colors = r >= 0 && g >= 0 && b >= 0, uvs = u >= 0 && v >= 0;
        mesh_.positions.reserve(3 * e.count);
        adviseHugePages(mesh_.positions.data(), mesh_.positions.capacity() * sizeof(float));
        if (colors) mesh_.colors.reserve(4 * e.count);
        mesh_.colors_alpha = colors && a >= 0;
        if (uvs) mesh_.uvs.reserve(2 * e.count);
        std::vector<double> values(e.properties.size(), 0.0);
        auto channel = [&](int p) { return float(values[p] / integerMax(e.properties[p].type)); };
        std::uint64_t i = 0;
        if constexpr (std::is_same_v<Source, BinarySource>) {
            // Records of float32 and uint8 scalars (positions, and 8-bit colours if any):
            // copied straight from the bytes.
            bool plain = !uvs &&
                (!colors ||
                 (e.properties[std::size_t(r)].type == Type::Uint8 &&
                  e.properties[std::size_t(g)].type == Type::Uint8 &&
                  e.properties[std::size_t(b)].type == Type::Uint8 &&
                  (a < 0 || e.properties[std::size_t(a)].type == Type::Uint8)));
            for (int axis : {x, y, z}) plain &= e.properties[std::size_t(axis)].type == Type::Float32;
            std::vector<std::size_t> offset(e.properties.size());
            std::size_t stride = 0;
            for (std::size_t p = 0; p < e.properties.size(); ++p) {
                const Property& property = e.properties[p];
                plain &= !property.list && (property.type == Type::Float32 || property.type == Type::Uint8);
                offset[p] = stride;
                stride += sizeOf(property.type);
            }
            if (plain) {
                const std::size_t xyz[3] = {offset[std::size_t(x)], offset[std::size_t(y)], offset[std::size_t(z)]};
                const int rgba[4] = {
                    colors ? int(offset[std::size_t(r)]) : -1, colors ? int(offset[std::size_t(g)]) : -1,
                    colors ? int(offset[std::size_t(b)]) : -1, a >= 0 ? int(offset[std::size_t(a)]) : -1};
                i = inChunks(e.count, [&](std::uint64_t chunk) {
                    return source.vertexRecords(chunk, stride, xyz, colors ? rgba : nullptr, mesh_.positions,
                                                mesh_.colors);
                });
            }
        }
        for (; i < e.count; ++i) {
            poll(i);
            try {
                for (std::size_t p = 0; p < e.properties.size(); ++p) {
                    const Property& property = e.properties[p];
                    if (property.list)
                        source.skip(property.type, listCount(property, source));
                    else
                        values[p] = source.scalar(property.type);
                }
            } catch (const RecordError& error) {
                failRecord(e, i, error.what, source.where());
            }
            mesh_.positions.insert(mesh_.positions.end(), {float(values[x]), float(values[y]), float(values[z])});
            if (colors)
                mesh_.colors.insert(mesh_.colors.end(),
                                    {channel(r), channel(g), channel(b), a >= 0 ? channel(a) : 1.0f});
            if (uvs) mesh_.uvs.insert(mesh_.uvs.end(), {float(values[u]), float(values[v])});
        }
    }

    template <class Source>
    void readFaces(const Element& e, int face_list, Source& source) {
        // Reserved for triangles only as many faces as the bytes left can hold with 3
        // indices each: a count the body cannot hold is not trusted with memory.
        const Property& list = e.properties[std::size_t(face_list)];
        const std::uint64_t min_face_bytes =
            std::is_same_v<Source, AsciiSource> ? 8 : sizeOf(list.count_type) + 3 * sizeOf(list.type);
        mesh_.triangles.reserve(3 * std::min<std::uint64_t>(e.count, source.remaining() / min_face_bytes));
        adviseHugePages(mesh_.triangles.data(), mesh_.triangles.capacity() * sizeof(std::uint32_t));
        std::uint64_t f = 0;
        if constexpr (std::is_same_v<Source, BinarySource>) {
            if (e.properties.size() == 1 && list.count_type == Type::Uint8 &&
                (list.type == Type::Int32 || list.type == Type::Uint32)) {
                const auto vertex_limit = std::uint32_t(std::min<std::uint64_t>(vertex_count_, 1u << 31));
                f = inChunks(e.count, [&](std::uint64_t chunk) {
                    return source.triangles(chunk, vertex_limit, mesh_.triangles);
                });
            }
        }
        for (; f < e.count; ++f) {
            poll(f);
            try {
                for (std::size_t p = 0; p < e.properties.size(); ++p) {
                    const Property& property = e.properties[p];
                    if (int(p) == face_list) {
                        readPolygon(property, source);
                    } else if (property.list) {
                        source.skip(property.type, listCount(property, source));
                    } else {
                        source.scalar(property.type);
                    }
                }
            } catch (const RecordError& error) {
                failRecord(e, f, error.what, source.where());
            }
        }
    }

    // One polygon, fan-triangulated (0,1,2), (0,2,3), ... as it is read: linear in its size.
    template <class Source>
    void readPolygon(const Property& property, Source& source) {
        const std::uint64_t n = listCount(property, source);
        if (n < 3) throw RecordError{"it has " + std::to_string(n) + " vertex indices; a face needs at least 3"};
        const std::uint32_t first = index(property, source);
        std::uint32_t previous = index(property, source);
        for (std::uint64_t k = 2; k < n; ++k) {
            const std::uint32_t current = index(property, source);
            mesh_.triangles.insert(mesh_.triangles.end(), {first, previous, current});
            previous = current;
        }
    }

    template <class Source>
    std::uint32_t index(const Property& property, Source& source) {
        const double i = source.scalar(property.type);
        if (!(i >= 0 && i < double(vertex_count_)) || i != std::floor(i))
            throw RecordError{"vertex index " + formatIndex(i) + " is not one of the " + std::to_string(vertex_count_) +
                              " vertices"};
        return std::uint32_t(i);
    }

    template <class Source>
    void skipElement(const Element& e, Source& source) {
        if (e.properties.empty()) return;  // nothing to read, however large the count
        for (std::uint64_t i = 0; i < e.count; ++i) {
            poll(i);
            try {
                for (const Property& property : e.properties) {
                    if (property.list)
                        source.skip(property.type, listCount(property, source));
                    else
                        source.scalar(property.type);
                }
            } catch (const RecordError& error) {
                failRecord(e, i, error.what, source.where());
            }
        }
    }

    // Cancellation between chunks of 64k records (hyvox::Cancelled; the caller's mesh is freed).
    // The reader asks the interrupter once every kPollRecords records.
    static constexpr std::uint64_t kPollRecords = 0x10000;
    void poll(std::uint64_t record) const {
        if (record % kPollRecords == 0) throwIfInterrupted(interrupter_);
    }

    // Runs a fast path (readChunk(n): reads up to n records, returns how many) over `count`
    // records in chunks of kPollRecords, so that a stop is seen at the same records as on the
    // per-value path. Returns the records read: fewer than `count` where the fast path left
    // the rest to the per-value path.
    template <typename ReadChunk>
    std::uint64_t inChunks(std::uint64_t count, ReadChunk readChunk) const {
        std::uint64_t done = 0;
        while (done < count) {
            poll(done);
            const std::uint64_t chunk = std::min<std::uint64_t>(count - done, kPollRecords);
            const std::uint64_t read = readChunk(chunk);
            done += read;
            if (read < chunk) break;
        }
        return done;
    }

    const Header& header_;
    const std::string& name_;
    Mesh& mesh_;
    Interrupter* interrupter_;
    std::uint64_t vertex_count_ = 0;
};

}  // namespace

bool looksLikePly(const char* data, std::size_t size) {
    return size >= 4 && std::memcmp(data, "ply", 3) == 0 && (data[3] == '\n' || data[3] == '\r');
}

Mesh readPly(const char* data, std::size_t size, const std::string& name, Interrupter* interrupter) {
    const Header header = readHeader(data, size, name);
    Mesh mesh;
    BodyReader reader(header, name, mesh, interrupter);
    const char* body = data + header.body_offset;
    const char* end = data + size;
    if (header.format == Format::Ascii) {
        AsciiSource source(body, end, header.body_line);
        reader.read(source);
    } else {
        // The host's byte order decides whether the file's values need a swap.
        const std::uint16_t probe = 1;
        unsigned char first_byte;
        std::memcpy(&first_byte, &probe, 1);
        const bool host_little = first_byte == 1;
        BinarySource source(body, end, host_little != (header.format == Format::BinaryLittleEndian));
        reader.read(source);
    }
    if (mesh.triangles.empty()) os::failMeshFile(name, "contains no triangles");
    return mesh;
}

}  // namespace hyvox::mesh_io
