// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/options.h"

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "hyvox/errors.h"

namespace hyvox {
namespace {

constexpr std::array<std::pair<Mode, const char*>, 3> kModes{{
    {Mode::Conservative, "conservative"},
    {Mode::Thin, "thin"},
    {Mode::Solid, "solid"},
}};
constexpr std::array<std::pair<InsideRule, const char*>, 3> kInsideRules{{
    {InsideRule::Auto, "auto"},
    {InsideRule::Parity, "parity"},
    {InsideRule::Winding, "winding"},
}};
constexpr std::array<std::pair<Method, const char*>, 6> kMethods{{
    {Method::Cpu, "cpu"},
    {Method::Reference, "reference"},
    {Method::Triangle, "triangle"},
    {Method::Fragment, "fragment"},
    {Method::Hybrid, "hybrid"},
    {Method::Tessellation, "tessellation"},
}};

template <typename Enum, std::size_t N>
Enum parseName(const std::array<std::pair<Enum, const char*>, N>& table, const std::string& text, const char* what) {
    std::string choices;
    for (const auto& [value, name] : table) {
        if (text == name) return value;
        choices += choices.empty() ? name : std::string(", ") + name;
    }
    throw InvalidInput("unknown " + std::string(what) + " '" + text + "' (choose one of: " + choices + ")");
}

template <typename Enum, std::size_t N>
const char* nameOf(const std::array<std::pair<Enum, const char*>, N>& table, Enum value) {
    for (const auto& [v, name] : table)
        if (v == value) return name;
    return "?";
}

template <typename Enum, std::size_t N>
std::vector<const char*> namesOf(const std::array<std::pair<Enum, const char*>, N>& table) {
    std::vector<const char*> names;
    for (const auto& entry : table) names.push_back(entry.second);
    return names;
}

}  // namespace

std::vector<const char*> modeNames() { return namesOf(kModes); }
std::vector<const char*> methodNames() { return namesOf(kMethods); }
const char* toString(Mode mode) { return nameOf(kModes, mode); }
const char* toString(Method method) { return nameOf(kMethods, method); }

Mode parseMode(const std::string& text) { return parseName(kModes, text, "mode"); }
Method parseMethod(const std::string& text) { return parseName(kMethods, text, "method"); }
std::vector<const char*> insideRuleNames() { return namesOf(kInsideRules); }
const char* toString(InsideRule rule) { return nameOf(kInsideRules, rule); }
InsideRule parseInsideRule(const std::string& text) { return parseName(kInsideRules, text, "inside rule"); }

namespace {
constexpr std::array<std::pair<bool AttributeSet::*, const char*>, 3> kAttributes{{
    {&AttributeSet::color, "color"},
    {&AttributeSet::normal, "normal"},
    {&AttributeSet::sdf, "sdf"},
}};
}  // namespace

std::vector<const char*> attributeNames() { return namesOf(kAttributes); }

std::string toString(const AttributeSet& set) {
    std::string text;
    for (const auto& [member, name] : kAttributes)
        if (set.*member) text += (text.empty() ? "" : ",") + std::string(name);
    return text;
}

AttributeSet parseAttributeSet(const std::string& text) {
    AttributeSet set;
    std::size_t begin = 0;
    while (begin < text.size()) {
        const std::size_t comma = std::min(text.find(',', begin), text.size());
        const std::string name = text.substr(begin, comma - begin);
        bool known = false;
        std::string names;
        for (const auto& [member, known_name] : kAttributes) {
            if (name == known_name) {
                set.*member = true;
                known = true;
            }
            names += (names.empty() ? "" : ", ") + std::string(known_name);
        }
        if (!known)  // the schema's message (option_schema.cpp checks the option first)
            throw InvalidInput("unknown attributes '" + name + "' in '" + text + "' (a comma list of " + names + ")");
        begin = comma + 1;
    }
    return set;
}

}  // namespace hyvox
