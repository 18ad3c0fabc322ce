// SPDX-License-Identifier: GPL-3.0-or-later
// hyvox.VoxelGrid: a voxelization result held natively (one bit per voxel); numpy arrays
// are made on request.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>

#include "bindings.h"
#include "cancel_token.h"
#include "hyvox/errors.h"
#include "hyvox/options.h"
#include "hyvox/result.h"
#include "hyvox/stats_json.h"
#include "hyvox/vdb.h"
#include "python_interrupter.h"

namespace hyvox::python {
namespace {

using Grid = std::shared_ptr<VoxelizeResult>;

std::vector<std::int32_t> flatCoords(const VoxelizeResult& r) {
    const auto ijk = r.occupancy.coords();
    std::vector<std::int32_t> flat(3 * ijk.size());
    for (std::size_t n = 0; n < ijk.size(); ++n)
        for (int a = 0; a < 3; ++a) flat[3 * n + std::size_t(a)] = ijk[n][a];
    return flat;
}

py::array_t<std::int32_t> coords(const Grid& g) {
    std::vector<std::int32_t> flat;
    {
        py::gil_scoped_release release;
        flat = flatCoords(*g);
    }
    const auto k = py::ssize_t(flat.size() / 3);
    return arrayFromVector(std::move(flat), {k, 3});
}

py::array_t<double> worldCentres(const Grid& g) {
    std::vector<double> centres;
    {
        py::gil_scoped_release release;
        const auto ijk = g->occupancy.coords();
        centres.resize(3 * ijk.size());
        for (std::size_t n = 0; n < ijk.size(); ++n) {
            const auto c = g->grid.voxelCentre(ijk[n][0], ijk[n][1], ijk[n][2]);
            for (int a = 0; a < 3; ++a) centres[3 * n + std::size_t(a)] = c[a];
        }
    }
    const auto k = py::ssize_t(centres.size() / 3);
    return arrayFromVector(std::move(centres), {k, 3});
}

py::tuple counts(const Grid& g) {
    std::vector<std::int32_t> ijk(3 * g->counts.size());
    std::vector<std::uint32_t> values(g->counts.size());
    for (std::size_t n = 0; n < g->counts.size(); ++n) {
        const VoxelCount& c = g->counts[n];
        ijk[3 * n] = c.i;
        ijk[3 * n + 1] = c.j;
        ijk[3 * n + 2] = c.k;
        values[n] = c.count;
    }
    const auto k = py::ssize_t(values.size());
    return py::make_tuple(arrayFromVector(std::move(ijk), {k, 3}), arrayFromVector(std::move(values), {k}));
}

py::array_t<bool> toDense(const Grid& g) {
    const auto& d = g->grid.dims;
    // One byte per voxel of the whole box: refused, not attempted, when the run's memory
    // budget would not hold it (the result itself is sparse and may be far larger).
    const std::uint64_t bytes = g->grid.voxelCount();
    if (bytes > g->stats.options.memoryBudgetBytes())
        throw ResourceError("to_dense() of a " + g->grid.dimsText() + " grid needs " + std::to_string(bytes >> 20) +
                            " MiB, more than the memory budget of " +
                            std::to_string(g->stats.options.memoryBudgetMib()) +
                            " MiB; use coords() or write_vdb(), which stay sparse");
    py::array_t<bool> dense({py::ssize_t(d[0]), py::ssize_t(d[1]), py::ssize_t(d[2])});
    bool* out = dense.mutable_data();
    {
        py::gil_scoped_release release;
        std::fill(out, out + g->grid.voxelCount(), false);
        for (const auto& ijk : g->occupancy.coords())
            out[(std::size_t(ijk[0]) * std::size_t(d[1]) + std::size_t(ijk[1])) * std::size_t(d[2]) +
                std::size_t(ijk[2])] = true;
    }
    return dense;
}

// The attribute grids as numpy arrays aligned with coords(): {"color": (K,3), "alpha": (K,),
// "normal": (K,3)}, those the run computed. A solid's tile voxels, which coords() lists one by
// one, each carry their tile region's value (the result holds one per region).
py::dict attributeArrays(const Grid& g) {
    const AttributeGrid& a = g->attributes;
    py::dict out;
    if (a.empty()) return out;
    std::vector<float> all;
    {
        py::gil_scoped_release release;
        all = valuesInCoordsOrder(g->occupancy, a);
    }
    const std::size_t channels = std::size_t(a.channels()), count = all.size() / channels;
    auto take = [&](int offset, int width) {
        std::vector<float> values(count * std::size_t(width));
        for (std::size_t v = 0; v < count; ++v)
            for (int c = 0; c < width; ++c)
                values[v * std::size_t(width) + std::size_t(c)] = all[v * channels + std::size_t(offset + c)];
        return values;
    };
    const auto k = py::ssize_t(count);
    if (a.color) out["color"] = arrayFromVector(take(a.colorOffset(), 3), {k, 3});
    if (a.alpha) out["alpha"] = arrayFromVector(take(a.alphaOffset(), 1), {k});
    if (a.normal) out["normal"] = arrayFromVector(take(a.normalOffset(), 3), {k, 3});
    return out;
}

// The sdf's band voxels (option attributes with sdf): (ijk int32 (K, 3), signed distance
// float32 (K,)), leaf by leaf; None without an sdf.
py::object levelSetArrays(const Grid& g) {
    const LevelSetGrid& sdf = g->sdf;
    if (sdf.empty()) return py::none();
    std::vector<std::int32_t> ijk(3 * sdf.values.size());
    {
        py::gil_scoped_release release;
        const BrickLayout bricks = g->grid.bricks();
        for (const LevelSetGrid::Leaf& leaf : sdf.leaves) {
            const std::array<std::int32_t, 3> b = bricks.at(leaf.brick);
            std::size_t at = leaf.first;
            for (int w = 0; w < BitGrid::kWordsPerBrick; ++w)
                for (std::uint64_t bits = leaf.active[w]; bits; bits &= bits - 1, ++at) {
                    const int v = w * 64 + __builtin_ctzll(bits);
                    ijk[3 * at] = 8 * b[0] + (v >> 6);
                    ijk[3 * at + 1] = 8 * b[1] + ((v >> 3) & 7);
                    ijk[3 * at + 2] = 8 * b[2] + (v & 7);
                }
        }
    }
    const auto k = py::ssize_t(sdf.values.size());
    std::vector<float> values = sdf.values;
    return py::make_tuple(arrayFromVector(std::move(ijk), {k, 3}), arrayFromVector(std::move(values), {k}));
}

}  // namespace

void bindVoxelGrid(py::module_& m) {
    py::class_<VoxelizeResult, Grid>(m, "VoxelGrid", R"doc(
The voxels of one voxelization. Voxel (i, j, k) covers the closed box
[origin + (i, j, k) * voxel_size, origin + (i + 1, j + 1, k + 1) * voxel_size].)doc")
        .def("coords", &coords,
             "(i, j, k) of every occupied voxel as an int32 array of shape (K, 3), in 8x8x8 brick "
             "order (sort it if order matters). The voxels of whole-brick tiles (a solid's interior) "
             "are listed one by one like the others.")
        .def("world_centres", &worldCentres,
             "World-space centres of the occupied voxels, float64 (K, 3), in the order of coords().")
        .def("counts", &counts,
             "Multi-valued results (tessellation): (ijk int32 (K, 3), counts uint32 (K,)); empty arrays "
             "for single-valued methods.")
        .def("attributes", &attributeArrays,
             "The attribute voxels the run computed (option attributes), aligned row by row with coords(): "
             "{'color': float32 (K, 3) linear RGB, 'alpha': float32 (K,), 'normal': float32 (K, 3) unit or zero}; "
             "an empty dict when none were asked for. Solid mode: the voxels of a whole-brick tile region "
             "(listed one by one in coords()) each carry the region's one value.")
        .def("sdf", &levelSetArrays,
             "The signed distance grid the run computed (option attributes with sdf): its narrow band's voxels "
             "as (ijk int32 (K, 3), distance float32 (K,)), world units, negative inside; None without one. "
             "The band's half-width (the grid's background) is stats['sdf']['background'].")
        .def("to_dense", &toDense,
             "The occupancy as a dense bool array of shape dims, indexed [i, j, k]; ResourceError when that "
             "box does not fit the run's memory budget.")
        .def(
            "write_vdb",
            [](const Grid& g, const std::filesystem::path& path, const py::object& threads,
               std::shared_ptr<CancelToken> cancel, py::object progress, const py::kwargs& options) {
                if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
                    throw py::type_error("progress must be callable or None");
                if (!threads.is_none()) options["threads"] = threads;  // a dict of this call's own
                const WriteOptions write = writeOptions(g->stats.options, options);
                PythonInterrupter interrupter(std::move(cancel), std::move(progress));
                VdbWriteReport report;
                try {
                    py::gil_scoped_release release;
                    report = writeVdb(*g, path.string(), write, &interrupter);
                } catch (const Cancelled&) {
                    interrupter.rethrowCallbackError();
                    throw;
                }
                interrupter.rethrowCallbackError();
                py::dict out;
                out["grid_bytes"] = report.grid_bytes;
                out["build_ms"] = report.build_ms;
                out["write_ms"] = report.write_ms;
                return out;
            },
            py::arg("path"), py::arg("threads") = py::none(), py::kw_only(), py::arg("cancel") = py::none(),
            py::arg("progress") = py::none(),
            "Write an OpenVDB file with a float grid 'density' (1 on occupied voxels; index space = "
            "voxel centres), plus 'count' for multi-valued results, the attribute grids ('color', 'alpha', "
            "'normal') and the level set 'sdf' the run computed. Atomic: on failure nothing is "
            "written and an existing file is kept. Options: those of hyvox.WRITE_OPTIONS by name "
            "(threads: cores used to build the grids, 0 = all; memory_budget_mib; durable_write); "
            "threads and memory_budget_mib unset or None take the values the voxelization used. "
            "cancel (a CancelToken) stops it until the file is being written (hyvox.Cancelled); "
            "progress(percent) is called as in voxelize. Returns {grid_bytes, build_ms, write_ms}.")
        .def_property_readonly(
            "origin",
            [](const Grid& g) { return py::make_tuple(g->grid.origin[0], g->grid.origin[1], g->grid.origin[2]); },
            "World position of voxel (0, 0, 0)'s min corner.")
        .def_property_readonly(
            "voxel_size", [](const Grid& g) { return g->grid.voxel_size; }, "Voxel edge length, world units.")
        .def_property_readonly(
            "dims", [](const Grid& g) { return py::make_tuple(g->grid.dims[0], g->grid.dims[1], g->grid.dims[2]); },
            "Voxels along x, y, z.")
        .def_property_readonly(
            "voxel_count", [](const Grid& g) { return g->stats.voxel_count; }, "Occupied voxels.")
        .def_property_readonly("method", [](const Grid& g) { return g->stats.method; })
        .def_property_readonly("mode", [](const Grid& g) { return g->stats.mode; })
        .def_property_readonly(
            "stats", [](const Grid& g) { return py::module_::import("json").attr("loads")(statsToJson(*g)); },
            "The stats as a dict, the same as the CLI's --stats-json: origin, voxel_size, dims, "
            "voxel_count, triangles {input, used, degenerate}, timings_ms {stage: ms}, total_ms, metrics.")
        .def("__len__", [](const Grid& g) { return g->stats.voxel_count; })
        .def("__repr__", [](const Grid& g) {
            const auto& d = g->grid.dims;
            return "<hyvox.VoxelGrid " + std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" +
                std::to_string(d[2]) + ", " + std::to_string(g->stats.voxel_count) + " voxels, " + g->stats.mode +
                ", " + g->stats.method + ">";
        });
}

}  // namespace hyvox::python
