// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// One 8³ leaf's attribute values, as a method (or the exact definition, src/attributes/)
// hands them to the dispatcher, which puts the leaves of all tiles in brick order
// (attributes::assembleAttributes).
#include <cstdint>
#include <vector>

namespace hyvox::attributes {

// The values of one leaf's set voxels (ascending bit order), channels() each.
struct AttributeLeaf {
    std::uint64_t brick;  // BrickLayout::index of the whole grid
    std::vector<float> values;
};

}  // namespace hyvox::attributes
