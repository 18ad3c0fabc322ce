// SPDX-License-Identifier: GPL-3.0-or-later
// readMesh picks the reader by the file's extension (mesh_formats.h): PLY, OBJ, STL, OFF and
// glTF (plain or .gz) are read by hyvox's own strict readers, also a PLY under another name (told
// by its first line); FBX (its container checked here first) and 3MF go to the assimp process
// (assimp_reader.h); any other name is refused, naming the formats hyvox reads.
#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "hyvox/errors.h"
#include "hyvox/mesh_io.h"
#include "hyvox/options.h"
#include "mesh_io/assimp_reader.h"
#include "mesh_io/fbx_check.h"
#include "mesh_io/gltf_reader.h"
#include "mesh_io/gzip_input.h"
#include "mesh_io/mesh_formats.h"
#include "mesh_io/obj_materials.h"
#include "mesh_io/obj_reader.h"
#include "mesh_io/off_reader.h"
#include "mesh_io/ply_reader.h"
#include "mesh_io/stl_reader.h"
#include "os/file_bytes.h"
#include "os/mapped_file.h"
#include "os/mesh_file_error.h"

namespace hyvox {
namespace {

std::string lower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return text;
}

bool endsWith(const std::string& text, const std::string& suffix) {
    return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// "mesh.ply" -> "ply"; "" when the file name has no extension.
std::string extensionOf(const std::string& lower_path) {
    const auto dot = lower_path.find_last_of('.');
    const auto slash = lower_path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    return lower_path.substr(dot + 1);
}

// An uncompressed file is read whole only by the readers that parse from memory; the assimp
// process opens files itself (some formats refer to other files beside them).
constexpr std::size_t kMaxMeshFileBytes = std::size_t(1) << 40;

std::uint64_t budgetBytes(const MeshReadOptions& options) {
    VoxelizeOptions budget;
    budget.memory_budget_mib = options.memory_budget_mib;
    return budget.memoryBudgetBytes();
}

// The bytes of a file our own readers read, compressed or not; a gzipped assimp format.
Mesh readBytes(const char* data, std::size_t size, const std::string& path, const mesh_io::MeshFormat* format,
               const MeshReadOptions& options, Interrupter* interrupter) {
    throwIfInterrupted(interrupter);
    // A PLY is told by its first line whatever its name, compressed or not.
    if (mesh_io::looksLikePly(data, size)) return mesh_io::readPly(data, size, path, interrupter);
    switch (format->reader) {
        case mesh_io::MeshReader::Ply: return mesh_io::readPly(data, size, path, interrupter);
        case mesh_io::MeshReader::Obj: {
            Mesh mesh = mesh_io::readObj(data, size, path, interrupter);
            mesh_io::readObjMaterials(mesh, path);
            return mesh;
        }
        case mesh_io::MeshReader::Stl: return mesh_io::readStl(data, size, path, interrupter);
        case mesh_io::MeshReader::Off: return mesh_io::readOff(data, size, path, interrupter);
        case mesh_io::MeshReader::Gltf: return mesh_io::readGltf(data, size, path, budgetBytes(options), interrupter);
        case mesh_io::MeshReader::Fbx: mesh_io::checkFbxContainer(data, size, path, budgetBytes(options)); break;
        case mesh_io::MeshReader::Assimp: break;
    }
    return mesh_io::readWithAssimp(data, size, format->extension, path, mesh_io::assimpReadLimits(options, size),
                                   interrupter);
}

[[noreturn]] void refuseFormat(const std::string& path, const std::string& extension) {
    const std::string offered = "hyvox reads " + mesh_io::offeredExtensions() + " files, also gzipped (as mesh.ply.gz)";
    if (extension.empty()) os::failMeshFile(path, "its name has no extension to tell its format by: " + offered);
    os::failMeshFile(path, "'." + extension + "' is not a format hyvox reads: " + offered);
}

Mesh readMeshFile(const std::string& path, const MeshReadOptions& options, Interrupter* interrupter) {
    const std::uint64_t file_bytes = os::checkMeshFile(path);
    const std::string lower_path = lower(path);
    const bool gzipped = endsWith(lower_path, ".gz");
    const std::string extension = extensionOf(gzipped ? lower_path.substr(0, lower_path.size() - 3) : lower_path);
    const mesh_io::MeshFormat* format = mesh_io::meshFormat(extension);

    if (gzipped) {
        if (!format) refuseFormat(path, extension);
        const std::vector<char> data = mesh_io::readGzipMeshFile(path, budgetBytes(options), interrupter);
        return readBytes(data.data(), data.size(), path, format, options, interrupter);
    }
    if (!format || format->reader != mesh_io::MeshReader::Assimp) {
        // Our readers and the FBX check read the file from memory; the checked FBX bytes are
        // then what the assimp process gets (on its standard input), not the file again.
        // A PLY under another name is read as one; any other unknown name is refused.
        if (!format) {
            const std::vector<char> prefix = os::readFilePrefix(path, 4);
            if (!mesh_io::looksLikePly(prefix.data(), prefix.size())) refuseFormat(path, extension);
            format = mesh_io::meshFormat("ply");
        }
        const os::MappedFile file(path, kMaxMeshFileBytes);
        Mesh mesh;
        try {
            mesh = readBytes(file.data(), file.size(), path, format, options, interrupter);
        } catch (const InvalidInput&) {
            // Zeros where another process cut the file short: not the file's own error.
            if (file.changedWhileRead()) os::failMeshFile(path, "changed size while it was read");
            throw;
        }
        if (file.changedWhileRead()) os::failMeshFile(path, "changed size while it was read");
        return mesh;
    }
    return mesh_io::readWithAssimp(path, extension, mesh_io::assimpReadLimits(options, file_bytes), interrupter);
}

}  // namespace

Mesh readMesh(const std::string& path, Interrupter* interrupter, const MeshReadOptions& options) {
    const InterrupterRun run(interrupter, "hyvox read mesh");
    // 0% and 100% at the ends of every read (a gzip reports its share in between), so a
    // front end sees the reading start: the CLI's progress line, a test waiting to interrupt.
    throwIfInterrupted(interrupter, 0);
    Mesh mesh = readMeshFile(path, options, interrupter);
    throwIfInterrupted(interrupter, 100);
    return mesh;
}

}  // namespace hyvox
