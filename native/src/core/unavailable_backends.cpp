// SPDX-License-Identifier: GPL-3.0-or-later
// Backends not built yet answer with a clear error. Each backend's folder replaces its entry
// here as it lands.
#include "core/backends.h"
#include "hyvox/errors.h"

namespace hyvox {


}  // namespace hyvox
