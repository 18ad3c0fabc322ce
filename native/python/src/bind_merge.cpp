// SPDX-License-Identifier: GPL-3.0-or-later
// hyvox._core.merge_vdb: the .vdb files of a region job joined into one (hyvox/vdb_merge.h),
// the GIL released while the files are read and written.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <string>
#include <vector>

#include "bindings.h"
#include "hyvox/errors.h"
#include "hyvox/vdb_merge.h"
#include "python_interrupter.h"

namespace hyvox::python {

void bindMerge(py::module_& m) {
    m.def(
        "merge_vdb",
        [](const std::vector<std::filesystem::path>& parts, const std::filesystem::path& output, int threads,
           bool durable_write, std::shared_ptr<CancelToken> cancel, py::object progress) {
            if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
                throw py::type_error("progress must be callable or None");
            std::vector<std::string> paths;
            for (const auto& part : parts) paths.push_back(part.string());
            PythonInterrupter interrupter(std::move(cancel), std::move(progress));
            MergeReport report;
            try {
                py::gil_scoped_release release;
                report = mergeVdbFiles(paths, output.string(), MergeOptions{threads, durable_write}, &interrupter);
            } catch (const Cancelled&) {
                interrupter.rethrowCallbackError();
                throw;
            }
            interrupter.rethrowCallbackError();
            py::dict out;
            out["parts"] = report.parts;
            out["grids"] = report.grids;
            out["voxels"] = report.voxels;
            out["leaves"] = report.leaves;
            out["regions"] = report.regions ? py::object(py::int_(report.regions)) : py::object(py::none());
            out["read_ms"] = report.read_ms;
            out["write_ms"] = report.write_ms;
            return out;
        },
        py::arg("parts"), py::arg("output"), py::kw_only(), py::arg("threads") = 0, py::arg("durable_write") = false,
        py::arg("cancel") = py::none(), py::arg("progress") = py::none(),
        "Join the .vdb files of a region job (voxelize(..., region=\"K/N\") for K = 0 .. N-1, or hyvox "
        "voxelize --region) into `output`, the file one run over the whole grid writes: every grid by name, "
        "leaf by leaf. Atomic: on failure nothing is written. ValueError for parts that do not fit together "
        "(another grid, method, mode or hyvox version; a region missing or given twice; parts that overlap). "
        "threads: cores that compress the leaves, 0 = all; durable_write as the option; cancel and progress as "
        "in voxelize. Returns {parts, grids, voxels, leaves, regions (N, or None for files of no job), read_ms, "
        "write_ms}.");
}

}  // namespace hyvox::python
