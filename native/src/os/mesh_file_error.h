// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// One wording for every mesh reader's errors: "mesh file 'PATH': WHAT". Here, below the
// readers (mesh_io/), because the file reads they use (file_bytes.h, mapped_file.h) word theirs so.
#include <string>

#include "hyvox/errors.h"

namespace hyvox::os {

[[noreturn]] inline void failMeshFile(const std::string& path, const std::string& what) {
    throw InvalidInput("mesh file '" + path + "': " + what);
}

}  // namespace hyvox::os
