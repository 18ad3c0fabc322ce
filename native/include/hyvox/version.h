// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

namespace hyvox {

// The project version from CMake, e.g. "0.1.0".
const char* version();

}  // namespace hyvox
