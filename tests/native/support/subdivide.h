// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// CPU subdivision for tests and benchmarks: dense-mesh stand-ins (midpoint subdivision) and
// the reference for displacement voxelization (a mesh subdivided and displaced on the CPU,
// then voxelized exactly, to compare with the GPU's displaced points).
#include "hyvox/grid.h"
#include "hyvox/mesh.h"
#include "hyvox/mesh_io.h"
#include "hyvox/options.h"

namespace hyvox::test {

// Splits every triangle into four at its edge midpoints, `levels` times (4^levels triangles
// each); vertices on shared edges are shared. UVs are interpolated when present.
Mesh midpointSubdivide(const MeshView& mesh, int levels);

// Splits every usable triangle into pieces² sub-triangles, puts their vertices on the flat or
// PN surface (options.pn_triangles) and displaces them by the options' displacement map:
// the surface the tessellation method samples (support/surface_twin.h), as a world-space
// triangle soup.
Mesh subdivideAndDisplace(const ValidatedMesh& mesh, const GridSpec& grid, const TessellationOptions& options,
                          int pieces);

}  // namespace hyvox::test
