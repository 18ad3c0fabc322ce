// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Comparing a grid read from the direct writer's .vdb with one read from OpenVDB's own
// file (test_io_vdb_direct*.cpp): header-only, as it is templated on the grid type.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <string>

namespace hyvox::test {

// The grid `name` of the .vdb at `path`, or null when it is not of type GridT.
template <typename GridT>
typename GridT::Ptr readVdbGrid(const std::string& path, const std::string& name) {
    openvdb::io::File file(path);
    file.open();
    auto grid = openvdb::gridPtrCast<GridT>(file.readGrid(name));
    file.close();
    return grid;
}

// The same grid: background, class, vector type, name, transform, tree shape and memory,
// every leaf's mask and values, every tile's value, state and level (the inactive ones of a
// level set's inside too), and the same metadata (but OpenVDB's optional
// "file_delayed_load", which the direct writer leaves out).
template <typename GridT>
void expectSameGrids(const GridT& direct, const GridT& reference) {
    EXPECT_EQ(direct.background(), reference.background());
    EXPECT_EQ(direct.getGridClass(), reference.getGridClass());
    EXPECT_EQ(direct.getVectorType(), reference.getVectorType());
    EXPECT_EQ(direct.getName(), reference.getName());
    EXPECT_EQ(direct.transform(), reference.transform());
    EXPECT_EQ(direct.tree().nodeCount(), reference.tree().nodeCount());
    EXPECT_EQ(direct.tree().leafCount(), reference.tree().leafCount());
    EXPECT_EQ(direct.tree().activeTileCount(), reference.tree().activeTileCount());
    EXPECT_EQ(direct.activeVoxelCount(), reference.activeVoxelCount());
    EXPECT_EQ(direct.memUsage(), reference.memUsage());
    for (auto leaf = reference.tree().cbeginLeaf(); leaf; ++leaf) {
        const auto* other = direct.tree().probeConstLeaf(leaf->origin());
        ASSERT_NE(other, nullptr) << leaf->origin();
        EXPECT_EQ(other->getValueMask(), leaf->getValueMask()) << leaf->origin();
        for (openvdb::Index n = 0; n < 512; ++n) ASSERT_EQ(other->getValue(n), leaf->getValue(n)) << leaf->origin();
    }
    // Every active tile: same value, active, at the same level.
    for (auto it = reference.tree().cbeginValueOn(); it; ++it) {
        if (!it.isTileValue()) continue;
        const openvdb::Coord at = it.getCoord();
        EXPECT_EQ(direct.tree().getValue(at), *it) << at;
        EXPECT_TRUE(direct.tree().isValueOn(at)) << at;
        EXPECT_EQ(direct.tree().getValueDepth(at), reference.tree().getValueDepth(at)) << at;
    }
    // Every inactive tile (a level set's -background inside; the background elsewhere).
    for (auto it = reference.tree().cbeginValueOff(); it; ++it) {
        if (!it.isTileValue()) continue;
        const openvdb::Coord at = it.getCoord();
        ASSERT_EQ(direct.tree().getValue(at), *it) << at;
        EXPECT_FALSE(direct.tree().isValueOn(at)) << at;
    }
    for (auto it = reference.beginMeta(); it != reference.endMeta(); ++it) {
        if (it->first == "file_delayed_load") continue;
        const auto mine = direct[it->first];
        ASSERT_TRUE(mine) << it->first;
        EXPECT_EQ(mine->typeName(), it->second->typeName()) << it->first;
        EXPECT_EQ(mine->str(), it->second->str()) << it->first;
    }
    for (auto it = direct.beginMeta(); it != direct.endMeta(); ++it)
        EXPECT_TRUE(reference[it->first]) << "extra metadata " << it->first;
}

}  // namespace hyvox::test
