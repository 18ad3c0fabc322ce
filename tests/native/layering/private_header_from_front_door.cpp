// SPDX-License-Identifier: GPL-3.0-or-later
// A front door (the CLI, the Python module: they link hyvox_front_door) that includes a private
// header of the library: it must not compile; the same source linked with hyvox_lib, as the
// tests are, does.
#include <cstdio>

#include "mesh_io/mesh_formats.h"

int main() { return std::printf("%s\n", hyvox::mesh_io::offeredExtensions().c_str()) < 0; }
