// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/options.h"

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

bool computesAttributes(Method method) {
    switch (method) {
        case Method::Cpu:
        case Method::Reference:
        case Method::Triangle:
        case Method::Fragment:
        case Method::Hybrid:
        case Method::Tessellation: return true;
    }
    return false;
}
Mode parseMode(const std::string& text) { return parseName(kModes, text, "mode"); }
Method parseMethod(const std::string& text) { return parseName(kMethods, text, "method"); }
std::vector<const char*> insideRuleNames() { return namesOf(kInsideRules); }
const char* toString(InsideRule rule) { return nameOf(kInsideRules, rule); }
InsideRule parseInsideRule(const std::string& text) { return parseName(kInsideRules, text, "inside rule"); }

}  // namespace hyvox
