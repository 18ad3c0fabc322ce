// SPDX-License-Identifier: GPL-3.0-or-later
// hyvox._core.plan_grid: the grid voxelize() would lay out for a mesh and options (the same
// validation and the same makeGrid), without voxelizing. A farm job's frame chunks take
// the voxel size of the job's first frame this way, as one run over the whole range does.
#include <pybind11/stl.h>

#include "bindings.h"
#include "hyvox/grid.h"
#include "hyvox/voxelize.h"

namespace hyvox::python {
namespace {

template <typename T>
py::array_t<T, py::array::c_style> rows(const py::array& array, const char* name, const char* dtype) {
    if (!py::isinstance<py::array_t<T>>(array) || array.ndim() != 2 || array.shape(1) != 3)
        throw py::value_error(std::string(name) + " must be a numpy array of dtype " + dtype + " and shape (count, 3)");
    auto contiguous = py::array_t<T, py::array::c_style>::ensure(array);
    if (!contiguous) throw py::error_already_set();
    return contiguous;
}

py::dict planGrid(const py::array& vertices, const py::array& triangles, const VoxelizeOptions& options) {
    const auto positions = rows<float>(vertices, "vertices", "float32");
    const auto indices = rows<std::uint32_t>(triangles, "triangles", "uint32");
    const MeshView view{positions.data(), std::size_t(positions.shape(0)), indices.data(),
                        std::size_t(indices.shape(0))};
    GridSpec grid;
    {
        py::gil_scoped_release release;  // the arrays are held above; validation reads them only
        grid = makeGrid(validate(view, options, nullptr).bounds, options.grid);
    }
    py::dict out;
    out["origin"] = py::make_tuple(grid.origin[0], grid.origin[1], grid.origin[2]);
    out["voxel_size"] = grid.voxel_size;
    out["dims"] = py::make_tuple(grid.dims[0], grid.dims[1], grid.dims[2]);
    return out;
}

}  // namespace

void bindPlanGrid(py::module_& m) {
    m.def("plan_grid", &planGrid, py::arg("vertices"), py::arg("triangles"), py::arg("options"),
          "The grid voxelize() would use for float32 (N,3) vertices, uint32 (M,3) triangles and an "
          "Options object: {'origin', 'voxel_size', 'dims'}; nothing is voxelized.");
}

}  // namespace hyvox::python
