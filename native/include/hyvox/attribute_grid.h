// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Attribute voxels (DESIGN.md, "Attributes"): for each occupied voxel, the area-weighted mean
// of the surface's colour and normal inside its closed box. Values are held per occupied
// voxel in the order of SparseGrid::coords() (leaf by leaf in brick order, the set bits of a
// leaf in ascending order), so they stay as sparse as the voxels.
#include <cstddef>
#include <string>
#include <vector>

namespace hyvox {

// Which attributes a run computes: the option `attributes`, a comma list of "color" and
// "normal" ("" = none).
struct AttributeSet {
    bool color = false;
    bool normal = false;
    bool any() const { return color || normal; }
};
// Throws InvalidInput naming the accepted names for anything else.
AttributeSet parseAttributeSet(const std::string& text);

struct AttributeGrid {
    bool color = false;   // channels 0..2: linear RGB
    bool alpha = false;   // then alpha (when the colour source has it)
    bool normal = false;  // then a unit normal (zero where the normals cancel)
    std::vector<float> values;  // channels() per occupied voxel, in coords() order

    int channels() const { return (color ? 3 : 0) + (alpha ? 1 : 0) + (normal ? 3 : 0); }
    bool empty() const { return channels() == 0; }
    std::size_t voxelCount() const { return empty() ? 0 : values.size() / std::size_t(channels()); }
    int colorOffset() const { return 0; }
    int alphaOffset() const { return color ? 3 : 0; }
    int normalOffset() const { return (color ? 3 : 0) + (alpha ? 1 : 0); }
};

}  // namespace hyvox
