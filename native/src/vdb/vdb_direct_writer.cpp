// SPDX-License-Identifier: GPL-3.0-or-later
// OpenVDB's file layout for float and Vec3f 5-4-3 trees, written without OpenVDB (see the header;
// why: docs/why/vdb-output.md).
// Byte order and field order follow openvdb::io::Archive::write (file version 224): the
// header, the file metadata, the grid descriptor with its stream offsets, the grid's
// compression flags, its metadata (sorted by name, as a MetaMap), its transform, the tree
// topology (root, 32³ and 16³ internal nodes with their masks, the leaves' masks) and the
// leaf buffers. Every integer is little-endian, as OpenVDB writes them on x86 and ARM.
#include "vdb/vdb_direct_writer.h"

#include <blosc.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "hyvox/errors.h"
#include "hyvox/region.h"
#include "hyvox/version.h"

namespace hyvox::vdb {
namespace {

constexpr std::int64_t kMagic = 0x56444220;  // OPENVDB_MAGIC
constexpr std::uint32_t kFileVersion = 224;  // OPENVDB_FILE_VERSION of OpenVDB 10
constexpr std::uint32_t kLibraryMajor = 10, kLibraryMinor = 0;
// io::COMPRESS_ACTIVE_MASK | io::COMPRESS_BLOSC, OpenVDB 10's default for every grid: each node
// stores its active values only, as one blosc block.
constexpr std::uint32_t kCompressActiveMask = 0x2, kCompressBlosc = 0x4;
constexpr std::uint32_t kCompression = kCompressActiveMask | kCompressBlosc;
// The metadata byte before a node's values (io::MaskCompress): which inactive values it holds.
constexpr std::int8_t kNoMaskOrInactiveVals = 0;   // every inactive value is the background
constexpr std::int8_t kNoMaskAndMinusBg = 1;       // every inactive value is -background
constexpr std::int8_t kMaskAndNoInactiveVals = 3;  // both, and a mask that selects +background

// Node geometry of Tree_float_5_4_3: a leaf spans 8 voxels per axis, a lower internal node
// 16 leaves (128 voxels), an upper internal node 32 lower nodes (4096 voxels).
constexpr int kLeafLog2 = 3, kLowerLog2 = 4, kUpperLog2 = 5;
constexpr int kLowerTotal = kLeafLog2 + kLowerLog2;                             // 7
constexpr int kUpperTotal = kLowerTotal + kUpperLog2;                           // 12
constexpr std::size_t kLowerWords = (std::size_t(1) << (3 * kLowerLog2)) / 64;  // 64
constexpr std::size_t kUpperWords = (std::size_t(1) << (3 * kUpperLog2)) / 64;  // 512
constexpr std::size_t kLeafMaskBytes = 8 * sizeof(std::uint64_t);

constexpr int kLowerSlots = 1 << (3 * kLowerLog2), kUpperSlots = 1 << (3 * kUpperLog2);

// OpenVDB's memUsage() terms for these tree types (checked against OpenVDB by the tests):
// the empty tree and root, each leaf (node + 512 values), each internal node (its table of
// unions of a child pointer and a value, two masks and an origin).
struct TreeBytes {
    std::uint64_t empty_tree, leaf, lower, upper;
};
constexpr TreeBytes kFloatTreeBytes{1304, 96 + 512 * 4, 4096 * 8 + 2 * 512 + 12, 32768 * 8 + 2 * 4096 + 12};
constexpr TreeBytes kVec3fTreeBytes{1320, 96 + 512 * 12, 4096 * 16 + 2 * 512 + 12, 32768 * 16 + 2 * 4096 + 12};
const TreeBytes& treeBytes(VdbValueType type) {
    return type == VdbValueType::Float ? kFloatTreeBytes : kVec3fTreeBytes;
}

// io::writeData with COMPRESS_BLOSC (io::bloscToStream): the compressed size as an int64 and
// blosc's block, compressed with OpenVDB's settings (level 9, byte shuffle over 4-byte
// words, LZ4, one block, one thread), so the bytes are the ones OpenVDB writes; a negative
// size and the raw bytes where blosc cannot compress. Thread-safe (blosc's _ctx API).
void appendBlosc(std::string& out, const void* data, std::size_t bytes) {
    const std::size_t at = out.size();
    out.resize(at + 8 + bytes + BLOSC_MAX_OVERHEAD);
    const int packed = blosc_compress_ctx(9, BLOSC_SHUFFLE, sizeof(float), bytes, data, &out[at + 8],
                                          bytes + BLOSC_MAX_OVERHEAD, BLOSC_LZ4_COMPNAME, bytes, 1);
    std::int64_t size = packed;
    if (packed <= 0) {
        size = -std::int64_t(bytes);
        if (bytes) std::memcpy(&out[at + 8], data, bytes);
    }
    std::memcpy(&out[at], &size, 8);
    out.resize(at + 8 + std::size_t(packed > 0 ? packed : std::int64_t(bytes)));
}

// Appends to a growing byte string (the parts before the leaf buffers: header, metadata,
// topology) that starts at file position `base`: size() is the file position of the next byte.
// With a `sink`, the bytes go to it whenever a MiB has gathered (a grid's topology holds every
// leaf's mask: 64 bytes a leaf) and at flush(); without, str() holds them all.
class Bytes {
public:
    explicit Bytes(std::size_t base = 0, std::ostream* sink = nullptr) : base_(base), sink_(sink) {}
    template <typename T>
    void pod(const T& value) {
        raw(&value, sizeof value);
    }
    void raw(const void* data, std::size_t size) {
        out_.append(static_cast<const char*>(data), size);
        spillIfFull();
    }
    // io::writeString: a 32-bit length, then the characters.
    void string(const std::string& text) {
        pod(std::uint32_t(text.size()));
        raw(text.data(), text.size());
    }
    void blosc(const void* data, std::size_t bytes) {
        appendBlosc(out_, data, bytes);
        spillIfFull();
    }
    std::size_t size() const { return base_ + out_.size(); }
    const std::string& str() const { return out_; }
    void flush() {  // with a sink only
        sink_->write(out_.data(), std::streamsize(out_.size()));
        base_ += out_.size();
        out_.clear();
    }
    // `bytes` straight to the sink, after what has gathered (a block of leaf buffers).
    void write(const std::string& bytes) {
        flush();
        sink_->write(bytes.data(), std::streamsize(bytes.size()));
        base_ += bytes.size();
    }
    // Writes `value` at file position `at`, before what has gathered (a position known only
    // after the bytes that follow it).
    template <typename T>
    void writeAt(std::size_t at, const T& value) {
        flush();
        sink_->seekp(std::streamoff(at));
        sink_->write(reinterpret_cast<const char*>(&value), sizeof value);
        sink_->seekp(std::streamoff(base_));
    }

private:
    void spillIfFull() {
        if (sink_ && out_.size() >= kSpillBytes) flush();
    }
    static constexpr std::size_t kSpillBytes = std::size_t(1) << 20;
    std::size_t base_;
    std::ostream* sink_;
    std::string out_;
};

// One Metadata value as MetaMap::writeMeta stores it after the name: type name, byte size, bytes.
struct MetaValue {
    std::string type;
    std::string bytes;
};

template <typename T, std::size_t N>
MetaValue metaOf(const char* type, const std::array<T, N>& values) {
    return {type, std::string(reinterpret_cast<const char*>(values.data()), sizeof(T) * N)};
}
MetaValue metaString(const std::string& text) { return {"string", text}; }
MetaValue metaDouble(double value) { return metaOf("double", std::array<double, 1>{value}); }
MetaValue metaInt64(std::int64_t value) { return metaOf("int64", std::array<std::int64_t, 1>{value}); }

// Archive::writeHeader's 36-character UUID (random, like OpenVDB's).
std::string randomUuid() {
    std::random_device seed;
    std::mt19937_64 random((std::uint64_t(seed()) << 32) ^ seed());
    static const char hex[] = "0123456789abcdef";
    std::string uuid;
    for (int i = 0; i < 32; ++i) {
        if (i == 8 || i == 12 || i == 16 || i == 20) uuid += '-';
        uuid += hex[random() & 15];
    }
    return uuid;
}

// A leaf's or tile's place in the tree's write order: upper node (by origin, as the root's
// std::map of Coords sorts them), then the lower node's offset in the upper node's table and
// the leaf's in the lower node's. Level-2 tiles take offset 0 in their lower slot, root
// tiles (level 3) slot 0.
struct Placed {
    std::uint64_t upper;  // x, y, z of the upper node, 21 bits each (grid coordinates are >= 0)
    std::uint32_t lower;  // offset in the upper node's table (15 bits)
    std::uint32_t leaf;   // offset in the lower node's table (12 bits)
    int level;            // 0: a leaf, else the tile's level
    std::size_t index;    // into the grid's leaves (level 0) or the tile values
};

int tableOffset(const std::array<std::int32_t, 3>& at, int node_total, int child_total, int log2) {
    const int mask = (1 << node_total) - 1;
    return (((at[0] & mask) >> child_total) << (2 * log2)) + (((at[1] & mask) >> child_total) << log2) +
        ((at[2] & mask) >> child_total);
}

Placed place(const std::array<std::int32_t, 3>& o, int level, std::size_t index) {
    static const int kSideLog2[] = {kLeafLog2, kLeafLog2, kLowerTotal, kUpperTotal};
    for (int a = 0; a < 3; ++a)
        if (o[a] < 0 || (o[a] & ((1 << kSideLog2[level]) - 1)) != 0)
            throw InvalidInput("vdb writer: a " + std::string(level ? "tile" : "leaf") + " at (" +
                               std::to_string(o[0]) + ", " + std::to_string(o[1]) + ", " + std::to_string(o[2]) +
                               ") is below 0 or off its node lattice");
    Placed p;
    p.upper = (std::uint64_t(o[0] >> kUpperTotal) << 42) | (std::uint64_t(o[1] >> kUpperTotal) << 21) |
        std::uint64_t(o[2] >> kUpperTotal);
    p.lower = level >= 3 ? 0 : std::uint32_t(tableOffset(o, kUpperTotal, kLowerTotal, kUpperLog2));
    p.leaf = level >= 2 ? 0 : std::uint32_t(tableOffset(o, kLowerTotal, kLeafLog2, kLowerLog2));
    p.level = level;
    p.index = index;
    return p;
}

std::array<std::int32_t, 3> upperOrigin(std::uint64_t upper) {
    const std::uint64_t bits = (std::uint64_t(1) << 21) - 1;
    return {std::int32_t((upper >> 42) << kUpperTotal), std::int32_t(((upper >> 21) & bits) << kUpperTotal),
            std::int32_t((upper & bits) << kUpperTotal)};
}

bool inSlot(const Placed& a, const Placed& b) { return a.upper == b.upper && a.lower == b.lower && a.leaf == b.leaf; }
bool writeOrder(const Placed& a, const Placed& b) {
    if (a.upper != b.upper) return a.upper < b.upper;
    if (a.lower != b.lower) return a.lower < b.lower;
    return a.leaf != b.leaf ? a.leaf < b.leaf : a.level > b.level;
}

// The tree of one grid, in write order: leaves and tiles (tiles merged upwards as prune()
// merges them), with the tiles' values.
struct PlacedTree {
    std::vector<Placed> items;
    std::vector<std::array<float, 3>> tile_values;  // by Placed::index for tiles
    std::vector<char> tile_active;                  // the same
};

// Whether `count` consecutive items (from `first`) are all tiles of `level` with one value.
bool mergeable(const PlacedTree& tree, std::size_t first, std::size_t count, int level) {
    const std::vector<Placed>& items = tree.items;
    for (std::size_t n = first; n < first + count; ++n)
        if (items[n].level != level || tree.tile_values[items[n].index] != tree.tile_values[items[first].index] ||
            tree.tile_active[items[n].index] != tree.tile_active[items[first].index])
            return false;
    return true;
}

// Where the items of one node (a lower node for level 1, an upper one for level 2) are
// tiles of `level` with one value filling the whole node, they become one tile of the level
// above, as Tree::prune() makes them.
void mergeTiles(PlacedTree& tree, int level) {
    const int slots = level == 1 ? kLowerSlots : kUpperSlots;
    std::vector<Placed> merged;
    merged.reserve(tree.items.size());
    std::size_t n = 0;
    const std::vector<Placed>& items = tree.items;
    while (n < items.size()) {
        std::size_t end = n;
        while (end < items.size() && items[end].upper == items[n].upper &&
               (level == 2 || items[end].lower == items[n].lower))
            ++end;
        if (end - n == std::size_t(slots) && mergeable(tree, n, end - n, level)) {
            Placed up = items[n];
            up.level = level + 1;
            up.leaf = 0;
            if (level == 2) up.lower = 0;
            merged.push_back(up);
        } else {
            merged.insert(merged.end(), items.begin() + long(n), items.begin() + long(end));
        }
        n = end;
    }
    tree.items.swap(merged);
}

PlacedTree placeTree(const VdbGrid& grid) {
    PlacedTree tree;
    tree.items.reserve(grid.leaves.size() + grid.tiles.size());
    tree.tile_values.reserve(grid.tiles.size());
    tree.tile_active.reserve(grid.tiles.size());
    for (std::size_t n = 0; n < grid.leaves.size(); ++n) tree.items.push_back(place(grid.leaves[n].origin, 0, n));
    for (std::size_t n = 0; n < grid.tiles.size(); ++n) {
        const VdbTile& tile = grid.tiles[n];
        if (tile.level < 1 || tile.level > 3) throw InvalidInput("vdb writer: a tile's level must be 1, 2 or 3");
        tree.items.push_back(place(tile.origin, tile.level, n));
        std::array<float, 3> value = tile.value;
        if (grid.type == VdbValueType::Float) value[1] = value[2] = 0;  // one channel
        if (!tile.active) value = {-grid.background, 0.0f, 0.0f};
        tree.tile_values.push_back(value);
        tree.tile_active.push_back(tile.active);
    }
    std::sort(tree.items.begin(), tree.items.end(), writeOrder);
    // Overlaps: two items in one slot, or a tile over a node that holds other items (such a
    // tile sorts first among them).
    for (std::size_t n = 1; n < tree.items.size(); ++n) {
        const Placed &a = tree.items[n - 1], &b = tree.items[n];
        const bool overlap =
            inSlot(a, b) || (a.upper == b.upper && (a.level == 3 || (a.level == 2 && a.lower == b.lower)));
        if (overlap) throw InvalidInput("vdb writer: leaves or tiles overlap");
    }
    mergeTiles(tree, 1);
    mergeTiles(tree, 2);
    return tree;
}

// Whether placeTree(a) is placeTree(b): both have the same leaves (origins, in order) and no tiles.
bool sameLeavesNoTiles(const VdbGrid& a, const VdbGrid& b) {
    if (!a.tiles.empty() || !b.tiles.empty() || a.leaves.size() != b.leaves.size()) return false;
    for (std::size_t n = 0; n < a.leaves.size(); ++n)
        if (a.leaves[n].origin != b.leaves[n].origin) return false;
    return true;
}

// Grid::memUsage() of the tree: its leaves and the internal nodes that hold leaves or tiles.
std::uint64_t memUsage(const PlacedTree& tree, VdbValueType type) {
    const TreeBytes& bytes = treeBytes(type);
    std::uint64_t leaves = 0, uppers = 0, lowers = 0;
    const std::vector<Placed>& items = tree.items;
    for (std::size_t n = 0; n < items.size(); ++n) {
        const Placed& p = items[n];
        if (p.level == 3) continue;
        leaves += p.level == 0;
        const bool new_upper = n == 0 || items[n - 1].upper != p.upper || items[n - 1].level == 3;
        uppers += new_upper;
        if (p.level < 2) lowers += new_upper || items[n - 1].lower != p.lower || items[n - 1].level == 2;
    }
    return bytes.empty_tree + leaves * bytes.leaf + lowers * bytes.lower + uppers * bytes.upper;
}

std::uint64_t activeCount(const std::uint64_t* mask) {
    std::uint64_t n = 0;
    for (int w = 0; w < 8; ++w) n += std::uint64_t(__builtin_popcountll(mask[w]));
    return n;
}

// Grid::evalActiveVoxelBoundingBox() and activeVoxelCount(); an empty grid's box is
// CoordBBox(): min INT_MAX, max INT_MIN.
struct ActiveVoxels {
    std::array<std::int32_t, 3> lo{INT_MAX, INT_MAX, INT_MAX}, hi{INT_MIN, INT_MIN, INT_MIN};
    std::uint64_t count = 0;
    void add(const std::array<std::int32_t, 3>& min, const std::array<std::int32_t, 3>& max) {
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], min[a]), hi[a] = std::max(hi[a], max[a]);
    }
};

