// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// The library's version.

namespace hyvox {

/// The project version from CMake, e.g. "0.1.0" (a static string).
const char* version();

}  // namespace hyvox
