// SPDX-License-Identifier: GPL-3.0-or-later
// OpenVDB's leaf layout (hyvox/bit_grid.h), the one addressing every voxel-writing shader
// uses so the host can copy the buffer straight into a BitGrid: 8³ bricks in x-major order,
// brick b = ((i>>3)*bricks_y + (j>>3))*bricks_z + (k>>3), bit n = (i&7)<<6 | (j&7)<<3 | (k&7)
// inside the brick's 512 bits, read as 16 uint words: word b*16 + (n>>5), bit n&31.

uvec3 leafBrickCounts(ivec3 dims) { return uvec3((dims + 7) >> 3); }

uint leafBrick(uvec3 v, uvec3 bricks) { return ((v.x >> 3u) * bricks.y + (v.y >> 3u)) * bricks.z + (v.z >> 3u); }

uint leafBit(uvec3 v) { return ((v.x & 7u) << 6u) | ((v.y & 7u) << 3u) | (v.z & 7u); }

uint leafWord(uint brick, uint bit) { return brick * 16u + (bit >> 5u); }

uint leafMask(uint bit) { return 1u << (bit & 31u); }