ActiveVoxels activeVoxels(const VdbGrid& grid, const PlacedTree& tree) {
    ActiveVoxels box;
    for (const Placed& p : tree.items) {
        if (p.level == 0 || !tree.tile_active[p.index]) continue;
        static const int kSideLog2[] = {0, kLeafLog2, kLowerTotal, kUpperTotal};
        std::array<std::int32_t, 3> o = upperOrigin(p.upper);
        const std::array<std::int32_t, 3> lower_at{std::int32_t(p.lower >> 10), std::int32_t((p.lower >> 5) & 31),
                                                   std::int32_t(p.lower & 31)};
        const std::array<std::int32_t, 3> leaf_at{std::int32_t(p.leaf >> 8), std::int32_t((p.leaf >> 4) & 15),
                                                  std::int32_t(p.leaf & 15)};
        for (int a = 0; a < 3; ++a) o[a] += (lower_at[a] << kLowerTotal) + (leaf_at[a] << kLeafLog2);
        const std::int32_t side = std::int32_t(1) << kSideLog2[p.level];
        box.add(o, {o[0] + side - 1, o[1] + side - 1, o[2] + side - 1});
        box.count += std::uint64_t(1) << (3 * kSideLog2[p.level]);
    }
    for (const VdbLeaf& leaf : grid.leaves) {
        box.count += activeCount(leaf.mask);
        // Word x holds the voxels of x; bit y * 8 + z. Folding the words gives the y and z
        // ranges: byte y of the OR is non-zero where row y has a voxel, the OR of its bytes
        // has bit z set where column z has one.
        std::uint64_t any = 0;
        int x0 = 8, x1 = -1;
        for (int x = 0; x < 8; ++x) {
            if (!leaf.mask[x]) continue;
            any |= leaf.mask[x];
            x0 = std::min(x0, x), x1 = x;
        }
        if (!any) continue;
        const int y0 = __builtin_ctzll(any) >> 3, y1 = (63 - __builtin_clzll(any)) >> 3;
        std::uint64_t columns = any;
        columns |= columns >> 32, columns |= columns >> 16, columns |= columns >> 8;
        const unsigned z_bits = unsigned(columns & 0xff);
        const int z0 = __builtin_ctz(z_bits), z1 = 31 - __builtin_clz(z_bits);
        const std::array<std::int32_t, 3>& o = leaf.origin;
        box.add({o[0] + x0, o[1] + y0, o[2] + z0}, {o[0] + x1, o[1] + y1, o[2] + z1});
    }
    return box;
}

