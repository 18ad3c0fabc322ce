# SPDX-License-Identifier: GPL-3.0-or-later
"""How dense a hyvox volume renders, decided without bpy, so that its look does not depend
on the resolution it was made at.

The `density` grid is 1 in every occupied voxel. The volume's material (its Density, set by
each run unless the artist changed it: blender/volume/material.py) multiplies it by:

- A filled (solid) volume gets a density in world units: SOLID_MEAN_FREE_PATHS mean free
  paths across the longest side of what was voxelized, the same at every resolution (and for
  an object of any size: a small object looks as solid as a large one).
- A surface (conservative or thin) is a shell about one voxel thick: its density is per voxel
  layer, SHELL_DEPTH_PER_LAYER optical depths each, so that the shell absorbs the same at every
  resolution (a density in world units would make the shell fainter as its voxels get finer).

The material's Color (the volume's scattering albedo) comes from the surface colour c the
`color` grid holds, in two steps:
- c = color / density. Blender interpolates both grids between voxel centres, and at the
  surface both fall toward zero (the background) with the same weights, so the `color` grid
  alone darkens the outer half voxel (a colour volume rendered darker than the same volume
  without colour); divided by the density it keeps the surface's colour there.
- albedo = 4 c / (1 + c)^2: the single-scattering albedo whose thick medium reflects c
  diffusely by two-flux (Kubelka-Munk) theory, the inverse of R = (1 - sqrt(1 - a)) /
  (1 + sqrt(1 - a)). With the colour itself as the albedo, light scattered many times inside
  comes out darker and more saturated than the surface; with this one it comes out close to
  the surface's brightness and hue once the renderer follows enough volume bounces (measured
  in docs/artist.md).
"""

SURFACE_GREY = 0.8  # what Blender renders an object without material as (core/colour.DEFAULT_GREY)
SOLID_MEAN_FREE_PATHS = 32.0
SHELL_DEPTH_PER_LAYER = 1.0
SOLID_MODE = "solid"


def voxelized_extent(voxel_size: float, dims, padding: int = 0) -> float:
    """The longest side of what was voxelized, in world units: the grid's longest side less
    its padding (which a resolution does not scale)."""
    return max(max(int(d) for d in dims) - 2 * int(padding), 1) * float(voxel_size)


def material_density(mode: str, voxel_size: float, dims, padding: int = 0) -> float:
    """The density (per world unit) the material gives an occupied voxel (see the module's
    docstring)."""
    voxel_size = max(float(voxel_size), 1e-30)
    if mode == SOLID_MODE:
        return SOLID_MEAN_FREE_PATHS / voxelized_extent(voxel_size, dims, padding)
    return SHELL_DEPTH_PER_LAYER / voxel_size


def result_density(stats: dict, voxel_size: float, dims) -> float:
    """material_density of a run's result, from the module's stats (mode and padding)."""
    options = stats.get("options", {}) if isinstance(stats, dict) else {}
    return material_density(
        str(stats.get("mode", options.get("mode", ""))), voxel_size, dims, int(options.get("padding", 0))
    )


def surface_albedo(color: float) -> float:
    """The volume albedo whose thick medium reflects `color` (the module's docstring)."""
    return 4.0 * color / (1.0 + color) ** 2
