// SPDX-License-Identifier: GPL-3.0-or-later
// Backends not built yet answer with a clear error. Each backend's folder replaces its entry
// here as it lands.
#include "core/backends.h"
#include "hyvox/errors.h"

namespace hyvox {

void runCpuBackend(const BackendJob&, VoxelizeResult&) { throw BackendError("method 'cpu' is not built yet"); }
void runReferenceBackend(const BackendJob&, VoxelizeResult&) { throw BackendError("method 'reference' is not built yet"); }
void runGlBackend(const BackendJob& job, VoxelizeResult&) {
    throw BackendError(std::string("method '") + toString(job.options.method) + "' is not built yet");
}
void runTessellationBackend(const BackendJob&, VoxelizeResult&) {
    throw BackendError("method 'tessellation' is not built yet");
}

}  // namespace hyvox