std::map<std::string, MetaValue> gridMetadata(const VoxelizeResult& result, const VdbGrid& vdb, const PlacedTree& tree,
                                              std::uint64_t mem_usage) {
    const ActiveVoxels active = activeVoxels(vdb, tree);
    const GridSpec& grid = result.grid;
    std::map<std::string, MetaValue> meta;
    if (!vdb.grid_class.empty()) meta["class"] = metaString(vdb.grid_class);
    if (!vdb.vector_type.empty()) meta["vector_type"] = metaString(vdb.vector_type);
    meta["creator"] = metaString(std::string("hyvox ") + version());
    meta["file_bbox_min"] = metaOf("vec3i", active.lo);
    meta["file_bbox_max"] = metaOf("vec3i", active.hi);
    meta["file_compression"] = metaString("blosc + active values");  // io::compressionToString
    meta["file_mem_bytes"] = metaInt64(std::int64_t(mem_usage));
    meta["file_voxel_count"] = metaInt64(std::int64_t(active.count));
    meta["name"] = metaString(vdb.name);
    // The hyvox_* entries, as addMetadata() in vdb_grid.cpp writes them.
    meta["hyvox_version"] = metaString(version());
    meta["hyvox_method"] = metaString(result.stats.method);
    meta["hyvox_mode"] = metaString(result.stats.mode);
    meta["hyvox_voxel_size"] = metaDouble(grid.voxel_size);
    meta["hyvox_origin"] = metaOf("vec3d", grid.origin);
    meta["hyvox_dims"] = metaOf("vec3i", grid.dims);
    if (!result.stats.options.region.whole())
        meta["hyvox_region"] = metaString(formatRegion(result.stats.options.region));
    return meta;
}

}  // namespace

