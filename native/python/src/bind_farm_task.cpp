// SPDX-License-Identifier: GPL-3.0-or-later
// hyvox._core.FARM_TASK_ARGUMENTS (the farm task's table, hyvox/farm_task.h), from which the
// Blender add-on builds the parser of its farm commands (the job generators write their command
// lines from the same table).
#include <pybind11/stl.h>

#include "bindings.h"
#include "hyvox/farm_task.h"

namespace hyvox::python {
namespace {

// The Python type of the flag's value: what the add-on's parser converts it with.
const char* valueType(const FarmTaskArgument& arg) {
    switch (arg.value) {
        case FarmValue::Text: return "str";
        case FarmValue::Switch: return "bool";
        case FarmValue::Option: return arg.option->type == OptionType::Integer ? "int" : "float";
    }
    return "?";
}

// The value when the flag is absent: the text's default, false for a switch, and for an
// option the value that stands for unset where the schema lets it be unset.
py::object defaultValue(const FarmTaskArgument& arg) {
    switch (arg.value) {
        case FarmValue::Text: return arg.default_text ? py::object(py::str(arg.default_text)) : py::none();
        case FarmValue::Switch: return py::bool_(false);
        case FarmValue::Option:
            return arg.option->nullable ? py::object(py::float_(farmUnsetValue(*arg.option))) : py::none();
    }
    return py::none();
}

py::tuple commands(const FarmTaskArgument& arg) {
    py::list out;
    if (arg.run) out.append("run");
    if (arg.assemble) out.append("assemble");
    return py::tuple(out);
}

}  // namespace

void bindFarmTask(py::module_& m) {
    py::class_<FarmTaskArgument>(m, "FarmTaskArgument", "One flag of the add-on's farm commands (read-only).")
        .def_property_readonly("flag", [](const FarmTaskArgument& a) { return a.flag; })
        .def_property_readonly("aliases", [](const FarmTaskArgument& a) { return a.aliases; })
        .def_property_readonly("commands", &commands, "The farm commands that take it: run, assemble.")
        .def_property_readonly("required", [](const FarmTaskArgument& a) { return a.required; })
        .def_property_readonly("type", &valueType, "str, int, float, or bool (a switch: the flag alone)")
        .def_property_readonly("default", &defaultValue, "The value when the flag is absent.")
        .def_property_readonly("help", [](const FarmTaskArgument& a) { return a.help; })
        .def("__repr__", [](const FarmTaskArgument& a) { return "<hyvox.FarmTaskArgument " + a.flag + ">"; });
    py::list table;
    for (const FarmTaskArgument& arg : farmTaskArguments())
        table.append(py::cast(&arg, py::return_value_policy::reference));
    m.attr("FARM_TASK_ARGUMENTS") = py::tuple(table);
}

}  // namespace hyvox::python
