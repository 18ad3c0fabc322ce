// SPDX-License-Identifier: GPL-3.0-or-later
// readMesh picks the reader: PLY and OBJ (plain or .gz) are read by hyvox's own strict
// readers, also a PLY under another name (told by its first line); every other format goes
// to assimp, which never sees PLY or OBJ (assimp_reader.h).
#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "hyvox/errors.h"
#include "hyvox/mesh_io.h"
#include "io/assimp_reader.h"
#include "io/file_bytes.h"
#include "io/gzip_input.h"
#include "io/mapped_file.h"
#include "io/mesh_file_error.h"
#include "io/obj_materials.h"
#include "io/obj_reader.h"
#include "io/ply_reader.h"

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

// An uncompressed file is read whole only by the readers that parse from memory; assimp
// opens files itself (some formats refer to other files beside them).
constexpr std::size_t kMaxMeshFileBytes = std::size_t(1) << 40;

// The bytes of a PLY or OBJ file, or of another format that was gzipped.
Mesh readBytes(const char* data, std::size_t size, const std::string& path, const std::string& extension,
               Interrupter* interrupter) {
    throwIfInterrupted(interrupter);
    // A PLY is told by its first line whatever its name, compressed or not.
    if (extension == "ply" || io::looksLikePly(data, size)) return io::readPly(data, size, path, interrupter);
    if (extension == "obj") {
        Mesh mesh = io::readObj(data, size, path, interrupter);
        io::readObjMaterials(mesh, path);
        return mesh;
    }
    return io::readWithAssimp(data, size, extension, path, interrupter);  // another format, gzipped
}

Mesh readMeshFile(const std::string& path, Interrupter* interrupter) {
    io::checkMeshFile(path);
    const std::string lower_path = lower(path);
    const bool gzipped = endsWith(lower_path, ".gz");
    const std::string extension = extensionOf(gzipped ? lower_path.substr(0, lower_path.size() - 3) : lower_path);

    if (gzipped && extension.empty())
        throw InvalidInput("cannot tell the format of '" + path + "': name it like mesh.ply.gz or mesh.obj.gz");
    // The prefix is read only when the name does not already send the file to our readers.
    const bool ours = gzipped || extension == "ply" || extension == "obj" || [&] {
        const std::vector<char> prefix = io::readFilePrefix(path, 4);
        return io::looksLikePly(prefix.data(), prefix.size());
    }();
    if (!ours) return io::readWithAssimp(path, extension, interrupter);
    if (!gzipped) {
        const io::MappedFile file(path, kMaxMeshFileBytes);
        Mesh mesh;
        try {
            mesh = readBytes(file.data(), file.size(), path, extension, interrupter);
        } catch (const InvalidInput&) {
            // Zeros where another process cut the file short: not the file's own error.
            if (file.changedWhileRead()) io::failMeshFile(path, "changed size while it was read");
            throw;
        }
        if (file.changedWhileRead()) io::failMeshFile(path, "changed size while it was read");
        return mesh;
    }
    const std::vector<char> data = io::readGzipFile(path, interrupter);
    return readBytes(data.data(), data.size(), path, extension, interrupter);
}

}  // namespace

Mesh readMesh(const std::string& path, Interrupter* interrupter) {
    const InterrupterRun run(interrupter, "hyvox read mesh");
    // 0% and 100% at the ends of every read (a gzip reports its share in between), so a
    // front end sees the reading start: the CLI's progress line, a test waiting to interrupt.
    throwIfInterrupted(interrupter, 0);
    Mesh mesh = readMeshFile(path, interrupter);
    throwIfInterrupted(interrupter, 100);
    return mesh;
}

}  // namespace hyvox