std::string vdbTransformBytes(const GridSpec& grid) {
    Bytes out;
    out.string("UniformScaleTranslateMap");
    const double s = grid.voxel_size, h = 0.5 * grid.voxel_size;
    const double inverse = 1.0 / s;
    // translation, then scale, voxel size, 1/scale, 1/scale², 1/(2 scale), each a Vec3d
    for (int a = 0; a < 3; ++a) out.pod(grid.origin[a] + h);
    for (const double v : {s, std::abs(s), inverse, inverse * inverse, inverse / 2})
        for (int a = 0; a < 3; ++a) out.pod(v);
    return out.str();
}

namespace {

// The metadata byte of a node whose inactive values are `inside` (-background) and
// `outside` (+background) (io::MaskCompress, as io::writeCompressedValues decides it): with
// both, the selection mask of the +background ones follows it.
std::int8_t inactiveMetadata(bool inside, bool outside, float background) {
    if (background == 0 || !inside) return kNoMaskOrInactiveVals;
    return outside ? kMaskAndNoInactiveVals : kNoMaskAndMinusBg;
}

// InternalNode::writeTopology's table: the child and value masks, the metadata byte (and the
// selection mask of a level set's table with tiles inside and empty slots outside) and the
// active tiles' values as one blosc block. `items` [first, last) are the node's children and
// tiles, one per slot in table order; `slotOf` gives their table offset, `tile_level` the
// level of the node's own tiles.
template <typename SlotOf>
void writeNodeTable(Bytes& out, const PlacedTree& tree, std::size_t first, std::size_t last, std::size_t words,
                    int tile_level, int channels, float background, SlotOf slotOf) {
    std::vector<std::uint64_t> children(words, 0), tiles(words, 0), outside(words, ~std::uint64_t(0));
    std::vector<float> values;
    bool any_inside = false;
    for (std::size_t n = first; n < last; ++n) {
        const Placed& p = tree.items[n];
        const std::uint32_t slot = slotOf(p);
        const std::uint64_t bit = std::uint64_t(1) << (slot & 63);
        outside[slot >> 6] &= ~bit;  // a child, an active tile or an inside tile
        if (p.level != tile_level) {
            children[slot >> 6] |= bit;
        } else if (tree.tile_active[p.index]) {
            tiles[slot >> 6] |= bit;
            // In table order: the order writeCompressedValues gathers active values in.
            values.insert(values.end(), tree.tile_values[p.index].begin(),
                          tree.tile_values[p.index].begin() + channels);
        } else {
            any_inside = true;
        }
    }
    bool any_outside = false;
    for (std::uint64_t w : outside) any_outside = any_outside || w != 0;
    out.raw(children.data(), words * 8);
    out.raw(tiles.data(), words * 8);
    const std::int8_t metadata = inactiveMetadata(any_inside, any_outside, background);
    out.pod(metadata);
    if (metadata == kMaskAndNoInactiveVals) out.raw(outside.data(), words * 8);
    out.blosc(values.data(), values.size() * sizeof(float));
}

// TreeBase::writeTopology: the root (background, tiles, then each upper node), every
// internal node's table and the leaves' masks, in OpenVDB's order.
void writeTopology(Bytes& out, const VdbGrid& grid, const PlacedTree& tree) {
    const int channels = grid.channels();
    const std::vector<Placed>& items = tree.items;
    out.pod(std::int32_t(1));  // buffer count
    for (int c = 0; c < channels; ++c) out.pod(c == 0 ? grid.background : 0.0f);
    std::uint32_t root_tiles = 0, uppers = 0;
    for (std::size_t n = 0; n < items.size(); ++n) {
        if (items[n].level == 3)
            ++root_tiles;
        else
            uppers += n == 0 || items[n].upper != items[n - 1].upper || items[n - 1].level == 3;
    }
    out.pod(root_tiles);
    out.pod(uppers);
    for (const Placed& p : items) {
        if (p.level != 3) continue;
        out.pod(upperOrigin(p.upper));
        out.raw(tree.tile_values[p.index].data(), sizeof(float) * std::size_t(channels));
        out.pod(bool(tree.tile_active[p.index]));
    }
    std::size_t n = 0;
    while (n < items.size()) {
        if (items[n].level == 3) {
            ++n;
            continue;
        }
        std::size_t upper_end = n;
        while (upper_end < items.size() && items[upper_end].upper == items[n].upper) ++upper_end;
        out.pod(upperOrigin(items[n].upper));
        writeNodeTable(out, tree, n, upper_end, kUpperWords, 2, channels, grid.background,
                       [](const Placed& p) { return p.lower; });
        while (n < upper_end) {
            if (items[n].level == 2) {
                ++n;
                continue;
            }
            std::size_t lower_end = n;
            while (lower_end < upper_end && items[lower_end].lower == items[n].lower) ++lower_end;
            writeNodeTable(out, tree, n, lower_end, kLowerWords, 1, channels, grid.background,
                           [](const Placed& p) { return p.leaf; });
            for (; n < lower_end; ++n)
                if (items[n].level == 0) out.raw(grid.leaves[items[n].index].mask, kLeafMaskBytes);
        }
    }
}

// Leaves per block of buffers compressed by one task.
constexpr std::size_t kLeavesPerBlock = 256;

// LeafNode::writeBuffers for `leaves` [first, last) (indices into grid.leaves in write
// order): per leaf its mask, the metadata byte and its active values as a blosc block.
std::string leafBuffers(const VdbGrid& grid, const std::vector<std::size_t>& leaves, std::size_t first,
                        std::size_t last) {
    std::string out;
    const std::size_t channels = std::size_t(grid.channels());
    const std::size_t stride = grid.stride ? grid.stride : channels;
    float active[512 * 3];
    for (std::size_t n = first; n != last; ++n) {
        const VdbLeaf& leaf = grid.leaves[leaves[n]];
        out.append(reinterpret_cast<const char*>(leaf.mask), kLeafMaskBytes);
        // A level set's inactive voxels: inside (-background) and outside (+background).
        std::uint64_t outside[8];
        bool any_inside = false, any_outside = false;
        for (int w = 0; w < 8; ++w) {
            const std::uint64_t inactive = ~leaf.mask[w], inside = leaf.inside ? inactive & leaf.inside[w] : 0;
            outside[w] = inactive & ~inside;
            any_inside = any_inside || inside != 0;
            any_outside = any_outside || outside[w] != 0;
        }
        const std::int8_t metadata = inactiveMetadata(any_inside, any_outside, grid.background);
        out += char(metadata);
        if (metadata == kMaskAndNoInactiveVals) out.append(reinterpret_cast<const char*>(outside), kLeafMaskBytes);
        float* to = active;
        std::size_t packed = 0;
        for (int w = 0; w < 8; ++w)
            for (std::uint64_t bits = leaf.mask[w]; bits; bits &= bits - 1, to += channels) {
                const float* from = grid.fill.data();
                if (grid.layout == VdbLeafValues::Dense)
                    from = leaf.values + std::size_t(w * 64 + __builtin_ctzll(bits)) * stride;
                else if (grid.layout == VdbLeafValues::Packed)
                    from = leaf.values + packed++ * stride;
                std::copy(from, from + channels, to);
            }
        appendBlosc(out, active, std::size_t(to - active) * sizeof(float));
    }
    return out;
}

// Blocks compressed side by side and then written, one batch after another: the write holds
// one batch's bytes, not the file's.
constexpr std::size_t kBlocksPerBatch = kVdbLeavesPerBatch / kLeavesPerBlock;

// One grid as Archive::writeGrid lays it out, appended to `file`: the descriptor, compression,
// metadata, transform and topology, then the leaf buffers, compressed in parallel in blocks of
// kLeavesPerBlock leaves. The descriptor's positions of the buffers and of the grid's end are
// known only once they are written, and are then written in place. `tree`: placeTree(grid).
// `done(fraction)` is called between batches. Returns Grid::memUsage().
std::uint64_t writeGrid(Bytes& file, const VoxelizeResult& result, const VdbGrid& grid, const PlacedTree& tree,
                        tbb::task_arena& arena, const std::function<void(double)>& done) {
    if (grid.layout != VdbLeafValues::Fill)
        for (const VdbLeaf& leaf : grid.leaves)
            if (!leaf.values && activeCount(leaf.mask))
                throw InvalidInput("vdb writer: grid '" + grid.name + "' has a leaf without values");
    // GridDescriptor::writeHeader and writeStreamPos: the grid's position (right after the three
    // positions), then where its buffers begin and where it ends (written in place below).
    file.string(grid.name);
    file.string(grid.type == VdbValueType::Float ? "Tree_float_5_4_3" : "Tree_vec3s_5_4_3");
    file.string("");  // not an instance
    const std::size_t stream_pos_at = file.size();
    file.pod(std::int64_t(stream_pos_at + 3 * sizeof(std::int64_t)));
    file.pod(std::int64_t(0));
    file.pod(std::int64_t(0));
    file.pod(kCompression);
    const std::uint64_t mem_usage = memUsage(tree, grid.type);
    const std::map<std::string, MetaValue> meta = gridMetadata(result, grid, tree, mem_usage);
    file.pod(std::uint32_t(meta.size()));
    for (const auto& [name, value] : meta) {
        file.string(name);
        file.string(value.type);
        file.string(value.bytes);  // Metadata::write: 32-bit size, then the value's bytes
    }
    const std::string transform = vdbTransformBytes(result.grid);
    file.raw(transform.data(), transform.size());
    writeTopology(file, grid, tree);
    file.writeAt(stream_pos_at + sizeof(std::int64_t), std::int64_t(file.size()));

    std::vector<std::size_t> leaves;
    leaves.reserve(grid.leaves.size());
    for (const Placed& p : tree.items)
        if (p.level == 0) leaves.push_back(p.index);
    const std::size_t blocks = (leaves.size() + kLeavesPerBlock - 1) / kLeavesPerBlock;
    std::vector<std::string> batch;
    for (std::size_t first = 0; first < blocks; first += kBlocksPerBatch) {
        batch.assign(std::min(kBlocksPerBatch, blocks - first), std::string());
        arena.execute([&] {
            tbb::parallel_for(std::size_t(0), batch.size(), [&](std::size_t b) {
                const std::size_t from = (first + b) * kLeavesPerBlock;
                batch[b] = leafBuffers(grid, leaves, from, std::min(leaves.size(), from + kLeavesPerBlock));
            });
        });
        for (const std::string& buffers : batch) file.write(buffers);
        done(double(first + batch.size()) / double(blocks));
    }
    file.writeAt(stream_pos_at + 2 * sizeof(std::int64_t), std::int64_t(file.size()));
    return mem_usage;
}

}  // namespace

