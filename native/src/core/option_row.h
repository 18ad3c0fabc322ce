// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The builder of the option schema's rows (option_schema.cpp), so that each row names what
// each of its values is.
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "hyvox/option_schema.h"

namespace hyvox {

// One row of the schema, each value set by name: Option("padding").integer(0, 1024).group("grid")...
// What a row does not set keeps OptionSpec's default (not nullable, no choices, no aliases,
// no environment variable, no field of that struct, any text).
class Option {
public:
    explicit Option(const char* name) {
        spec_.name = name;
        spec_.unit = "";
    }
    // The value's kind, with its limits or choices.
    Option& integer(double min, double max) { return limits(OptionType::Integer, min, max); }
    Option& number(double min, double max) { return limits(OptionType::Number, min, max); }
    Option& excludingMin() {  // a Number above min
        spec_.min_exclusive = true;
        return *this;
    }
    Option& flag() {
        spec_.type = OptionType::Flag;
        return *this;
    }
    Option& text() {
        spec_.type = OptionType::Text;
        return *this;
    }
    Option& vector3() {
        spec_.type = OptionType::Vector3;
        return *this;
    }
    Option& box() {
        spec_.type = OptionType::Box;
        return *this;
    }
    Option& choice(std::vector<const char*> names) { return named(OptionType::Choice, std::move(names)); }
    Option& choiceList(std::vector<const char*> names) { return named(OptionType::Choices, std::move(names)); }
    // How front doors show it.
    Option& group(const char* group) {
        spec_.group = group;
        return *this;
    }
    Option& label(const char* label) {
        spec_.label = label;
        return *this;
    }
    Option& unit(const char* unit) {
        spec_.unit = unit;
        return *this;
    }
    Option& help(const char* help) {
        spec_.help = help;
        return *this;
    }
    Option& nullable() {
        spec_.nullable = true;
        return *this;
    }
    Option& cliAlias(const char* flag) {
        spec_.cli_aliases.push_back(flag);
        return *this;
    }
    Option& env(const char* variable) {
        spec_.env = variable;
        return *this;
    }
    // The fields behind it (HYVOX_FIELD, HYVOX_WRITE_FIELD).
    Option& field(OptionValue (*get)(const VoxelizeOptions&), void (*put)(VoxelizeOptions&, const OptionValue&)) {
        spec_.get = get;
        spec_.put = put;
        return *this;
    }
    Option& writeField(OptionValue (*get)(const WriteOptions&), void (*put)(WriteOptions&, const OptionValue&)) {
        spec_.get_write = get;
        spec_.put_write = put;
        return *this;
    }
    // A Text of a form of its own: the form for a usage line, the rule for messages, the test.
    Option& textForm(const char* form, const char* rule, bool (*valid)(const std::string&)) {
        spec_.text_form = form;
        spec_.text_rule = rule;
        spec_.text_valid = valid;
        return *this;
    }

    // The finished row; a row without its group, label or help is a mistake in this file.
    OptionSpec spec() const {
        if (!spec_.group || !spec_.label || !spec_.help)
            throw std::logic_error(std::string("option schema: ") + spec_.name + " lacks its group, label or help");
        return spec_;
    }

private:
    Option& limits(OptionType type, double min, double max) {
        spec_.type = type;
        spec_.min = min;
        spec_.max = max;
        return *this;
    }
    Option& named(OptionType type, std::vector<const char*> names) {
        spec_.type = type;
        spec_.choices = std::move(names);
        return *this;
    }

    OptionSpec spec_{};
};

}  // namespace hyvox
