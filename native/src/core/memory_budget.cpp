// SPDX-License-Identifier: GPL-3.0-or-later
// The default memory budget: a share of the memory this process can have, read once.
#include <algorithm>
#include <cstdint>

#include "hyvox/options.h"
#include "os/system_memory.h"

namespace hyvox {
namespace {

// What the budget assumes of a system that does not say how much memory it has.
constexpr std::uint64_t kUnknownMemoryBytes = 8ull << 30;

}  // namespace

std::uint64_t defaultMemoryBudgetMib() {
    static const std::uint64_t mib = [] {
        const std::uint64_t available = os::availableMemoryBytes();
        return std::max<std::uint64_t>(256, ((available > 0 ? available : kUnknownMemoryBytes) / 2) >> 20);
    }();
    return mib;
}

}  // namespace hyvox
