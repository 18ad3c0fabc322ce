// SPDX-License-Identifier: GPL-3.0-or-later
#include "cancel_token.h"

#include <memory>

#include "bindings.h"

namespace hyvox::python {

void bindCancelToken(py::module_& m) {
    py::class_<CancelToken, std::shared_ptr<CancelToken>>(m, "CancelToken", R"doc(
Cancels a running voxelization from another thread and reports its progress.

Pass it as ``hyvox.voxelize(..., cancel=token)``; call ``token.cancel()`` from any thread
(a UI timer, a signal handler) and the voxelization stops at its next check and raises
``hyvox.Cancelled``. ``token.progress`` is the percent done (0-100, -1 before start).
Reading or setting it needs no lock and never waits for the voxelization.)doc")
        .def(py::init<>())
        .def("cancel", &CancelToken::cancel, "Ask the voxelization using this token to stop.")
        .def("reset", &CancelToken::reset, "Clear the cancel request and the progress, to reuse the token.")
        .def_property_readonly("cancelled", &CancelToken::cancelled, "True once cancel() was called.")
        .def_property_readonly("progress", &CancelToken::progress, "Percent done, 0-100; -1 before a run starts.")
        .def_property_readonly("running", &CancelToken::running, "True while a voxelization uses this token.")
        .def("__repr__", [](const CancelToken& t) {
            return "<hyvox.CancelToken cancelled=" + std::string(t.cancelled() ? "True" : "False") +
                " progress=" + std::to_string(t.progress()) + ">";
        });
}

}  // namespace hyvox::python
