// SPDX-License-Identifier: GPL-3.0-or-later
// OpenVDB's file layout for a float 5-4-3 tree, written without OpenVDB (see the header).
// Byte order and field order follow openvdb::io::Archive::write (file version 224): the
// header, the file metadata, the grid descriptor with its stream offsets, the grid's
// compression flags, its metadata (sorted by name, as a MetaMap), its transform, the tree
// topology (root, 32³ and 16³ internal nodes with their masks, the leaves' masks) and the
// leaf buffers. Every integer is little-endian, as OpenVDB writes them on x86 and ARM.
#include "io/vdb_direct_writer.h"

#include <blosc.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "hyvox/version.h"

namespace hyvox::io {
namespace {

constexpr std::int64_t kMagic = 0x56444220;  // OPENVDB_MAGIC
constexpr std::uint32_t kFileVersion = 224;  // OPENVDB_FILE_VERSION of OpenVDB 10
constexpr std::uint32_t kLibraryMajor = 10, kLibraryMinor = 0;
// io::COMPRESS_ACTIVE_MASK | io::COMPRESS_BLOSC, OpenVDB 10's default for every grid: each node
// stores its active values only, as one blosc block.
constexpr std::uint32_t kCompressActiveMask = 0x2, kCompressBlosc = 0x4;
constexpr std::uint32_t kCompression = kCompressActiveMask | kCompressBlosc;
constexpr std::int8_t kNoMaskOrInactiveVals = 0;    // every inactive value is the background

// Node geometry of Tree_float_5_4_3: a leaf spans 8 voxels per axis, a lower internal node
// 16 leaves (128 voxels), an upper internal node 32 lower nodes (4096 voxels).
constexpr int kLeafLog2 = 3, kLowerLog2 = 4, kUpperLog2 = 5;
constexpr int kLowerTotal = kLeafLog2 + kLowerLog2;  // 7
constexpr int kUpperTotal = kLowerTotal + kUpperLog2;  // 12
constexpr std::size_t kLowerWords = (std::size_t(1) << (3 * kLowerLog2)) / 64;  // 64
constexpr std::size_t kUpperWords = (std::size_t(1) << (3 * kUpperLog2)) / 64;  // 512
constexpr std::size_t kLeafMaskBytes = 8 * sizeof(std::uint64_t);

// OpenVDB's memUsage() terms for this tree type (values checked against OpenVDB by a test):
// the empty tree and root, each leaf (node + 512 floats), each internal node (its table of
// 8-byte unions, two masks and an origin).
constexpr std::uint64_t kEmptyTreeBytes = 1304;
constexpr std::uint64_t kLeafBytes = 96 + 512 * sizeof(float);
constexpr std::uint64_t kLowerBytes = 4096 * 8 + 2 * 512 + 12;
constexpr std::uint64_t kUpperBytes = 32768 * 8 + 2 * 4096 + 12;

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

// Appends to a growing byte string (the small parts: header, metadata, topology) that
// will start at file position `base`: size() is the file position of the next byte.
class Bytes {
public:
    explicit Bytes(std::size_t base = 0) : base_(base) {}
    template <typename T>
    void pod(const T& value) {
        out_.append(reinterpret_cast<const char*>(&value), sizeof value);
    }
    void raw(const void* data, std::size_t size) { out_.append(static_cast<const char*>(data), size); }
    // io::writeString: a 32-bit length, then the characters.
    void string(const std::string& text) {
        pod(std::uint32_t(text.size()));
        out_ += text;
    }
    void blosc(const void* data, std::size_t bytes) { appendBlosc(out_, data, bytes); }
    std::size_t size() const { return base_ + out_.size(); }
    const std::string& str() const { return out_; }
    template <typename T>
    void patch(std::size_t at, const T& value) {
        std::memcpy(&out_[at - base_], &value, sizeof value);
    }

private:
    std::size_t base_;
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

// A leaf's place in the tree's write order: upper node (by origin, as the root's std::map of
// Coords sorts them), then lower node and leaf by their offsets in the parents' tables.
struct Placed {
    std::uint64_t upper;  // x, y, z of the upper node, 21 bits each (grid coordinates are >= 0)
    std::uint32_t inner;  // lower node's offset in the upper (15 bits) and leaf's in the lower (12)
    const FogLeaf* leaf;
};

int tableOffset(const std::array<std::int32_t, 3>& at, int node_total, int child_total, int log2) {
    const int mask = (1 << node_total) - 1;
    return (((at[0] & mask) >> child_total) << (2 * log2)) + (((at[1] & mask) >> child_total) << log2) +
           ((at[2] & mask) >> child_total);
}

std::vector<Placed> placeLeaves(const std::vector<FogLeaf>& leaves) {
    std::vector<Placed> placed;
    placed.reserve(leaves.size());
    for (const FogLeaf& leaf : leaves) {
        const std::array<std::int32_t, 3>& o = leaf.origin;
        Placed p;
        p.upper = (std::uint64_t(o[0] >> kUpperTotal) << 42) | (std::uint64_t(o[1] >> kUpperTotal) << 21) |
                  std::uint64_t(o[2] >> kUpperTotal);
        p.inner = std::uint32_t(tableOffset(o, kUpperTotal, kLowerTotal, kUpperLog2)) << 12 |
                  std::uint32_t(tableOffset(o, kLowerTotal, kLeafLog2, kLowerLog2));
        p.leaf = &leaf;
        placed.push_back(p);
    }
    std::sort(placed.begin(), placed.end(), [](const Placed& a, const Placed& b) {
        return a.upper != b.upper ? a.upper < b.upper : a.inner < b.inner;
    });
    return placed;
}

// Grid::memUsage() of the tree holding these leaves.
std::uint64_t memUsage(const std::vector<Placed>& placed) {
    std::uint64_t uppers = 0, lowers = 0;
    for (std::size_t n = 0; n < placed.size(); ++n) {
        const bool new_upper = n == 0 || placed[n].upper != placed[n - 1].upper;
        uppers += new_upper;
        lowers += new_upper || (placed[n].inner >> 12) != (placed[n - 1].inner >> 12);
    }
    return kEmptyTreeBytes + placed.size() * kLeafBytes + lowers * kLowerBytes + uppers * kUpperBytes;
}

std::uint64_t activeCount(const FogLeaf& leaf) {
    std::uint64_t n = 0;
    for (int w = 0; w < 8; ++w) n += std::uint64_t(__builtin_popcountll(leaf.mask[w]));
    return n;
}

std::map<std::string, MetaValue> gridMetadata(const VoxelizeResult& result, const FogGrid& fog, std::uint64_t mem_usage) {
    // Grid::evalActiveVoxelBoundingBox(); an empty grid's is CoordBBox(): min INT_MAX, max INT_MIN.
    std::array<std::int32_t, 3> lo{INT_MAX, INT_MAX, INT_MAX}, hi{INT_MIN, INT_MIN, INT_MIN};
    std::uint64_t voxels = 0;
    for (const FogLeaf& leaf : fog.leaves) {
        voxels += activeCount(leaf);
        // Word x holds the voxels of x; bit y * 8 + z. Folding the words gives the y and z
        // ranges: byte y of the OR is non-zero where row y has a voxel, the OR of its bytes
        // has bit z set where column z has one.
        std::uint64_t any = 0;
        for (int x = 0; x < 8; ++x) {
            if (!leaf.mask[x]) continue;
            any |= leaf.mask[x];
            lo[0] = std::min(lo[0], leaf.origin[0] + x), hi[0] = std::max(hi[0], leaf.origin[0] + x);
        }
        if (!any) continue;
        const int y0 = __builtin_ctzll(any) >> 3, y1 = (63 - __builtin_clzll(any)) >> 3;
        std::uint64_t columns = any;
        columns |= columns >> 32, columns |= columns >> 16, columns |= columns >> 8;
        const unsigned z_bits = unsigned(columns & 0xff);
        const int z0 = __builtin_ctz(z_bits), z1 = 31 - __builtin_clz(z_bits);
        lo[1] = std::min(lo[1], leaf.origin[1] + y0), hi[1] = std::max(hi[1], leaf.origin[1] + y1);
        lo[2] = std::min(lo[2], leaf.origin[2] + z0), hi[2] = std::max(hi[2], leaf.origin[2] + z1);
    }
    const GridSpec& grid = result.grid;
    std::map<std::string, MetaValue> meta;
    meta["class"] = metaString("fog volume");
    meta["creator"] = metaString(std::string("hyvox ") + version());
    meta["file_bbox_min"] = metaOf("vec3i", lo);
    meta["file_bbox_max"] = metaOf("vec3i", hi);
    meta["file_compression"] = metaString("blosc + active values");  // io::compressionToString
    meta["file_mem_bytes"] = metaInt64(std::int64_t(mem_usage));
    meta["file_voxel_count"] = metaInt64(std::int64_t(voxels));
    meta["name"] = metaString(fog.name);
    // The hyvox_* entries, as addMetadata() in vdb_grid.cpp writes them.
    meta["hyvox_version"] = metaString(version());
    meta["hyvox_method"] = metaString(result.stats.method);
    meta["hyvox_mode"] = metaString(result.stats.mode);
    meta["hyvox_voxel_size"] = metaDouble(grid.voxel_size);
    meta["hyvox_origin"] = metaOf("vec3d", grid.origin);
    meta["hyvox_dims"] = metaOf("vec3i", grid.dims);
    return meta;
}

// Transform::write of createLinearTransform(s) post-translated to the first voxel's centre:
// the map's type name, then ScaleTranslateMap's six Vec3d, computed as OpenVDB computes them.
void writeTransform(Bytes& out, const GridSpec& grid) {
    out.string("UniformScaleTranslateMap");
    const double s = grid.voxel_size, h = 0.5 * grid.voxel_size;
    const double inverse = 1.0 / s;
    // translation, then scale, voxel size, 1/scale, 1/scale², 1/(2 scale), each a Vec3d
    for (int a = 0; a < 3; ++a) out.pod(grid.origin[a] + h);
    for (const double v : {s, std::abs(s), inverse, inverse * inverse, inverse / 2})
        for (int a = 0; a < 3; ++a) out.pod(v);
}

// Root, upper and lower nodes and the leaves' masks, in OpenVDB's order (RootNode,
// InternalNode and LeafNode::writeTopology). Internal nodes hold no tiles: their values
// are all the background, so each writes its two masks, the metadata byte and an empty
// blosc block (no active values).
void writeTopology(Bytes& out, const std::vector<Placed>& placed) {
    out.pod(std::int32_t(1));  // TreeBase::writeTopology: buffer count
    out.pod(0.0f);             // background
    std::uint32_t uppers = 0;
    for (std::size_t n = 0; n < placed.size(); ++n) uppers += n == 0 || placed[n].upper != placed[n - 1].upper;
    out.pod(std::uint32_t(0));  // tiles
    out.pod(uppers);
    const std::vector<std::uint64_t> no_values_upper(kUpperWords, 0), no_values_lower(kLowerWords, 0);
    std::size_t n = 0;
    while (n < placed.size()) {
        const std::size_t upper_end =
            std::size_t(std::find_if(placed.begin() + long(n), placed.end(),
                                     [&](const Placed& p) { return p.upper != placed[n].upper; }) -
                        placed.begin());
        const int upper_mask = ~((1 << kUpperTotal) - 1);
        for (int a = 0; a < 3; ++a) out.pod(std::int32_t(placed[n].leaf->origin[a] & upper_mask));
        std::vector<std::uint64_t> children(kUpperWords, 0);
        for (std::size_t m = n; m < upper_end; ++m) {
            const std::uint32_t lower = placed[m].inner >> 12;
            children[lower >> 6] |= std::uint64_t(1) << (lower & 63);
        }
        out.raw(children.data(), kUpperWords * 8);
        out.raw(no_values_upper.data(), kUpperWords * 8);
        out.pod(kNoMaskOrInactiveVals);
        out.blosc(nullptr, 0);
        while (n < upper_end) {
            const std::uint32_t lower = placed[n].inner >> 12;
            std::size_t lower_end = n;
            std::vector<std::uint64_t> leaves(kLowerWords, 0);
            for (; lower_end < upper_end && (placed[lower_end].inner >> 12) == lower; ++lower_end) {
                const std::uint32_t at = placed[lower_end].inner & 0xfff;
                leaves[at >> 6] |= std::uint64_t(1) << (at & 63);
            }
            out.raw(leaves.data(), kLowerWords * 8);
            out.raw(no_values_lower.data(), kLowerWords * 8);
            out.pod(kNoMaskOrInactiveVals);
            out.blosc(nullptr, 0);
            for (; n < lower_end; ++n) out.raw(placed[n].leaf->mask, kLeafMaskBytes);
        }
    }
}


// Leaves per block of buffers compressed by one task.
constexpr std::size_t kLeavesPerBlock = 256;

// LeafNode::writeBuffers for placed[first, last): per leaf its mask, the metadata byte and
// its active values as a blosc block.
std::string leafBuffers(const std::vector<Placed>& placed, std::size_t first, std::size_t last) {
    std::string out;
    float active[512];
    for (std::size_t n = first; n != last; ++n) {
        const FogLeaf& leaf = *placed[n].leaf;
        out.append(reinterpret_cast<const char*>(leaf.mask), kLeafMaskBytes);
        out += char(kNoMaskOrInactiveVals);
        std::size_t count = 0;
        for (int w = 0; w < 8; ++w)
            for (std::uint64_t bits = leaf.mask[w]; bits; bits &= bits - 1)
                active[count++] = leaf.values ? leaf.values[w * 64 + __builtin_ctzll(bits)] : 1.0f;
        appendBlosc(out, active, count * sizeof(float));
    }
    return out;
}

// One grid as Archive::writeGrid lays it out: `head` gets the descriptor, compression,
// metadata, transform and topology; `buffers` the leaf buffers that follow them, compressed
// in parallel in blocks of kLeavesPerBlock leaves.
struct GridLayout {
    std::uint64_t mem_usage = 0;
    std::vector<std::string> buffers;
    std::size_t end = 0;  // file position after the grid
};

GridLayout layOutGrid(Bytes& head, const VoxelizeResult& result, const FogGrid& fog, tbb::task_arena& arena) {
    GridLayout layout;
    const std::vector<Placed> placed = placeLeaves(fog.leaves);
    // GridDescriptor::writeHeader and writeStreamPos (patched below).
    head.string(fog.name);
    head.string("Tree_float_5_4_3");
    head.string("");  // not an instance
    const std::size_t stream_pos_at = head.size();
    for (int i = 0; i < 3; ++i) head.pod(std::int64_t(0));
    const std::int64_t grid_pos = std::int64_t(head.size());
    head.pod(kCompression);
    layout.mem_usage = memUsage(placed);
    const std::map<std::string, MetaValue> meta = gridMetadata(result, fog, layout.mem_usage);
    head.pod(std::uint32_t(meta.size()));
    for (const auto& [name, value] : meta) {
        head.string(name);
        head.string(value.type);
        head.string(value.bytes);  // Metadata::write: 32-bit size, then the value's bytes
    }
    writeTransform(head, result.grid);
    writeTopology(head, placed);
    const std::int64_t block_pos = std::int64_t(head.size());
    layout.buffers.resize((placed.size() + kLeavesPerBlock - 1) / kLeavesPerBlock);
    arena.execute([&] {
        tbb::parallel_for(std::size_t(0), layout.buffers.size(), [&](std::size_t b) {
            layout.buffers[b] = leafBuffers(placed, b * kLeavesPerBlock, std::min(placed.size(), (b + 1) * kLeavesPerBlock));
        });
    });
    layout.end = std::size_t(block_pos);
    for (const std::string& buffer : layout.buffers) layout.end += buffer.size();
    head.patch(stream_pos_at, grid_pos);
    head.patch(stream_pos_at + 8, block_pos);
    head.patch(stream_pos_at + 16, std::int64_t(layout.end));
    return layout;
}

}  // namespace

std::vector<FogLeaf> densityLeaves(const SparseGrid& occupancy) {
    const BrickLayout& bricks = occupancy.bricks();
    std::vector<FogLeaf> leaves;
    leaves.reserve(occupancy.leaves().size());
    for (const SparseGrid::Leaf& leaf : occupancy.leaves()) {
        const std::array<std::int32_t, 3> b = bricks.at(leaf.brick);
        leaves.push_back({{b[0] * BrickLayout::kSide, b[1] * BrickLayout::kSide, b[2] * BrickLayout::kSide}, leaf.words, nullptr});
    }
    return leaves;
}

std::uint64_t fogTreeMemUsage(const std::vector<FogLeaf>& leaves) { return memUsage(placeLeaves(leaves)); }

std::uint64_t fogGridMemUsageForLeaves(std::uint64_t leaves) {
    // The leaves dominate; the internal nodes above them add a few percent at most.
    return std::uint64_t(double(leaves) * double(kLeafBytes) * 1.05);
}

VdbBytes serializeFogGrids(const VoxelizeResult& result, const std::vector<FogGrid>& grids, int threads) {
    Bytes head;
    // Archive::writeHeader.
    head.pod(kMagic);
    head.pod(kFileVersion);
    head.pod(kLibraryMajor);
    head.pod(kLibraryMinor);
    head.pod(char(1));  // has grid offsets (a seekable file)
    head.raw(randomUuid().data(), 36);
    head.pod(std::uint32_t(0));  // file-level metadata: none
    head.pod(std::int32_t(grids.size()));
    // Each grid's header parts follow the previous grid's buffers: lay them out one after
    // the other, each `head` shifted by the bytes before it.
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    std::vector<GridLayout> layouts;
    std::vector<Bytes> heads;
    std::size_t offset = head.size();
    for (const FogGrid& fog : grids) {
        heads.emplace_back(offset);
        layouts.push_back(layOutGrid(heads.back(), result, fog, arena));
        offset = layouts.back().end;
    }
    VdbBytes file;
    for (const GridLayout& layout : layouts) file.mem_usage += layout.mem_usage;
    file.size = offset;
    file.data.reset(new char[file.size]);
    char* at = file.data.get();
    at = std::copy(head.str().begin(), head.str().end(), at);
    for (std::size_t g = 0; g < grids.size(); ++g) {
        at = std::copy(heads[g].str().begin(), heads[g].str().end(), at);
        for (const std::string& buffer : layouts[g].buffers) at = std::copy(buffer.begin(), buffer.end(), at);
    }
    return file;
}

}  // namespace hyvox::io