std::uint64_t vdbTreeMemUsage(const VdbGrid& grid) { return memUsage(placeTree(grid), grid.type); }

VdbGrid resultDensityGrid(const VoxelizeResult& result) {
    VdbGrid grid = densityGrid(result.occupancy);
    const std::vector<std::uint64_t>& valued = result.attributes.valued_tile_bricks;
    if (valued.empty()) return grid;
    const BrickLayout& bricks = result.occupancy.bricks();
    auto brickOf = [&](const std::array<std::int32_t, 3>& origin) {
        return bricks.index(origin[0] / BrickLayout::kSide, origin[1] / BrickLayout::kSide,
                            origin[2] / BrickLayout::kSide);
    };
    std::vector<VdbTile> tiles;
    for (const VdbTile& tile : grid.tiles) {
        if (std::binary_search(valued.begin(), valued.end(), std::uint64_t(brickOf(tile.origin)))) {
            grid.leaves.push_back({tile.origin, BitGrid::kFullBrick});
        } else {
            tiles.push_back(tile);
        }
    }
    grid.tiles = std::move(tiles);
    return grid;
}

VdbGrid attributeGrid(const SparseGrid& occupancy, const AttributeGrid& attributes, int offset, std::string name,
                      VdbValueType type, std::string vector_type) {
    VdbGrid grid;
    grid.name = std::move(name);
    grid.type = type;
    grid.grid_class.clear();
    grid.vector_type = std::move(vector_type);
    grid.layout = VdbLeafValues::Packed;
    const std::size_t channels = std::size_t(attributes.channels());
    grid.stride = channels;
    const BrickLayout& bricks = occupancy.bricks();
    const std::vector<ValuedBrick> valued = valuedBricks(occupancy, attributes);
    grid.leaves.reserve(valued.size());
    for (const ValuedBrick& brick : valued) {
        const std::array<std::int32_t, 3> b = bricks.at(brick.brick);
        grid.leaves.push_back({{b[0] * BrickLayout::kSide, b[1] * BrickLayout::kSide, b[2] * BrickLayout::kSide},
                               brick.mask,
                               attributes.values.data() + brick.first * channels + std::size_t(offset)});
    }
    const int width = grid.channels();
    for (const AttributeTile& tile : attributes.tiles) {
        VdbTile out{tile.origin, tile.level, {0.0f, 0.0f, 0.0f}};
        for (int c = 0; c < width; ++c) out.value[std::size_t(c)] = tile.values[std::size_t(offset + c)];
        grid.tiles.push_back(out);
    }
    return grid;
}

