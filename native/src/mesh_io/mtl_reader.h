// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A Wavefront MTL (material library) reader for the colour of OBJ materials: "newmtl NAME",
// "Kd r g b" (or one value for grey; linear, as Blender reads and writes it) and
// "map_Kd [options] FILE" (the diffuse image). Every other statement (Ka, Ks, Ns, d, illum,
// other maps, ...) is skipped. A malformed Kd or a statement before any newmtl is an
// InvalidInput naming the file and the line.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace hyvox::mesh_io {

struct MtlMaterial {
    std::string name;
    std::optional<std::array<float, 3>> diffuse;  // Kd
    std::string diffuse_map;                      // map_Kd's file as written (slashes normalised to '/'), or ""
};

// Reads the MTL held in [data, data + size); `name` is quoted in errors. Materials are in file
// order; a name given twice is kept twice (the first one is used).
std::vector<MtlMaterial> readMtl(const char* data, std::size_t size, const std::string& name);

}  // namespace hyvox::mesh_io
