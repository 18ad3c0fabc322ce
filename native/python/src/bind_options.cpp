// SPDX-License-Identifier: GPL-3.0-or-later
// hyvox._core.OPTIONS (the options schema as OptionSpec objects) and hyvox._core.Options
// (the native options struct, filled by schema name). Python values are turned into the
// schema's value types here, and checked by the schema, so Python gets the same messages
// as the CLI and the Blender add-on.
#include <pybind11/stl.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "bindings.h"
#include "hyvox/errors.h"
#include "hyvox/option_schema.h"

namespace hyvox::python {
namespace {

const char* typeName(OptionType type) {
    switch (type) {
        case OptionType::Integer: return "int";
        case OptionType::Number: return "float";
        case OptionType::Flag: return "bool";
        case OptionType::Text: return "str";
        case OptionType::Choice: return "choice";
        case OptionType::Choices: return "choices";
        case OptionType::Vector3: return "vector3";
        case OptionType::Box: return "box";
    }
    return "?";
}

[[noreturn]] void refuseType(const OptionSpec& spec, const py::handle& value) {
    throw py::type_error(std::string(spec.name) + " must be " + describeOption(spec) + ", got " +
                         py::repr(value).cast<std::string>());
}

bool isNumber(const py::handle& v) {
    return !py::isinstance<py::bool_>(v) && !py::isinstance<py::str>(v) &&
        (py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v) || py::hasattr(v, "__float__"));
}

[[noreturn]] void refuseValue(const OptionSpec& spec, const py::handle& value) {
    throw InvalidInput(std::string(spec.name) + " must be " + describeOption(spec) + ", got " +
                       py::repr(value).cast<std::string>());
}

// A sequence of three numbers; a sequence of another length or with other items is a
// ValueError (the right kind, a wrong value), anything else a TypeError.
std::array<double, 3> vector3(const OptionSpec& spec, const py::handle& value, const py::handle& whole) {
    if (py::isinstance<py::str>(value) || !py::isinstance<py::sequence>(value)) refuseType(spec, whole);
    const auto items = py::reinterpret_borrow<py::sequence>(value);
    if (items.size() != 3) refuseValue(spec, whole);
    std::array<double, 3> out{};
    for (std::size_t a = 0; a < 3; ++a) {
        if (!isNumber(items[a])) refuseValue(spec, whole);
        out[a] = items[a].cast<double>();
    }
    return out;
}

// The Python value as the spec's value type; TypeError for a value of another kind.
OptionValue fromPython(const OptionSpec& spec, const py::handle& value) {
    if (value.is_none()) return std::monostate{};
    switch (spec.type) {
        case OptionType::Integer:
            // int and numpy integers (they have __index__), not bool and not float.
            if (py::isinstance<py::bool_>(value) || !py::hasattr(value, "__index__")) refuseType(spec, value);
            {
                const auto index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
                if (!index) throw py::error_already_set();
                const long long v = PyLong_AsLongLong(index.ptr());
                if (v == -1 && PyErr_Occurred()) {  // beyond 64 bits: out of every limit
                    PyErr_Clear();
                    refuseValue(spec, value);
                }
                return std::int64_t(v);
            }
        case OptionType::Number:
            if (!isNumber(value)) refuseType(spec, value);
            return value.cast<double>();
        case OptionType::Flag:
            if (!py::isinstance<py::bool_>(value) && std::string(py::str(value.get_type().attr("__name__"))) != "bool_")
                refuseType(spec, value);
            return PyObject_IsTrue(value.ptr()) == 1;
        case OptionType::Text:
        case OptionType::Choice:
            if (!py::isinstance<py::str>(value)) refuseType(spec, value);
            return value.cast<std::string>();
        case OptionType::Choices: {
            // The schema's text form ("color,sdf"), or a sequence of names joined into it.
            if (py::isinstance<py::str>(value)) return value.cast<std::string>();
            if (!py::isinstance<py::sequence>(value)) refuseType(spec, value);
            std::string text;
            for (const py::handle item : py::reinterpret_borrow<py::sequence>(value)) {
                if (!py::isinstance<py::str>(item)) refuseType(spec, value);
                text += (text.empty() ? "" : ",") + item.cast<std::string>();
            }
            return text;
        }
        case OptionType::Vector3: return vector3(spec, value, value);
        case OptionType::Box: {
            if (py::isinstance<py::str>(value) || !py::isinstance<py::sequence>(value)) refuseType(spec, value);
            const auto corners = py::reinterpret_borrow<py::sequence>(value);
            if (corners.size() != 2) refuseValue(spec, value);
            return Bounds{vector3(spec, corners[0], value), vector3(spec, corners[1], value)};
        }
    }
    refuseType(spec, value);
}

py::object toPython(const OptionValue& value) {
    struct ToPython {
        py::object operator()(std::monostate) const { return py::none(); }
        py::object operator()(std::int64_t v) const { return py::int_(v); }
        py::object operator()(double v) const { return py::float_(v); }
        py::object operator()(bool v) const { return py::bool_(v); }
        py::object operator()(const std::string& v) const { return py::str(v); }
        py::object operator()(const std::array<double, 3>& v) const { return py::make_tuple(v[0], v[1], v[2]); }
        py::object operator()(const Bounds& b) const { return py::make_tuple((*this)(b.min), (*this)(b.max)); }
    };
    return std::visit(ToPython{}, value);
}

// Unknown names are a TypeError, as for any unexpected keyword argument, with the schema's
// message.
const OptionSpec& specNamed(const std::string& name) {
    try {
        return findOption(name);
    } catch (const InvalidInput& e) {
        throw py::type_error(e.what());
    }
}

void setFromPython(VoxelizeOptions& options, const std::string& name, const py::handle& value) {
    const OptionSpec& spec = specNamed(name);
    if (!spec.isVoxelizeOption())
        throw py::type_error(name + " is an option of VoxelGrid.write_vdb(), not of voxelize()");
    setOption(options, name, fromPython(spec, value));
}

// The schema's entries of one struct, as OptionSpec objects (references into the schema).
py::tuple specsWhere(bool (OptionSpec::*belongs)() const) {
    py::list specs;
    for (const OptionSpec& spec : optionSchema())
        if ((spec.*belongs)()) specs.append(py::cast(&spec, py::return_value_policy::reference));
    return py::tuple(specs);
}

}  // namespace

