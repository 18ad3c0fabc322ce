// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Limits of a GL device that callers outside the GL worker plan with (the dispatcher sizes
// the tessellation's tiles by them).
#include <cstdint>
#include <string>

namespace hyvox::gl {

// GL_MAX_SHADER_STORAGE_BLOCK_SIZE of the device `device` selects (GlOptions::device): the
// largest bit grid one storage buffer holds. Starts the device's GL worker if needed.
std::uint64_t maxStorageBlockBytes(const std::string& device);

}  // namespace hyvox::gl
