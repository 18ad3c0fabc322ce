// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The split both bounding volume hierarchies of solid mode (fast winding numbers, the
// gradient bound's open edges) build with: half the items on each side of the median of
// their centres along the longest side of the node's box.
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace hyvox::solid {

// Reorders items [first, first + count) so that the lower count / 2 of them by
// `centre(item, axis)` come first, `axis` being the longest side of the box [lo, hi], items of
// equal centres ordered by `before` (a strict total order of the items). Returns count / 2.
// Which items go to which half is then the same with every standard library: nth_element
// leaves ties, and the order within each half, to the implementation, and the trees' sums
// (so the winding numbers' last bits, and a voxel whose number is 0.5 to within them)
// would differ between platforms.
template <typename Item, typename Centre, typename Before>
std::uint32_t splitAtMedian(std::vector<Item>& items, std::uint32_t first, std::uint32_t count,
                            const std::array<double, 3>& lo, const std::array<double, 3>& hi, Centre centre,
                            Before before) {
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
    const std::uint32_t half = count / 2;
    const auto begin = items.begin() + first;
    std::nth_element(begin, begin + half, begin + count, [&](const Item& x, const Item& y) {
        const double cx = centre(x, axis), cy = centre(y, axis);
        return cx < cy || (cx == cy && before(x, y));
    });
    return half;
}

}  // namespace hyvox::solid
