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
#include "hyvox/errors.h"
#include "hyvox/texture.h"
#include "hyvox/voxelize.h"
#include "hyvox/zero_page_allocator.h"
#include "python_interrupter.h"

namespace hyvox::python {
namespace {

// The private copies of the caller's arrays. Their memory is fresh pages asking for huge
// pages, filled by one memcpy: a std::vector would zero them first, and a large mesh's 4 KiB
// first touches cost more than the copy itself (docs/why/startup.md; the CLI's mesh arrays get
// the same hint before they are filled).
template <typename T>
using PrivateRows = std::vector<T, ZeroPageAllocator<T>>;

// Exact dtype and layout, or ValueError: the Python layer converts, this only refuses.
template <typename T>
PrivateRows<T> copyRows(const py::array& array, const char* name, const char* dtype, py::ssize_t width = 3) {
    if (!py::isinstance<py::array_t<T>>(array))  // dtype equivalent to T, native byte order
        throw py::value_error(std::string(name) + " must be a numpy array of dtype " + dtype);
    if (array.ndim() != 2 || array.shape(1) != width)
        throw py::value_error(std::string(name) + " must have shape (count, " + std::to_string(width) + ")");
    // A private copy: another Python thread may modify the caller's array while the GIL is
    // released, and validated indices must stay valid.
    const auto contiguous = py::array_t<T, py::array::c_style>::ensure(array);
    if (!contiguous) throw py::error_already_set();
    PrivateRows<T> copy(std::size_t(contiguous.size()));  // not zeroed: see ZeroPageAllocator
    if (!copy.empty()) std::memcpy(copy.data(), contiguous.data(), copy.size() * sizeof(T));
    return copy;
}

// Optional per-vertex rows (uvs, normals): one row per vertex, or absent.
PrivateRows<float> copyVertexRows(const std::optional<py::array>& array, const char* name, py::ssize_t width,
                                  std::size_t vertex_count) {
    if (!array) return {};
    PrivateRows<float> rows = copyRows<float>(*array, name, "float32", width);
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

// A texture from (height, width, 3|4) pixels: uint8 / uint16 sRGB-encoded, float32 linear.
std::optional<Texture> textureFromArray(const std::optional<py::array>& array) {
    if (!array) return std::nullopt;
    if (array->ndim() != 3)
        throw py::value_error("texture must be a path or an array of shape (height, width, 3 or 4)");
    const int height = int(array->shape(0)), width = int(array->shape(1)), channels = int(array->shape(2));
    if (py::isinstance<py::array_t<std::uint8_t>>(*array)) {
        const auto c = py::array_t<std::uint8_t, py::array::c_style>::ensure(*array);
        return textureFromBytes(c.data(), width, height, channels);
    }
    if (py::isinstance<py::array_t<std::uint16_t>>(*array)) {
        const auto c = py::array_t<std::uint16_t, py::array::c_style>::ensure(*array);
        return textureFromWords(c.data(), width, height, channels);
    }
    if (py::isinstance<py::array_t<float>>(*array)) {
        const auto c = py::array_t<float, py::array::c_style>::ensure(*array);
        return textureFromLinear(c.data(), width, height, channels);
    }
    throw py::value_error("texture pixels must be uint8 or uint16 (sRGB) or float32 (linear)");
}

// One texture per material: a list whose entries are None, a PNG path or pixels as above.
MaterialTextures materialTextures(const std::optional<py::list>& list) {
    MaterialTextures out;
    if (!list) return out;
    out.images.reserve(list->size());  // no reallocation: of_material points into it
    for (const py::handle entry : *list) {
        if (entry.is_none()) {
            out.of_material.push_back(nullptr);
            continue;
        }
        if (py::isinstance<py::str>(entry)) {
            const std::string path = entry.cast<std::string>();
            py::gil_scoped_release release;
            out.images.push_back(readPngTexture(path));
        } else {
            const py::array pixels = py::array::ensure(entry);
            if (!pixels) throw py::value_error("textures: each entry is None, a PNG path or an array of pixels");
            out.images.push_back(*textureFromArray(pixels));
        }
        out.of_material.push_back(&out.images.back());
    }
    return out;
}

// Colours: (N, 3|4) per vertex or (3M, 3|4) per corner.
struct ColorRows {
    PrivateRows<float> values;
    int channels = 0;
    bool per_corner = false;
};
ColorRows colorRows(const std::optional<py::array>& array, std::size_t vertex_count, std::size_t triangle_count) {
    ColorRows out;
    if (!array) return out;
    if (array->ndim() != 2 || (array->shape(1) != 3 && array->shape(1) != 4))
        throw py::value_error("colors must have shape (N, 3) or (N, 4)");
    out.channels = int(array->shape(1));
    out.values = copyRows<float>(*array, "colors", "float32", out.channels);
    const std::size_t rows = out.values.size() / std::size_t(out.channels);
    out.per_corner = rows == 3 * triangle_count && rows != vertex_count;
    if (rows != vertex_count && !out.per_corner)
        throw py::value_error("colors must have one row per vertex (" + std::to_string(vertex_count) +
                              ") or per triangle corner (" + std::to_string(3 * triangle_count) + "), got " +
                              std::to_string(rows));
    return out;
}

std::shared_ptr<VoxelizeResult> voxelizeArrays(
    const py::array& vertices, const py::array& triangles, VoxelizeOptions options, const std::optional<py::array>& uvs,
    const std::optional<py::array>& normals, const std::optional<py::array>& displacement_pixels,
    const std::optional<py::array>& colors, bool colors_srgb, const std::optional<py::array>& texture,
    std::optional<std::string> texture_path, std::optional<py::array> material_ids, std::optional<py::array> palette,
    const std::optional<py::list>& textures, std::optional<py::array> face_normals, std::shared_ptr<CancelToken> cancel,
    py::object progress) {
    options.tessellation.displacement_pixels = heightImage(displacement_pixels);
    if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
        throw py::type_error("progress must be callable or None");

    const PrivateRows<float> positions = copyRows<float>(vertices, "vertices", "float32");
    const PrivateRows<std::uint32_t> indices = copyRows<std::uint32_t>(triangles, "triangles", "uint32");
    const PrivateRows<float> uv_rows = copyVertexRows(uvs, "uvs", 2, positions.size() / 3);
    const PrivateRows<float> normal_rows = copyVertexRows(normals, "normals", 3, positions.size() / 3);
    MeshView view{positions.data(), positions.size() / 3, indices.data(), indices.size() / 3};
    if (uvs) view.uvs = uv_rows.data();
    if (normals) view.normals = normal_rows.data();

    const ColorRows color_rows = colorRows(colors, view.vertex_count, view.triangle_count);
    if (colors) {
        view.colors = color_rows.values.data();
        view.color_channels = color_rows.channels;
        view.colors_per_corner = color_rows.per_corner;
        view.colors_srgb = colors_srgb;
    }
    std::optional<Texture> image = textureFromArray(texture);
    if (texture_path) {
        py::gil_scoped_release release;
        image = readPngTexture(*texture_path);
    }
    if (image) view.texture = &*image;
    PrivateRows<std::uint32_t> material_rows;
    if (material_ids) {
        material_rows = copyRows<std::uint32_t>(material_ids->reshape({material_ids->size(), py::ssize_t(1)}),
                                                "material_ids", "uint32", 1);
        if (material_rows.size() != view.triangle_count)
            throw py::value_error("material_ids must have one entry per triangle (" +
                                  std::to_string(view.triangle_count) + "), got " +
                                  std::to_string(material_rows.size()));
        view.material_ids = material_rows.data();
    }
    PrivateRows<float> palette_rows;
    if (palette) {
        if (palette->ndim() != 2 || (palette->shape(1) != 3 && palette->shape(1) != 4))
            throw py::value_error("palette must have shape (P, 3) or (P, 4)");
        view.palette_channels = int(palette->shape(1));
        palette_rows = copyRows<float>(*palette, "palette", "float32", view.palette_channels);
        view.palette = palette_rows.data();
        view.palette_count = palette_rows.size() / std::size_t(view.palette_channels);
    }
    const MaterialTextures material_textures = materialTextures(textures);
    if (textures) {
        if (!palette || material_textures.of_material.size() != view.palette_count)
            throw py::value_error("textures must have one entry (None, a PNG path or pixels) per palette colour (" +
                                  std::to_string(view.palette_count) + "), got " +
                                  std::to_string(material_textures.of_material.size()));
        view.material_textures = material_textures.of_material.data();
    }
    PrivateRows<float> face_normal_rows;
    if (face_normals) {
        face_normal_rows = copyRows<float>(*face_normals, "face_normals", "float32", 3);
        if (face_normal_rows.size() != 3 * view.triangle_count)
            throw py::value_error("face_normals must have one row per triangle (" +
                                  std::to_string(view.triangle_count) + ")");
        view.face_normals = face_normal_rows.data();
    }

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
          py::arg("colors") = py::none(), py::arg("colors_srgb") = false, py::arg("texture") = py::none(),
          py::arg("texture_path") = py::none(), py::arg("material_ids") = py::none(), py::arg("palette") = py::none(),
          py::arg("textures") = py::none(), py::arg("face_normals") = py::none(), py::arg("cancel") = py::none(),
          py::arg("progress") = py::none(),
          "Voxelize float32 (N,3) vertices and uint32 (M,3) triangles (exact dtypes; hyvox.voxelize "
          "converts) with an Options object. Releases the GIL while it runs.");
}

}  // namespace hyvox::python
