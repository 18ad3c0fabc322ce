// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The binding points and uniform locations of shaders/common/bindings.glsl: the same file,
// included as C++ (it holds only #defines), so the two sides cannot drift apart.
#include "common/bindings.glsl"