void appendAttributeGrids(std::vector<VdbGrid>& grids, const SparseGrid& occupancy, const AttributeGrid& attributes) {
    if (attributes.empty()) return;
    if (attributes.color)
        grids.push_back(
            attributeGrid(occupancy, attributes, attributes.colorOffset(), "color", VdbValueType::Vec3f, "invariant"));
    if (attributes.alpha)
        grids.push_back(attributeGrid(occupancy, attributes, attributes.alphaOffset(), "alpha", VdbValueType::Float));
    if (attributes.normal)
        grids.push_back(attributeGrid(occupancy, attributes, attributes.normalOffset(), "normal", VdbValueType::Vec3f,
                                      "covariant normalize"));
}

VdbGrid levelSetGrid(const VoxelizeResult& result) {
    const LevelSetGrid& sdf = result.sdf;
    VdbGrid grid;
    grid.name = "sdf";
    grid.grid_class = "level set";
    grid.layout = VdbLeafValues::Packed;
    grid.background = sdf.background;
    const BrickLayout bricks = result.grid.bricks();
    auto originOf = [&](std::uint64_t brick) {
        const std::array<std::int32_t, 3> b = bricks.at(brick);
        return std::array<std::int32_t, 3>{b[0] * BrickLayout::kSide, b[1] * BrickLayout::kSide,
                                           b[2] * BrickLayout::kSide};
    };
    grid.leaves.reserve(sdf.leaves.size());
    for (const LevelSetGrid::Leaf& leaf : sdf.leaves)
        grid.leaves.push_back({originOf(leaf.brick), leaf.active, sdf.values.data() + leaf.first, leaf.inside});
    for (const SparseGrid::TileRun& run : sdf.inside_runs)
        for (std::uint64_t b = run.begin; b < run.end; ++b) {
            VdbTile tile{originOf(b), 1};
            tile.active = false;
            grid.tiles.push_back(tile);
        }
    return grid;
}

