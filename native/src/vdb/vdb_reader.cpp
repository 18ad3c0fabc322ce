// SPDX-License-Identifier: GPL-3.0-or-later
// OpenVDB's file layout read back, field for field as openvdb::io::Archive, RootNode,
// InternalNode, LeafNode and io::readCompressedValues read it (the order vdb_direct_writer.cpp
// writes): the header, the file metadata, then per grid its descriptor and stream offsets,
// compression flags, metadata, transform, topology (root, 32³ and 16³ internal nodes, leaf
// masks) and leaf buffers. Little-endian, as OpenVDB writes on x86 and ARM.
#include "vdb/vdb_reader.h"

#include <blosc.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <memory>

#include "hyvox/errors.h"

namespace hyvox::vdb {
namespace {

constexpr std::int64_t kMagic = 0x56444220;   // OPENVDB_MAGIC
constexpr std::uint32_t kFirstVersion = 222;  // OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION
constexpr std::uint32_t kCompressZip = 0x1, kCompressActiveMask = 0x2, kCompressBlosc = 0x4;

// io::readCompressedValues' metadata byte: how a node's inactive values are stored.
enum InactiveValues : std::int8_t {
    kNoMaskOrInactiveVals = 0,     // all the background
    kNoMaskAndMinusBg = 1,         // all -background
    kNoMaskAndOneInactiveVal = 2,  // all one other value (stored)
    kMaskAndNoInactiveVals = 3,    // background or -background, by a selection mask
    kMaskAndOneInactiveVal = 4,    // background or one other value, by a selection mask
    kMaskAndTwoInactiveVals = 5,   // two other values, by a selection mask
    kNoMaskAndAllVals = 6,         // every value stored
};

// Node geometry of the 5-4-3 trees (vdb_direct_writer.cpp has the same).
constexpr int kLeafLog2 = 3, kLowerLog2 = 4, kUpperLog2 = 5;
constexpr int kLowerTotal = kLeafLog2 + kLowerLog2;  // 7
constexpr std::size_t kLeafValues = 512;

// Bounds every count read from the file before anything is allocated for it.
constexpr std::uint32_t kMaxEntries = 1u << 20;  // metadata entries, grids
constexpr std::uint32_t kMaxText = 1u << 26;     // a string's or a metadata value's bytes

// The file as a checked byte stream: every read that runs past the end, or fails, is an
// InvalidInput naming the file and the byte.
class Input {
public:
    explicit Input(const std::string& path) : path_(path), file_(path, std::ios::binary) {
        if (!file_) throw InvalidInput("cannot open '" + path + "': " + std::strerror(errno));
        file_.seekg(0, std::ios::end);
        size_ = std::uint64_t(file_.tellg());
        file_.seekg(0);
        if (!file_) throw InvalidInput("cannot read '" + path + "'");
    }

