// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// KHR_debug errors become exceptions: the driver's messages of type ERROR are collected
// synchronously (GL_DEBUG_OUTPUT_SYNCHRONOUS) on the GL thread and thrown by checkGl().

namespace hyvox::gl {

// Installs the collecting callback on the current context (GlWorker does this once).
void enableDebugOutput();

// Throws BackendError("<what>: <messages>") if the driver reported errors since the last
// check (KHR_debug messages or glGetError), and clears them.
void checkGl(const char* what);

}  // namespace hyvox::gl
