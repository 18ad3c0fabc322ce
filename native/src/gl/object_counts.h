// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Counts of the GL object names alive in the process, by kind (a diagnostic: the soak test
// checks they stay flat over hundreds of runs). Kept by the RAII owners of gl_objects.h.
#include <atomic>

namespace hyvox::gl {

enum class GlKind { Buffer, VertexArray, Framebuffer, Program, Shader, Query, Count };

inline std::atomic<long> object_counts[int(GlKind::Count)];

inline void countCreated(GlKind kind) { object_counts[int(kind)].fetch_add(1, std::memory_order_relaxed); }
inline void countDeleted(GlKind kind) { object_counts[int(kind)].fetch_sub(1, std::memory_order_relaxed); }

}  // namespace hyvox::gl
