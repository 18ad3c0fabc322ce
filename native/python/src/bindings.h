// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Pieces of the hyvox._core module, one file each; module.cpp calls them in order.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <vector>

namespace hyvox {
struct VoxelizeOptions;
struct WriteOptions;
}  // namespace hyvox

namespace hyvox::python {

namespace py = pybind11;

void bindErrors(py::module_& m);
void bindCancelToken(py::module_& m);
void bindVoxelGrid(py::module_& m);
void bindOptions(py::module_& m);
void bindVoxelize(py::module_& m);
void bindMeshIo(py::module_& m);
void bindPlanGrid(py::module_& m);
void bindMerge(py::module_& m);
void bindFarmTask(py::module_& m);

// write_vdb's options: the schema's write options by name from `given` (None = unset), checked
// as voxelize() checks its own; an unset option that is also a voxelize option takes the value
// `voxelized` (the run that made the grid) used. TypeError for a name that is not a write option.
WriteOptions writeOptions(const VoxelizeOptions& voxelized, const py::dict& given);

// A numpy array that takes over a vector's storage (no copy): the vector lives in a
// capsule that numpy frees with the array.
template <typename T>
py::array_t<T> arrayFromVector(std::vector<T>&& data, const std::vector<py::ssize_t>& shape) {
    auto* owned = new std::vector<T>(std::move(data));
    py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
    return py::array_t<T>(shape, owned->data(), free_when_done);
}

}  // namespace hyvox::python
