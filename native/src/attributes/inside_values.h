// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Attribute values of a solid's inside voxels (solid mode with the option `attributes`).
//
// The definition, which every method, thread count and tiling gives alike:
//  - Surface voxels (the surface pass's voxels: the conservative surface, or the tessellation's
//    points) keep the values the method's attribute pass gave them (docs/design.md, "Attributes").
//  - Inside voxels held voxel by voxel ("leaf voxels": those of the bricks the result holds as
//    leaves, and of whole bricks that hold surface voxels) are valued by layers from the
//    surface inward. Layer 0 = the surface voxels. Layer k = the leaf voxels not yet valued
//    that have at least one 26-neighbour valued in a layer < k; the value = the plain mean of
//    those neighbours' values (normal: the mean, then normalised, zero when it cancels:
//    meanOfSums; alpha like colour).
//  - Every other inside brick is a tile. Tiles are grouped into regions as OpenVDB's prune()
//    groups the density's tiles (an 8³ brick, a 128³ node wholly tiles, a 4096³ node wholly
//    such nodes), and each region holds one value, so memory follows the surface. Region
//    layer 0: the regions with valued leaf voxels in their shell (the voxels outside the
//    region's box within one voxel of it: its 26-neighbourhood), valued by the plain mean of
//    those voxels, after the leaf layers. Region layer k: the regions not yet valued that
//    touch (by a face, edge or corner) a region valued in a layer < k: the plain mean of those
//    regions' values, each region counted once.
//  - Leaf voxels the leaf layers could not reach (their leaves touch the surface only through
//    tiles: only where the winding number bridges a hole) continue the leaf layers with the
//    regions' voxels as valued neighbours (a region's voxel holds the region's value).
//  - Whatever is still without a value (an inside part that touches nothing valued; not
//    expected for a connected inside) gets the mesh's mean: each triangle's value at its
//    centroid, weighted by its area. Counted in `fallback`.
// Each value depends only on values of earlier layers, summed in a fixed order (the 26
// neighbours in (dx, dy, dz) order; regions by id): the result does not depend on threads.
#include <cstdint>
#include <vector>

#include "attributes/surface_values.h"
#include "hyvox/attribute_grid.h"
#include "hyvox/mesh.h"
#include "hyvox/sparse_grid.h"

namespace hyvox::attributes {

struct InsideValueCounts {
    std::uint64_t voxels = 0;           // inside leaf voxels valued by the leaf layers
    std::uint64_t layers = 0;           // leaf layers run (the deepest leaf voxel's layer)
    std::uint64_t regions = 0;          // tile regions (one value each)
    std::uint64_t region_layers = 0;    // region layers after layer 0
    std::uint64_t through_regions = 0;  // leaf voxels valued next to regions (second leaf pass)
    std::uint64_t fallback = 0;         // leaf voxels and regions given the mesh's mean
};

// `surface`: the surface pass's voxels (finished); `surface_values`: their values, every brick
// valued voxel by voxel (coords() order of `surface`); `solid`: the result's voxels (finished,
// a superset of `surface`). `mesh_mean`: channels() values for the fallback. Returns the
// attribute grid of `solid` (values, valued_tile_bricks, tiles). `threads`: 0 = all.
AttributeGrid valueInside(const SparseGrid& surface, const AttributeGrid& surface_values, const SparseGrid& solid,
                          const std::vector<float>& mesh_mean, int threads, InsideValueCounts& counts);

// The mesh's mean attribute value: each usable triangle's value at its centroid weighted by its
// area (normal: the mean normalised).
std::vector<float> meshMeanValue(const ValidatedMesh& mesh, const SurfaceValues& values);

}  // namespace hyvox::attributes
