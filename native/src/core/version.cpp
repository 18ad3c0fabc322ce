// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/version.h"

namespace hyvox {

const char* version() { return HYVOX_VERSION_STRING; }

}  // namespace hyvox
