// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// One 8³ leaf's attribute values, as a method (or the exact definition, src/attributes/)
// hands them to the dispatcher, which puts the leaves of all tiles in brick order
// (attributes::assembleAttributes).
#include <cstdint>
#include <memory>
#include <vector>

namespace hyvox {

// The values of one leaf's set voxels (ascending bit order), channels() each: in `values`, or
// `count` floats from `offset` of a `block` that a tile's leaves share (the cpu method writes
// its means there: no vector per leaf, and a block holding the whole grid's values in brick
// order becomes the result without a copy).
struct AttributeLeaf {
    std::uint64_t brick;  // BrickLayout::index of the whole grid
    std::vector<float> values;
    std::shared_ptr<std::vector<float>> block;
    std::size_t offset = 0, count = 0;

    std::size_t size() const { return block ? count : values.size(); }
    const float* data() const { return block ? block->data() + offset : values.data(); }
};

}  // namespace hyvox