WriteOptions writeOptions(const VoxelizeOptions& voxelized, const py::dict& given) {
    for (const auto& [name, value] : given) {
        const OptionSpec& spec = specNamed(py::str(name));
        if (!spec.isWriteOption())
            throw py::type_error(std::string(spec.name) + " is an option of voxelize(), not of VoxelGrid.write_vdb()");
    }
    WriteOptions options;
    for (const OptionSpec& spec : optionSchema()) {
        if (!spec.isWriteOption()) continue;
        const py::object value = given.contains(spec.name) ? py::object(given[spec.name]) : py::none();
        if (!value.is_none())
            setOption(options, spec.name, fromPython(spec, value));
        else if (spec.isVoxelizeOption())
            spec.put_write(options, spec.get(voxelized));
    }
    return options;
}

void bindOptions(py::module_& m) {
    py::class_<OptionSpec>(m, "OptionSpec", "One entry of the options schema (read-only).")
        .def_property_readonly("name", [](const OptionSpec& s) { return s.name; })
        .def_property_readonly(
            "type", [](const OptionSpec& s) { return typeName(s.type); },
            "int, float, bool, str, choice, choices (a comma list), vector3 or box")
        .def_property_readonly("group", [](const OptionSpec& s) { return s.group; })
        .def_property_readonly("label", [](const OptionSpec& s) { return s.label; })
        .def_property_readonly("unit", [](const OptionSpec& s) { return s.unit; })
        .def_property_readonly("help", [](const OptionSpec& s) { return s.help; })
        .def_property_readonly("nullable", [](const OptionSpec& s) { return s.nullable; })
        .def_property_readonly("min", [](const OptionSpec& s) { return s.min; })
        .def_property_readonly("max", [](const OptionSpec& s) { return s.max; })
        .def_property_readonly("min_exclusive", [](const OptionSpec& s) { return s.min_exclusive; })
        .def_property_readonly(
            "choices", [](const OptionSpec& s) { return std::vector<std::string>(s.choices.begin(), s.choices.end()); })
        .def_property_readonly("cli_flag", &OptionSpec::cliFlag)
        .def_property_readonly(
            "cli_aliases",
            [](const OptionSpec& s) { return std::vector<std::string>(s.cli_aliases.begin(), s.cli_aliases.end()); })
        .def_property_readonly("env",
                               [](const OptionSpec& s) { return s.env ? py::object(py::str(s.env)) : py::none(); })
        .def_property_readonly(
            "default", [](const OptionSpec& s) { return toPython(s.defaultValue()); },
            "The native default (None for nullable options: derived at run time).")
        .def_property_readonly("requirement", &describeOption, "What a valid value is, as error messages say it.")
        .def(
            "applies_to",
            [](const OptionSpec& s, const std::string& method) { return optionAppliesTo(s, parseMethod(method)); },
            py::arg("method"),
            "Whether the option changes what `method` does (the rule behind the CLI's and voxelize()'s "
            "'does not apply' warnings); ValueError for an unknown method.")
        .def("__repr__", [](const OptionSpec& s) { return std::string("<hyvox.OptionSpec ") + s.name + ">"; });

    // voxelize()'s keywords and write_vdb()'s: threads and memory_budget_mib are both.
    m.attr("OPTIONS") = specsWhere(&OptionSpec::isVoxelizeOption);
    m.attr("WRITE_OPTIONS") = specsWhere(&OptionSpec::isWriteOption);

    py::class_<VoxelizeOptions>(m, "Options", "The options of one voxelization, by schema name.")
        .def(py::init([](const py::kwargs& kwargs) {
                 VoxelizeOptions options;
                 for (const auto& [name, value] : kwargs) setFromPython(options, py::str(name), value);
                 return options;
             }),
             "Options(**values): unset names keep the native default.")
        .def("set", &setFromPython, py::arg("name"), py::arg("value"),
             "Set one option; ValueError out of its limits, TypeError for another kind of value or an "
             "unknown name. None restores the default.")
        .def("get", [](const VoxelizeOptions& o, const std::string& name) { return toPython(specNamed(name).get(o)); })
        .def(
            "apply_environment",
            [](VoxelizeOptions& o) {
                applyEnvironment(o, [](const char* variable) -> const char* { return std::getenv(variable); });
            },
            "Set the options whose environment variable (OptionSpec.env) is set.")
        .def("to_dict", [](const VoxelizeOptions& o) {
            py::dict out;
            for (const OptionSpec& spec : optionSchema())
                if (spec.isVoxelizeOption()) out[spec.name] = toPython(spec.get(o));
            return out;
        });
    m.def(
        "check_option",
        [](const std::string& name, const py::handle& value) {
            const OptionSpec& spec = specNamed(name);
            checkOption(spec, fromPython(spec, value));
        },
        py::arg("name"), py::arg("value"),
        "Raise the error voxelize() would raise for this value (ValueError / TypeError); None if valid.");
}

}  // namespace hyvox::python
