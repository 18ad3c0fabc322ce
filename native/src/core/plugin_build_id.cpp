// SPDX-License-Identifier: GPL-3.0-or-later
// Compiled into every plugin (hyvox_plugin() in CMakeLists.txt), not taken from hyvox_core:
// the plugins hide what their static libraries define, and this symbol must be seen.
#include "core/plugin_library.h"
#include "hyvox_build_id.h"

extern "C" HYVOX_PLUGIN_ENTRY const char hyvox_plugin_build_id[] = HYVOX_BUILD_ID;
