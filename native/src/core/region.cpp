// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/region.h"

#include <cctype>
#include <cstdlib>

#include "hyvox/errors.h"
#include "hyvox/option_schema.h"

namespace hyvox {
namespace {

// A whole number of at most five digits (kMaxRegions has four), no sign or space.
bool smallWholeNumber(const std::string& text, int& value) {
    if (text.empty() || text.size() > 5) return false;
    for (const char c : text)
        if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    value = std::atoi(text.c_str());
    return true;
}

bool parse(const std::string& text, RegionOptions& region) {
    if (text.empty()) {
        region = RegionOptions{};
        return true;
    }
    const std::size_t slash = text.find('/');
    if (slash == std::string::npos) return false;
    int index = 0, count = 0;
    if (!smallWholeNumber(text.substr(0, slash), index) || !smallWholeNumber(text.substr(slash + 1), count))
        return false;
    if (count < 1 || count > kMaxRegions || index >= count) return false;
    region.index = index;
    region.count = count;
    return true;
}

}  // namespace

std::array<std::int32_t, 3> RegionBox::brickLo() const {
    return {lo[0] / BrickLayout::kSide, lo[1] / BrickLayout::kSide, lo[2] / BrickLayout::kSide};
}

std::array<std::int32_t, 3> RegionBox::brickHi() const {
    const std::int32_t side = BrickLayout::kSide;
    return {(hi[0] + side - 1) / side, (hi[1] + side - 1) / side, (hi[2] + side - 1) / side};
}

RegionBox regionBox(const GridSpec& grid, const RegionOptions& region) {
    RegionBox box;
    box.hi = grid.dims;
    for (int a = 1; a < 3; ++a)
        if (grid.dims[a] > grid.dims[box.axis]) box.axis = a;
    if (region.whole()) return box;
    static const char* const kAxes[] = {"x", "y", "z"};
    const std::int64_t leaves = grid.bricks().counts[box.axis];
    if (region.count > leaves)
        throw InvalidInput("region " + formatRegion(region) + ": the " + grid.dimsText() + " grid has " +
                           std::to_string(leaves) + " leaves (8 voxels each) along its longest side (" +
                           kAxes[box.axis] + "), so it can be cut into at most " + std::to_string(leaves) + " regions");
    const std::int64_t first = std::int64_t(region.index) * leaves / region.count;
    const std::int64_t end = std::int64_t(region.index + 1) * leaves / region.count;
    box.lo[box.axis] = std::int32_t(first * BrickLayout::kSide);
    box.hi[box.axis] = std::min(std::int32_t(end * BrickLayout::kSide), grid.dims[box.axis]);
    return box;
}

std::string formatRegion(const RegionOptions& region) {
    if (region.whole()) return "";
    return std::to_string(region.index) + "/" + std::to_string(region.count);
}

bool isRegionText(const std::string& text) {
    RegionOptions ignored;
    return parse(text, ignored);
}

RegionOptions parseRegion(const std::string& text) {
    RegionOptions region;
    if (!parse(text, region)) checkOption(findOption("region"), text);  // refuses with the schema's message
    return region;
}

}  // namespace hyvox
