// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// How much memory this process can have, for the default memory budget (core/memory_budget.cpp).
#include <cstdint>

namespace hyvox::os {

// The machine's physical memory, or a container's tighter limit on this process; 0 when the
// system does not say.
std::uint64_t availableMemoryBytes();

}  // namespace hyvox::os
