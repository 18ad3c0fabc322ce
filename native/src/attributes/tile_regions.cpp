// SPDX-License-Identifier: GPL-3.0-or-later
#include "attributes/tile_regions.h"

#include <algorithm>
#include <unordered_map>

namespace hyvox::attributes {

using Int3 = std::array<std::int32_t, 3>;

TileRegions::TileRegions(const SparseGrid& solid, const std::vector<std::uint64_t>& valued_tile_bricks)
    : bricks_(solid.bricks()) {
    for (int a = 0; a < 3; ++a) nodes_[a] = (bricks_.counts[a] + kNodeBricks - 1) / kNodeBricks;
    node_of_.assign(std::size_t(nodes_[0]) * std::size_t(nodes_[1]) * std::size_t(nodes_[2]), -1);
    std::size_t v = 0;
    for (const SparseGrid::TileRun& run : solid.tileRuns())
        for (std::uint64_t b = run.begin; b < run.end; ++b) {
            while (v < valued_tile_bricks.size() && valued_tile_bricks[v] < b) ++v;
            if (v < valued_tile_bricks.size() && valued_tile_bricks[v] == b) continue;
            const Int3 at = bricks_.at(b);
            std::int32_t& slot = node_of_[nodeIndex(at[0] / kNodeBricks, at[1] / kNodeBricks, at[2] / kNodeBricks)];
            if (slot < 0) {
                slot = std::int32_t(node_.size());
                node_.emplace_back();
            }
            const int bit = slotInNode(at);
            node_[std::size_t(slot)].mask[std::size_t(bit >> 6)] |= std::uint64_t(1) << (bit & 63);
        }
    // 4096³ nodes wholly of whole 128³ nodes.
    std::unordered_map<std::uint64_t, std::uint32_t> whole_in_top;
    for (Node& node : node_) {
        int count = 0;
        for (std::uint64_t word : node.mask) count += popcount(word);
        node.whole = count == kNodeBricks * kNodeBricks * kNodeBricks;
    }
    forEachNode([&](const Int3& n, Node& node) {
        if (node.whole) ++whole_in_top[topKey(n)];
    });
    // Region ids node by node in node order, a node's bricks in slot order.
    std::unordered_map<std::uint64_t, std::int64_t> top_region;
    forEachNode([&](const Int3& n, Node& node) {
        if (node.whole && whole_in_top[topKey(n)] == std::uint32_t(kTopNodes * kTopNodes * kTopNodes)) {
            auto [it, fresh] = top_region.emplace(topKey(n), std::int64_t(regions_.size()));
            if (fresh) {
                const Int3 lo{n[0] / kTopNodes * kTopNodes * kNodeBricks, n[1] / kTopNodes * kTopNodes * kNodeBricks,
                              n[2] / kTopNodes * kTopNodes * kNodeBricks};
                regions_.push_back({lo, kTopNodes * kNodeBricks, 3});
            }
            node.base = it->second;
            return;
        }
        node.base = std::int64_t(regions_.size());
        if (node.whole) {
            regions_.push_back({{n[0] * kNodeBricks, n[1] * kNodeBricks, n[2] * kNodeBricks}, kNodeBricks, 2});
            return;
        }
        std::uint32_t before = 0;
        for (int w = 0; w < kNodeWords; ++w) {
            node.before[std::size_t(w)] = before;
            std::uint64_t word = node.mask[std::size_t(w)];
            before += std::uint32_t(popcount(word));
            while (word) {
                const int bit = w * 64 + __builtin_ctzll(word);
                word &= word - 1;
                regions_.push_back({{n[0] * kNodeBricks + (bit >> 8), n[1] * kNodeBricks + ((bit >> 4) & 15),
                                     n[2] * kNodeBricks + (bit & 15)},
                                    1,
                                    1});
            }
        }
    });
}

std::vector<std::int64_t> TileRegions::neighbours(std::int64_t r) const {
    const Region& region = regions_[std::size_t(r)];
    std::vector<std::int64_t> out;
    const Int3& lo = region.lo;
    const std::int32_t hi[3] = {lo[0] + region.side, lo[1] + region.side, lo[2] + region.side};
    for (std::int32_t x = lo[0] - 1; x <= hi[0]; ++x)
        for (std::int32_t y = lo[1] - 1; y <= hi[1]; ++y) {
            const bool inner = x >= lo[0] && x < hi[0] && y >= lo[1] && y < hi[1];
            for (std::int32_t z = lo[2] - 1; z <= hi[2]; z = inner && z == lo[2] - 1 ? hi[2] : z + 1) {
                const std::int64_t id = at(x, y, z);
                if (id >= 0 && id != r && (out.empty() || out.back() != id)) out.push_back(id);
            }
        }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

}  // namespace hyvox::attributes