    [[noreturn]] void fail(const std::string& what) const {
        throw InvalidInput("'" + path_ + "' is not a .vdb file hyvox can read: " + what + " (at byte " +
                           std::to_string(at_) + " of " + std::to_string(size_) + ")");
    }
    void bytes(void* out, std::uint64_t n) {
        if (n > size_ - at_) fail("it ends early");
        file_.read(static_cast<char*>(out), std::streamsize(n));
        if (!file_) fail("reading failed");
        at_ += n;
    }
    template <typename T>
    T pod() {
        T value;
        bytes(&value, sizeof value);
        return value;
    }
    std::string text() {
        const auto n = pod<std::uint32_t>();
        if (n > kMaxText || n > size_ - at_) fail("a string of " + std::to_string(n) + " bytes");
        std::string out(n, '\0');
        bytes(out.data(), n);
        return out;
    }
    void seek(std::int64_t to) {
        if (to < 0 || std::uint64_t(to) > size_) fail("a stream offset " + std::to_string(to) + " outside the file");
        file_.clear();
        file_.seekg(to);
        at_ = std::uint64_t(to);
    }
    std::uint64_t at() const { return at_; }
    const std::string& path() const { return path_; }

private:
    std::string path_;
    std::ifstream file_;
    std::uint64_t size_ = 0, at_ = 0;
};

std::vector<VdbMetaEntry> readMetaMap(Input& in) {
    const auto count = in.pod<std::uint32_t>();
    if (count > kMaxEntries) in.fail(std::to_string(count) + " metadata entries");
    std::vector<VdbMetaEntry> entries(count);
    for (VdbMetaEntry& entry : entries) {
        entry.name = in.text();
        entry.type = in.text();
        entry.bytes = in.text();  // Metadata::read: a 32-bit size, then the value
    }
    return entries;
}

// Transform::read: the map's type name, then the map, of a size each map type fixes.
std::string readTransform(Input& in) {
    const std::string type = in.text();
    std::uint64_t bytes = 0;
    if (type == "UniformScaleTranslateMap" || type == "ScaleTranslateMap")
        bytes = 6 * 24;  // translation, scale, voxel size, 1/scale, 1/scale², 1/(2 scale)
    else if (type == "UniformScaleMap" || type == "ScaleMap")
        bytes = 5 * 24;
    else if (type == "TranslationMap")
        bytes = 24;
    else if (type == "AffineMap" || type == "UnitaryMap")
        bytes = 16 * 8;  // a Mat4d
    else
        in.fail("a transform of type '" + type + "'");
    std::string out(4, '\0');
    const auto length = std::uint32_t(type.size());
    std::memcpy(out.data(), &length, 4);
    out += type;
    const std::size_t at = out.size();
    out.resize(at + bytes);
    in.bytes(&out[at], bytes);
    return out;
}

// One grid's stream settings: what io::readCompressedValues reads the nodes' values with.
struct ValueCodec {
    std::uint32_t compression = 0;
    int channels = 1;
    std::array<float, 3> background{};

    std::size_t valueBytes() const { return sizeof(float) * std::size_t(channels); }

    // io::readData: `count` values, compressed as the grid says, into `out`.
    void readData(Input& in, float* out, std::size_t count) const {
        const std::size_t want = count * valueBytes();
        if (!(compression & (kCompressBlosc | kCompressZip))) {
            in.bytes(out, want);
            return;
        }
        const auto stored = in.pod<std::int64_t>();
        if (stored <= 0) {  // stored uncompressed (too small to compress)
            if (std::uint64_t(-stored) != want)
                in.fail("a block of " + std::to_string(-stored) + " bytes where " + std::to_string(want) +
                        " were expected");
            in.bytes(out, want);
            return;
        }
        if (std::uint64_t(stored) > want + (want >> 4) + 64 + BLOSC_MAX_OVERHEAD)
            in.fail("a compressed block larger than its data");
        std::unique_ptr<char[]> packed(new char[std::size_t(stored)]);
        in.bytes(packed.get(), std::uint64_t(stored));
        if (compression & kCompressBlosc) {
            std::size_t raw = 0, compressed = 0, block = 0;
            if (blosc_cbuffer_validate(packed.get(), std::size_t(stored), &raw) != 0 || raw != want)
                in.fail("a blosc block that does not hold " + std::to_string(want) + " bytes");
            blosc_cbuffer_sizes(packed.get(), &raw, &compressed, &block);
            if (compressed != std::size_t(stored) || blosc_decompress_ctx(packed.get(), out, want, 1) != int(want))
                in.fail("a blosc block that does not decompress");
        } else {
            uLongf size = uLongf(want);
            if (uncompress(reinterpret_cast<Bytef*>(out), &size, reinterpret_cast<const Bytef*>(packed.get()),
                           uLong(stored)) != Z_OK ||
                size != want)
                in.fail("a zip block that does not decompress to " + std::to_string(want) + " bytes");
        }
    }

