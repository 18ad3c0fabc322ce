// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// The exceptions every hyvox entry point may throw. Bindings map them to the host's own
/// errors (Python: ValueError / RuntimeError / hyvox.Cancelled); nothing aborts. Each message
/// is one line meant for the user (it names the option, file or limit concerned).
#include <stdexcept>
#include <string>

namespace hyvox {

/// The caller's input is wrong (NaN coordinates, bad indices, resolution out of range, ...).
struct InvalidInput : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};

/// The work would not fit (grid larger than the memory budget or a GPU limit).
struct ResourceError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// A backend cannot run here (no GL 4.5 device, shader compile failure, a missing plugin, ...).
struct BackendError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// The Interrupter asked to stop; partial results are discarded.
struct Cancelled : std::runtime_error {
    Cancelled() : std::runtime_error("voxelization cancelled") {}
};

}  // namespace hyvox
