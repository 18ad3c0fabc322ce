// SPDX-License-Identifier: GPL-3.0-or-later
// hyvox._core.voxelize: copies the (already converted) numpy input, releases the GIL and
// runs hyvox::voxelize with an interrupter wired to a CancelToken and a progress callback.
#include <pybind11/stl.h>

#include <cstring>
#include <exception>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include "bindings.h"
#include "cancel_token.h"
#include "python_interrupter.h"
#include "hyvox/errors.h"
#include "hyvox/voxelize.h"

namespace hyvox::python {
namespace {

// Exact dtype and layout, or ValueError: the Python layer converts, this only refuses.
template <typename T>
std::vector<T> copyRows(const py::array& array, const char* name, const char* dtype, py::ssize_t width = 3) {
    if (!py::isinstance<py::array_t<T>>(array))  // dtype equivalent to T, native byte order
        throw py::value_error(std::string(name) + " must be a numpy array of dtype " + dtype);
    if (array.ndim() != 2 || array.shape(1) != width)
        throw py::value_error(std::string(name) + " must have shape (count, " + std::to_string(width) + ")");
    // A private copy: another Python thread may modify the caller's array while the GIL is
    // released, and validated indices must stay valid.
    const auto contiguous = py::array_t<T, py::array::c_style>::ensure(array);
    if (!contiguous) throw py::error_already_set();
    std::vector<T> copy(std::size_t(contiguous.size()));
    if (!copy.empty()) std::memcpy(copy.data(), contiguous.data(), copy.size() * sizeof(T));
    return copy;
}

// Optional per-vertex rows (uvs, normals): one row per vertex, or absent.
std::vector<float> copyVertexRows(const std::optional<py::array>& array, const char* name, py::ssize_t width,
                                  std::size_t vertex_count) {
    if (!array) return {};
    std::vector<float> rows = copyRows<float>(*array, name, "float32", width);
    if (rows.size() != vertex_count * std::size_t(width))
        throw py::value_error(std::string(name) + " must have one row per vertex (" + std::to_string(vertex_count) +
                              "), got " + std::to_string(rows.size() / std::size_t(width)));
    return rows;
}

HeightImage heightImage(const std::optional<py::array>& array) {
    HeightImage image;
    if (!array) return image;
    if (!py::isinstance<py::array_t<float>>(*array) || array->ndim() != 2)
        throw py::value_error("displacement_pixels must be a float32 array of shape (height, width)");
    const auto contiguous = py::array_t<float, py::array::c_style>::ensure(*array);
    if (!contiguous) throw py::error_already_set();
    image.height = int(contiguous.shape(0));
    image.width = int(contiguous.shape(1));
    image.values.assign(contiguous.data(), contiguous.data() + contiguous.size());
    return image;
}

std::shared_ptr<VoxelizeResult> voxelizeArrays(const py::array& vertices, const py::array& triangles,
                                               VoxelizeOptions options, std::optional<py::array> uvs,
                                               std::optional<py::array> normals,
                                               std::optional<py::array> displacement_pixels,
                                               std::shared_ptr<CancelToken> cancel, py::object progress) {
    options.tessellation.displacement_pixels = heightImage(displacement_pixels);
    if (!progress.is_none() && !PyCallable_Check(progress.ptr())) throw py::type_error("progress must be callable or None");

    const std::vector<float> positions = copyRows<float>(vertices, "vertices", "float32");
    const std::vector<std::uint32_t> indices = copyRows<std::uint32_t>(triangles, "triangles", "uint32");
    const std::vector<float> uv_rows = copyVertexRows(uvs, "uvs", 2, positions.size() / 3);
    const std::vector<float> normal_rows = copyVertexRows(normals, "normals", 3, positions.size() / 3);
    MeshView view{positions.data(), positions.size() / 3, indices.data(), indices.size() / 3};
    if (uvs) view.uvs = uv_rows.data();
    if (normals) view.normals = normal_rows.data();

    PythonInterrupter interrupter(std::move(cancel), std::move(progress));
    auto result = std::make_shared<VoxelizeResult>();
    try {
        py::gil_scoped_release release;
        *result = voxelize(view, options, &interrupter);
    } catch (const Cancelled&) {
        interrupter.rethrowCallbackError();  // the callback's own exception wins
        throw;
    }
    interrupter.rethrowCallbackError();
    return result;
}

}  // namespace

void bindVoxelize(py::module_& m) {
    m.def("voxelize", &voxelizeArrays, py::arg("vertices"), py::arg("triangles"), py::arg("options"), py::kw_only(),
          py::arg("uvs") = py::none(), py::arg("normals") = py::none(), py::arg("displacement_pixels") = py::none(),
          py::arg("cancel") = py::none(), py::arg("progress") = py::none(),
          "Voxelize float32 (N,3) vertices and uint32 (M,3) triangles (exact dtypes; hyvox.voxelize "
          "converts) with an Options object. Releases the GIL while it runs.");
}

}  // namespace hyvox::python