    // io::readCompressedValues: all `count` values of a node whose value mask is `mask`
    // (count bits), inactive ones restored, into `out` (count × channels floats).
    void readValues(Input& in, const std::uint64_t* mask, std::size_t count, float* out) const {
        const auto kind = in.pod<std::int8_t>();
        if (kind < kNoMaskOrInactiveVals || kind > kNoMaskAndAllVals)
            in.fail("an unknown value encoding " + std::to_string(kind));
        std::array<float, 3> outside = background, inside = background;
        if (kind != kNoMaskOrInactiveVals)
            for (int c = 0; c < channels; ++c) inside[std::size_t(c)] = -background[std::size_t(c)];
        if (kind == kNoMaskAndOneInactiveVal || kind == kMaskAndOneInactiveVal || kind == kMaskAndTwoInactiveVals)
            in.bytes(inside.data(), valueBytes());
        if (kind == kMaskAndTwoInactiveVals) in.bytes(outside.data(), valueBytes());
        std::vector<std::uint64_t> selection;
        if (kind == kMaskAndNoInactiveVals || kind == kMaskAndOneInactiveVal || kind == kMaskAndTwoInactiveVals) {
            selection.resize(count / 64);
            in.bytes(selection.data(), count / 8);
        }
        std::size_t active = 0;
        for (std::size_t w = 0; w < count / 64; ++w) active += std::size_t(__builtin_popcountll(mask[w]));
        const bool packed = (compression & kCompressActiveMask) && kind != kNoMaskAndAllVals && active != count;
        if (!packed) {
            readData(in, out, count);
            return;
        }
        std::vector<float> values(active * std::size_t(channels));
        readData(in, values.data(), active);
        const std::size_t width = std::size_t(channels);
        for (std::size_t n = 0, next = 0; n < count; ++n) {
            const bool on = (mask[n >> 6] >> (n & 63)) & 1;
            const float* from = on
                ? &values[width * next++]
                : (!selection.empty() && ((selection[n >> 6] >> (n & 63)) & 1) ? outside.data() : inside.data());
            std::copy(from, from + width, out + width * n);
        }
    }
};

bool sameValue(const float* a, const float* b, int channels) { return std::equal(a, a + channels, b); }

// A tile of `level` at `origin` from a node's slot, kept when active or not the background.
void addTile(VdbReadGrid& grid, const std::array<std::int32_t, 3>& origin, int level, const float* value, bool active) {
    VdbTile tile{origin, level, {0.0f, 0.0f, 0.0f}};
    std::copy(value, value + grid.channels(), tile.value.begin());
    if (active)
        grid.tiles.push_back(tile);
    else if (!sameValue(value, grid.background.data(), grid.channels()))
        grid.inactive_tiles.push_back(tile);
}

// Slot n of an internal node whose children are 2^child_total voxels a side and which has
// 2^log2 slots a side: the child's origin.
std::array<std::int32_t, 3> slotOrigin(const std::array<std::int32_t, 3>& node, std::size_t n, int log2,
                                       int child_total) {
    const std::size_t side = std::size_t(1) << log2;
    return {node[0] + std::int32_t((n >> (2 * log2)) << child_total),
            node[1] + std::int32_t(((n >> log2) & (side - 1)) << child_total),
            node[2] + std::int32_t((n & (side - 1)) << child_total)};
}

// InternalNode::readTopology: child and value masks, every slot's value, then the children
// (lower nodes, or for a lower node the leaves' masks), in slot order.
void readInternalTopology(Input& in, const ValueCodec& codec, VdbReadGrid& grid,
                          const std::array<std::int32_t, 3>& origin, int log2) {
    const std::size_t slots = std::size_t(1) << (3 * log2);
    const int child_total = log2 == kUpperLog2 ? kLowerTotal : kLeafLog2;
    std::vector<std::uint64_t> children(slots / 64), tiles(slots / 64);
    in.bytes(children.data(), slots / 8);
    in.bytes(tiles.data(), slots / 8);
    std::vector<float> values(slots * std::size_t(codec.channels));
    codec.readValues(in, tiles.data(), slots, values.data());
    for (std::size_t n = 0; n < slots; ++n) {
        if ((children[n >> 6] >> (n & 63)) & 1) continue;
        const bool active = (tiles[n >> 6] >> (n & 63)) & 1;
        addTile(grid, slotOrigin(origin, n, log2, child_total), log2 == kUpperLog2 ? 2 : 1,
                &values[n * std::size_t(codec.channels)], active);
    }
    for (std::size_t n = 0; n < slots; ++n) {
        if (!((children[n >> 6] >> (n & 63)) & 1)) continue;
        const std::array<std::int32_t, 3> child = slotOrigin(origin, n, log2, child_total);
        if (log2 == kUpperLog2) {
            readInternalTopology(in, codec, grid, child, kLowerLog2);
        } else {
            VdbReadGrid::Leaf leaf;
            leaf.origin = child;
            in.bytes(leaf.mask, sizeof leaf.mask);
            grid.leaves.push_back(leaf);
        }
    }
}

// RootNode::readTopology (the current format): background, tiles, then the upper nodes.
void readTopology(Input& in, const ValueCodec& codec, VdbReadGrid& grid) {
    if (in.pod<std::int32_t>() != 1) in.fail("a tree of more than one buffer");
    in.bytes(grid.background.data(), codec.valueBytes());
    const auto root_tiles = in.pod<std::uint32_t>();
    const auto uppers = in.pod<std::uint32_t>();
    if (root_tiles > kMaxEntries || uppers > kMaxEntries)
        in.fail("a root of " + std::to_string(root_tiles + 0ull + uppers) + " entries");
    ValueCodec with_background = codec;
    with_background.background = grid.background;
    for (std::uint32_t t = 0; t < root_tiles; ++t) {
        const auto origin = in.pod<std::array<std::int32_t, 3>>();
        std::array<float, 3> value{};
        in.bytes(value.data(), codec.valueBytes());
        const auto active = in.pod<std::uint8_t>();
        addTile(grid, origin, 3, value.data(), active != 0);
    }
    for (std::uint32_t u = 0; u < uppers; ++u) {
        const auto origin = in.pod<std::array<std::int32_t, 3>>();
        readInternalTopology(in, with_background, grid, origin, kUpperLog2);
    }
}

// LeafNode::readBuffers of every leaf, in the order of the topology: its mask again, then its
// values; the active ones are kept packed, inactive ones only where not the background.
void readLeafBuffers(Input& in, const ValueCodec& codec, VdbReadGrid& grid, Interrupter* interrupter) {
    const std::size_t width = std::size_t(grid.channels());
    std::vector<float> dense(kLeafValues * width);
    std::uint64_t active_so_far = 0;
    for (std::size_t n = 0; n < grid.leaves.size(); ++n) {
        if (n % 4096 == 0) throwIfInterrupted(interrupter);
        VdbReadGrid::Leaf& leaf = grid.leaves[n];
        std::uint64_t mask[8];
        in.bytes(mask, sizeof mask);
        if (!std::equal(mask, mask + 8, leaf.mask)) in.fail("a leaf whose buffer's mask is not its topology's");
        codec.readValues(in, leaf.mask, kLeafValues, dense.data());
        leaf.first = active_so_far;
        bool background_only = true;
        for (std::size_t v = 0; v < kLeafValues; ++v) {
            const float* value = &dense[v * width];
            if (!((leaf.mask[v >> 6] >> (v & 63)) & 1)) {
                background_only = background_only && sameValue(value, grid.background.data(), grid.channels());
                continue;
            }
            if (active_so_far == 0 && grid.values.empty()) std::copy(value, value + width, grid.uniform_value.begin());
            if (grid.uniform && !sameValue(value, grid.uniform_value.data(), grid.channels())) {
                // The first value that differs: the earlier ones were all the uniform value.
                grid.uniform = false;
                grid.values.reserve(std::size_t(active_so_far + 1) * width);
                for (std::uint64_t k = 0; k < active_so_far; ++k)
                    grid.values.insert(grid.values.end(), grid.uniform_value.begin(),
                                       grid.uniform_value.begin() + long(width));
            }
            if (!grid.uniform) grid.values.insert(grid.values.end(), value, value + width);
            ++active_so_far;
        }
        if (!background_only) {
            leaf.inactive = std::int64_t(grid.inactive_values.size() / (kLeafValues * width));
            grid.inactive_values.insert(grid.inactive_values.end(), dense.begin(), dense.end());
        }
    }
}

VdbReadGrid readGrid(Input& in, const std::string& unique_name, const std::string& tree_type,
                     Interrupter* interrupter) {
    VdbReadGrid grid;
    // GridDescriptor: "name\x1e<n>" for the second and later grids of one name.
    grid.name = unique_name.substr(0, unique_name.find('\x1e'));
    if (tree_type == "Tree_float_5_4_3")
        grid.type = VdbValueType::Float;
    else if (tree_type == "Tree_vec3s_5_4_3")
        grid.type = VdbValueType::Vec3f;
    else
        in.fail("grid '" + grid.name + "' is a " + tree_type + " (float and Vec3f grids are read)");
    ValueCodec codec;
    codec.channels = grid.channels();
    codec.compression = in.pod<std::uint32_t>();
    if (codec.compression & ~(kCompressZip | kCompressActiveMask | kCompressBlosc))
        in.fail("unknown compression flags " + std::to_string(codec.compression));
    grid.metadata = readMetaMap(in);
    grid.transform = readTransform(in);
    readTopology(in, codec, grid);
    codec.background = grid.background;
    readLeafBuffers(in, codec, grid, interrupter);
    return grid;
}

}  // namespace

std::uint64_t VdbReadGrid::activeLeafVoxels() const {
    std::uint64_t n = 0;
    for (const Leaf& leaf : leaves)
        for (std::uint64_t w : leaf.mask) n += std::uint64_t(__builtin_popcountll(w));
    return n;
}

const VdbMetaEntry* VdbReadGrid::meta(const std::string& key) const {
    for (const VdbMetaEntry& entry : metadata)
        if (entry.name == key) return &entry;
    return nullptr;
}

std::string VdbReadGrid::metaText(const std::string& key) const {
    const VdbMetaEntry* entry = meta(key);
    return entry && entry->type == "string" ? entry->bytes : std::string();
}

VdbFile readVdbFile(const std::string& path, Interrupter* interrupter) {
    Input in(path);
    VdbFile file;
    // Archive::readHeader.
    if (in.pod<std::int64_t>() != kMagic) in.fail("it does not start with OpenVDB's magic number");
    file.version = in.pod<std::uint32_t>();
    if (file.version < kFirstVersion)
        in.fail("file format version " + std::to_string(file.version) + " (written before OpenVDB 3; version " +
                std::to_string(kFirstVersion) + " and later are read)");
    in.pod<std::uint32_t>();  // library major
    in.pod<std::uint32_t>();  // library minor
    if (in.pod<char>() == 0) in.fail("it was written to a stream, without grid offsets");
    char uuid[36];
    in.bytes(uuid, sizeof uuid);
    file.metadata = readMetaMap(in);
    const auto grids = in.pod<std::int32_t>();
    if (grids < 0 || std::uint32_t(grids) > kMaxEntries) in.fail(std::to_string(grids) + " grids");
    for (std::int32_t g = 0; g < grids; ++g) {
        // GridDescriptor::read.
        const std::string unique_name = in.text();
        const std::string tree_type = in.text();
        if (tree_type.size() >= 10 && tree_type.compare(tree_type.size() - 10, 10, "_HalfFloat") == 0)
            in.fail("grid '" + unique_name + "' is stored as half floats");
        if (!in.text().empty()) in.fail("grid '" + unique_name + "' is an instance of another grid");
        const auto grid_pos = in.pod<std::int64_t>();
        in.pod<std::int64_t>();  // where its leaf buffers start
        const auto end_pos = in.pod<std::int64_t>();
        in.seek(grid_pos);
        file.grids.push_back(readGrid(in, unique_name, tree_type, interrupter));
        if (std::int64_t(in.at()) != end_pos)
            in.fail("grid '" + unique_name + "' does not end where its descriptor says");
        in.seek(end_pos);
    }
    return file;
}

}  // namespace hyvox::vdb
