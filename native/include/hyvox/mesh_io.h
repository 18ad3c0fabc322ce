// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// Reading triangle meshes from files into an owning mesh. PLY, OBJ, STL, OFF and glTF are
/// read by hyvox's own strict readers (src/mesh_io/*_reader.h): every declared count is checked
/// against the bytes present before allocating, and a damaged file is an InvalidInput naming
/// the file and the place. The other formats go through assimp in a separate process
/// (src/mesh_io/assimp_reader.h). Triangles are kept exactly as the file lists them: degenerate and
/// duplicate triangles stay (validate() skips and counts them), so triangle counts match the
/// file.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hyvox/interrupter.h"
#include "hyvox/mesh.h"

namespace hyvox {

/// A mesh read from a file, owning its arrays (view() gives the MeshView voxelize() takes).
struct Mesh {
    std::vector<float> positions;          ///< vertex_count × 3, world units
    std::vector<std::uint32_t> triangles;  ///< triangle_count × 3 vertex indices
    std::vector<float> colors;             ///< empty, or vertex_count × 4 (RGBA, 0..1, colour sRGB-encoded)
    bool colors_alpha = false;             ///< the file gave alpha (else alpha is 1)
    std::vector<float> uvs;                ///< empty, or vertex_count × 2
    /// Materials (OBJ "usemtl", with its MTL files): empty, or one id per triangle into the
    /// material lists. Their colours are the mesh's colour source when it has no vertex
    /// colours (and no other texture is given).
    std::vector<std::uint32_t> material_ids;
    std::vector<std::string> material_names;      ///< in order of first use; "" = faces before any usemtl
    std::vector<float> material_colors;           ///< 3 per material, linear RGB (MTL Kd; 0.8 grey without)
    std::vector<std::string> material_textures;   ///< per material: its image file (MTL map_Kd), or ""
    std::vector<std::string> material_libraries;  ///< OBJ "mtllib" files as written (readMesh reads them)
    /// What the reader could not use and left out (a missing .mtl or image, an unknown
    /// material): the front doors show these as warnings.
    std::vector<std::string> warnings;

    std::size_t vertexCount() const { return positions.size() / 3; }    ///< rows of positions
    std::size_t triangleCount() const { return triangles.size() / 3; }  ///< rows of triangles
    bool hasColors() const { return !colors.empty(); }                  ///< the file gave vertex colours
    bool hasUvs() const { return !uvs.empty(); }                        ///< the file gave UVs
    bool hasMaterials() const { return !material_ids.empty(); }         ///< the file named materials
    /// A view for voxelize(); valid while this mesh lives and is not modified.
    MeshView view() const {
        MeshView v{positions.data(), vertexCount(), triangles.data(), triangleCount()};
        v.uvs = hasUvs() ? uvs.data() : nullptr;  // the tessellation method's displacement reads them
        if (hasColors()) {                        // attribute voxels read them (options.attributes)
            v.colors = colors.data();
            v.color_stride = 4;
            v.color_channels = colors_alpha ? 4 : 3;
            v.colors_srgb = true;
        }
        if (hasMaterials()) {  // the textures are decoded by the caller (loadMaterialTextures)
            v.material_ids = material_ids.data();
            v.palette = material_colors.data();
            v.palette_count = material_colors.size() / 3;
            v.palette_channels = 3;
        }
        return v;
    }
};

/// What a read may take. The strict readers hold at most a small multiple of the file (every
/// count is checked against the bytes present); a gzip's output and everything the assimp
/// process does are held to these.
struct MeshReadOptions {
    /// The gzip output, a glTF scene and the assimp process's memory, in MiB;
    /// 0 = defaultMemoryBudgetMib() (hyvox/options.h), as VoxelizeOptions::memory_budget_mib.
    std::uint64_t memory_budget_mib = 0;
    /// The assimp process is ended after this many seconds (wall clock); 0 = 60 s plus 2 s
    /// per MiB of the file.
    double time_limit_s = 0;
};

/// Reads a mesh file. The formats and who reads them (docs/mesh-formats.md): PLY, OBJ, STL,
/// OFF and glTF/GLB by hyvox's own strict readers; FBX (binary; its container checked first)
/// and 3MF through assimp in a process of its own, so nothing in the file can crash, hang or
/// exhaust this process.
/// A name ending in ".gz" is decompressed first (bounded: see mesh_io/gzip_input.h; a stream cut
/// short is an error) and read as the extension before ".gz" (e.g. "x.ply.gz" as PLY); a
/// file whose first line is "ply" is read as PLY whatever its name. Points and lines in the
/// file are ignored (a PLY face or OBJ "f" with fewer than 3 corners is an error); polygons
/// are fan-triangulated. Several meshes in one file are merged, with their node transforms
/// applied. Reentrant: files may be read from several threads at once.
/// @param path the file; positions are taken in the file's units as world units
/// @param interrupter may be null; asked at milestones (every MiB decompressed, every 64k
///        records or lines parsed, every 20 ms of the assimp process)
/// @param options the memory budget and time limit of the read
/// @return the mesh, its triangles exactly as the file lists them
/// @throws InvalidInput naming the file: a missing, unreadable, non-regular, damaged or
///         unparsable file, one without triangles, a format hyvox does not read, and an
///         assimp read that crashed, ran past the time limit or past the memory budget
/// @throws Cancelled the interrupter asked to stop (the partly read mesh is freed, the
///         assimp process ended)
Mesh readMesh(const std::string& path, Interrupter* interrupter = nullptr, const MeshReadOptions& options = {});

}  // namespace hyvox
