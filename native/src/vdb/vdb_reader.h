// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// .vdb files read without OpenVDB: the counterpart of vdb_direct_writer.h, for `hyvox merge`
// (hyvox/vdb_merge.h, vdb_merge.cpp).
//
// Reads what OpenVDB's own readers read of these: file version 222 and later (OpenVDB 3 on;
// OpenVDB 10 writes 224), float and Vec3f 5-4-3 trees (Tree_float_5_4_3, Tree_vec3s_5_4_3),
// uncompressed, zip or blosc, with or without active-mask compression, with every way of
// storing inactive values OpenVDB writes (a level set's -background inside, one or two other
// values and the mask that picks between them). Refused with InvalidInput, naming the file
// and what is wrong: other tree types, half floats, instanced grids, files written to a stream
// without grid offsets, and anything truncated or inconsistent.
//
// A leaf keeps its mask and its active values only (packed in mask order, the layout of
// VdbLeafValues::Packed), and its inactive values only where they are not the background (a
// level set's inside): memory follows the active voxels, as in a voxelization's own result,
// not OpenVDB's 512 values a leaf.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "hyvox/interrupter.h"
#include "vdb/vdb_direct_writer.h"  // VdbValueType, VdbTile

namespace hyvox::vdb {

// One metadata entry as OpenVDB's MetaMap stores it: name, type name and value bytes.
struct VdbMetaEntry {
    std::string name, type, bytes;
};

struct VdbReadGrid {
    struct Leaf {
        std::array<std::int32_t, 3> origin;
        std::uint64_t mask[8];       // OpenVDB's NodeMask<3> words
        std::uint64_t first = 0;     // its first active value, in voxels, in `values`
        std::int64_t inactive = -1;  // its 512 inactive-or-not values in `inactive_values`, or -1: all background
    };

    std::string name;
    VdbValueType type = VdbValueType::Float;
    std::vector<VdbMetaEntry> metadata;  // in file order (by name)
    std::string transform;               // the map's type name, then its bytes, as stored
    std::array<float, 3> background{};   // channels() used
    std::vector<Leaf> leaves;            // in file order
    // channels() floats per active leaf voxel, leaf after leaf; left empty while every active
    // leaf value is `uniform_value` (a density grid: all 1).
    std::vector<float> values;
    bool uniform = true;
    std::array<float, 3> uniform_value{};
    std::vector<float> inactive_values;   // 512 × channels() floats per leaf with Leaf::inactive >= 0
    std::vector<VdbTile> tiles;           // active tiles
    std::vector<VdbTile> inactive_tiles;  // inactive tiles whose value is not the background

    int channels() const { return type == VdbValueType::Float ? 1 : 3; }
    std::uint64_t activeLeafVoxels() const;
    // The metadata entry `name`, or null.
    const VdbMetaEntry* meta(const std::string& name) const;
    // A string entry's text ("" when absent or not a string).
    std::string metaText(const std::string& name) const;
};

struct VdbFile {
    std::uint32_t version = 0;           // the file format version
    std::vector<VdbMetaEntry> metadata;  // the file's own
    std::vector<VdbReadGrid> grids;      // in file order
};

// `interrupter` (may be null) is asked between leaves; hyvox::Cancelled stops the reading.
VdbFile readVdbFile(const std::string& path, Interrupter* interrupter = nullptr);

}  // namespace hyvox::vdb
