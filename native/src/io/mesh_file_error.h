// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// One wording for every mesh reader's errors: "mesh file 'PATH': WHAT".
#include <string>

#include "hyvox/errors.h"

namespace hyvox::io {

[[noreturn]] inline void failMeshFile(const std::string& path, const std::string& what) {
    throw InvalidInput("mesh file '" + path + "': " + what);
}

}  // namespace hyvox::io
