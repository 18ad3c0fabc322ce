// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/plugin_fault.h"

namespace hyvox {

void throwPluginFault(const PluginFault& fault, const std::string& purpose) {
    using Kind = PluginFault::Kind;
    switch (fault.kind) {
        case Kind::None: return;
        case Kind::InvalidInput: throw InvalidInput(fault.message);
        case Kind::ResourceError: throw ResourceError(fault.message);
        case Kind::BackendError: throw BackendError(fault.message);
        case Kind::Cancelled: throw Cancelled();
        case Kind::OutOfMemory: throw ResourceError(purpose + " ran out of memory (" + fault.message + ")");
        case Kind::Other: throw BackendError(purpose + " failed: " + fault.message);
    }
}

}  // namespace hyvox
