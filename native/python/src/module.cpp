// SPDX-License-Identifier: GPL-3.0-or-later
// hyvox._core: the compiled half of the `hyvox` package. Private: use `import hyvox`,
// whose __init__.py converts and checks numpy input before it reaches this module.
#include "bindings.h"
#include "hyvox/errors.h"
#include "hyvox/version.h"

namespace hyvox::python {

void bindErrors(py::module_& m) {
    // Cancelled is not an error of the input or the machine: a plain Exception subclass, so
    // `except RuntimeError` around a voxelization does not swallow a user's cancel.
    py::register_exception<Cancelled>(m, "Cancelled", PyExc_Exception);
    py::register_exception<ResourceError>(m, "ResourceError", PyExc_RuntimeError);
    py::register_exception<BackendError>(m, "BackendError", PyExc_RuntimeError);
    // InvalidInput derives from std::invalid_argument, which pybind11 already maps to
    // ValueError; said explicitly so a reader need not know that.
    // NOLINTNEXTLINE(performance-unnecessary-value-param): pybind11's translator type takes it by value
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const InvalidInput& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        }
    });
}

}  // namespace hyvox::python

PYBIND11_MODULE(_core, m) {
    using namespace hyvox::python;
    m.doc() = "hyvox native core (private; import hyvox instead)";
    m.attr("__version__") = hyvox::version();
    bindErrors(m);
    bindCancelToken(m);
    bindOptions(m);
    bindVoxelGrid(m);
    bindVoxelize(m);
    bindMeshIo(m);
    bindPlanGrid(m);
    bindFarmTask(m);
    bindMerge(m);
}
