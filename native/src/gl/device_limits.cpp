// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/device_limits.h"

#include "gl/gl_limits.h"
#include "gl/gl_worker.h"

namespace hyvox::gl {

std::uint64_t maxStorageBlockBytes(const std::string& device) {
    return GlWorker::get(device).run([] { return std::uint64_t(glLimit(GL_MAX_SHADER_STORAGE_BLOCK_SIZE)); });
}

}  // namespace hyvox::gl
