# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's Blender side, by feature: the operator (operators.py, settings gathered by
gather.py), export/ (Blender's meshes and colours out), volume/ (the results in: Volume
objects, materials, Blocks), live/ (volumes that follow their sources), files/ (where the
voxel files go and when they are cleaned), ui/ (properties, panels, earlier versions'
settings); registration.py registers them. The subpackages' __init__ files import nothing,
so importing one module never runs another's."""