std::uint64_t fogGridMemUsageForLeaves(std::uint64_t leaves) {
    // The leaves dominate; the internal nodes above them add a few percent at most.
    return std::uint64_t(double(leaves) * double(kFloatTreeBytes.leaf) * 1.05);
}

std::uint64_t writeVdbGrids(std::ostream& out, const VoxelizeResult& result, const std::vector<VdbGrid>& grids,
                            int threads, Interrupter* interrupter, int progress_from, int progress_to) {
    Bytes file(0, &out);
    // Archive::writeHeader.
    file.pod(kMagic);
    file.pod(kFileVersion);
    file.pod(kLibraryMajor);
    file.pod(kLibraryMinor);
    file.pod(char(1));  // has grid offsets (a seekable file)
    file.raw(randomUuid().data(), 36);
    file.pod(std::uint32_t(0));  // file-level metadata: none
    file.pod(std::int32_t(grids.size()));
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    std::uint64_t mem_usage = 0;
    PlacedTree tree;
    for (std::size_t g = 0; g < grids.size(); ++g) {
        // The attribute grids share one set of leaves: they are placed (and sorted) once.
        if (g == 0 || !sameLeavesNoTiles(grids[g], grids[g - 1])) tree = placeTree(grids[g]);
        mem_usage += writeGrid(file, result, grids[g], tree, arena, [&](double fraction) {
            const double done = (double(g) + fraction) / double(grids.size());
            throwIfInterrupted(interrupter, progress_from + int(double(progress_to - progress_from) * done));
        });
    }
    file.flush();
    return mem_usage;
}

}  // namespace hyvox::vdb
