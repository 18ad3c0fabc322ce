// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The tessellation shaders' binding points, included as C++ (the file holds only #defines).
#include "tessellation/bindings.glsl"
