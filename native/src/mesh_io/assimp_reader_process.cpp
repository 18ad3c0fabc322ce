// SPDX-License-Identifier: GPL-3.0-or-later
// hyvox_assimp_reader: the program hyvox starts to read a mesh file through assimp
// (assimp_reader.h), so that whatever assimp does with the file ends this process and not the
// one that asked. It reads one file and writes the mesh, or why there is none, to its
// standard output (mesh_wire.h). Not meant to be run by hand.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "hyvox/errors.h"
#include "mesh_io/assimp_import.h"
#include "mesh_io/mesh_wire.h"
#include "os/helper_process.h"

namespace {

using namespace hyvox;

// assimp's progress steps, passed on; the process is never asked to stop (it is ended).
class ProgressToParent final : public Interrupter {
public:
    bool wasInterrupted(int percent) override {
        if (percent >= 0 && percent != last_) {
            last_ = percent;
            os::writeStandardOutput(mesh_io::wire::progressMessage(percent));
        }
        return false;
    }

private:
    int last_ = -1;
};

}  // namespace

int main(int argc, char** argv) {
    if (argc != 7 || std::strcmp(argv[1], mesh_io::wire::kProtocol) != 0) {
        std::fprintf(stderr, "hyvox_assimp_reader: started by hyvox to read one mesh file (protocol %s), not by hand\n",
                     mesh_io::wire::kProtocol);
        return mesh_io::wire::kExitUsage;
    }
    if (!os::endWithParent(argv[2])) return mesh_io::wire::kExitUsage;  // it is already gone
    // The limits first: nothing the file makes assimp do may outgrow them or leave a core file.
    os::limitThisProcess(std::strtoull(argv[3], nullptr, 10), mesh_io::wire::kExitOutOfMemory);
    const std::string extension = argv[4], source = argv[5], name = argv[6];
    ProgressToParent progress;
    std::string message;
    try {
        Mesh mesh;
        if (source == "-") {
            const std::vector<char> bytes = os::readStandardInput();
            mesh = mesh_io::importWithAssimp(bytes.data(), bytes.size(), extension, name, &progress);
        } else {
            mesh = mesh_io::importWithAssimp(source, extension, &progress);
        }
        message = mesh_io::wire::meshMessage(mesh);
    } catch (const std::bad_alloc&) {
        return mesh_io::wire::kExitOutOfMemory;
    } catch (const InvalidInput& e) {
        message = mesh_io::wire::errorMessage(e.what());
    } catch (const std::exception& e) {
        message = mesh_io::wire::errorMessage("cannot read mesh file '" + name + "': " + e.what());
    }
    return os::writeStandardOutput(message) ? 0 : 1;
}
