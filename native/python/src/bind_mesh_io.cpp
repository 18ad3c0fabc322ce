// SPDX-License-Identifier: GPL-3.0-or-later
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <string>

#include "bindings.h"
#include "hyvox/gl_devices.h"
#include "hyvox/mesh_io.h"
#include "python_interrupter.h"

namespace hyvox::python {

void bindMeshIo(py::module_& m) {
    m.def(
        "read_mesh",
        [](const std::filesystem::path& path, std::shared_ptr<CancelToken> cancel, std::uint64_t memory_budget_mib) {
            Mesh mesh;
            {
                PythonInterrupter interrupter(std::move(cancel), py::none());
                py::gil_scoped_release release;
                MeshReadOptions options;
                options.memory_budget_mib = memory_budget_mib;
                mesh = readMesh(path.string(), &interrupter, options);
            }
            const auto n = py::ssize_t(mesh.vertexCount());
            const auto t = py::ssize_t(mesh.triangleCount());
            py::object colors = py::none(), uvs = py::none(), materials = py::none();
            if (mesh.hasColors()) colors = arrayFromVector(std::move(mesh.colors), {n, 4});
            if (mesh.hasUvs()) uvs = arrayFromVector(std::move(mesh.uvs), {n, 2});
            if (mesh.hasMaterials()) {
                const auto count = py::ssize_t(mesh.material_names.size());
                py::list textures;
                for (const std::string& image : mesh.material_textures)
                    textures.append(image.empty() ? py::object(py::none()) : py::object(py::str(image)));
                materials =
                    py::dict(py::arg("material_ids") = arrayFromVector(std::move(mesh.material_ids), {t}),
                             py::arg("palette") = arrayFromVector(std::move(mesh.material_colors), {count, 3}),
                             py::arg("textures") = textures, py::arg("material_names") = py::cast(mesh.material_names));
            }
            return py::make_tuple(arrayFromVector(std::move(mesh.positions), {n, 3}),
                                  arrayFromVector(std::move(mesh.triangles), {t, 3}), colors, uvs, materials,
                                  py::cast(mesh.warnings));
        },
        py::arg("path"), py::arg("cancel") = py::none(), py::arg("memory_budget_mib") = 0,
        "Read a mesh file; cancel: a CancelToken whose cancel() stops the reading (hyvox.Cancelled); "
        "memory_budget_mib: what a gzip's output and the assimp reader process may take (0 = half of this "
        "machine's memory). Returns (vertices float32 (N,3), triangles uint32 (M,3), colors float32 (N,4) "
        "or None, uvs float32 (N,2) or None, materials (dict: material_ids uint32 (M,), palette float32 (P,3) linear, "
        "textures [str or None] * P, material_names [str] * P) or None, warnings [str]).");

    m.def(
        "gl_devices",
        [] {
            py::list devices;
            for (const auto& d : listGlDevices())
                devices.append(
                    py::dict(py::arg("index") = d.index, py::arg("name") = d.name, py::arg("software") = d.software));
            return devices;
        },
        "The EGL devices the GL methods can use: [{'index', 'name', 'software'}]. Creates no context.");

    m.def(
        "gl_live_objects",
        [] {
            const GlObjectCounts c = liveGlObjects();
            return py::dict(py::arg("buffers") = c.buffers, py::arg("vertex_arrays") = c.vertex_arrays,
                            py::arg("framebuffers") = c.framebuffers, py::arg("programs") = c.programs,
                            py::arg("shaders") = c.shaders, py::arg("queries") = c.queries);
        },
        "Diagnostic: the GL objects alive in the process now, by kind (flat over repeated runs).");
}

}  // namespace hyvox::python
