// SPDX-License-Identifier: GPL-3.0-or-later
#include "farm/yaml_writer.h"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "hyvox/json_text.h"

namespace hyvox::farm {

// A JSON string literal is also a YAML double-quoted scalar and a JavaScript string.
std::string quoted(const std::string& value) { return jsonQuote(value); }

std::string shortestNumber(double value) {
    char buf[32];
    for (int precision = 1; precision <= 17; ++precision) {
        std::snprintf(buf, sizeof buf, "%.*g", precision, value);
        if (std::strtod(buf, nullptr) == value) break;
    }
    return buf;
}

Yaml Yaml::text(const std::string& value) { return Yaml(Kind::Scalar, quoted(value)); }
Yaml Yaml::integer(std::int64_t value) { return Yaml(Kind::Scalar, std::to_string(value)); }
Yaml Yaml::number(double value) {
    std::string text = shortestNumber(value);
    if (text.find_first_of(".e") == std::string::npos) text += ".0";  // a float, also when whole
    return Yaml(Kind::Scalar, text);
}
Yaml Yaml::boolean(bool value) { return Yaml(Kind::Scalar, value ? "true" : "false"); }
Yaml Yaml::block(const std::string& lines) { return Yaml(Kind::Block, lines); }
Yaml Yaml::map() { return Yaml(Kind::Map); }
Yaml Yaml::list() { return Yaml(Kind::List); }
Yaml Yaml::texts(const std::vector<std::string>& values) {
    Yaml out = list();
    for (const std::string& v : values) out.push(text(v));
    return out;
}

Yaml& Yaml::add(const std::string& key, Yaml value) {
    if (kind_ != Kind::Map) throw std::logic_error("Yaml::add on a non-map");
    entries_.emplace_back(key, std::move(value));
    return *this;
}

Yaml& Yaml::push(Yaml value) {
    if (kind_ != Kind::List) throw std::logic_error("Yaml::push on a non-list");
    items_.push_back(std::move(value));
    return *this;
}

std::string Yaml::render() const {
    std::string out;
    renderInto(out, 0);
    return out;
}

// A map's entries or a list's items, each line at `indent` spaces.
void Yaml::renderInto(std::string& out, int indent) const {
    const std::string pad(std::size_t(indent), ' ');
    if (kind_ == Kind::Map) {
        for (const auto& [key, value] : entries_) {
            out += pad + key + ":";
            value.renderValue(out, indent);
        }
    } else if (kind_ == Kind::List) {
        for (const Yaml& item : items_) {
            out += pad + "-";
            if (item.kind_ == Kind::Map && !item.entries_.empty()) {
                // The first entry on the dash's line, the others under it.
                std::string nested;
                item.renderInto(nested, indent + 2);
                out += " " + nested.substr(std::size_t(indent) + 2);
            } else {
                item.renderValue(out, indent);
            }
        }
    }
}

void Yaml::renderValue(std::string& out, int indent) const {
    switch (kind_) {
        case Kind::Scalar: out += " " + scalar_ + "\n"; return;
        case Kind::Block: {
            out += " |\n";
            const std::string pad(std::size_t(indent) + 2, ' ');
            std::size_t begin = 0;
            while (begin < scalar_.size()) {
                std::size_t end = scalar_.find('\n', begin);
                if (end == std::string::npos) end = scalar_.size();
                const std::string line = scalar_.substr(begin, end - begin);
                out += (line.empty() ? "" : pad + line) + "\n";
                begin = end + 1;
            }
            return;
        }
        case Kind::Map:
            if (entries_.empty()) {
                out += " {}\n";
                return;
            }
            out += "\n";
            renderInto(out, indent + 2);
            return;
        case Kind::List:
            if (items_.empty()) {
                out += " []\n";
                return;
            }
            out += "\n";
            renderInto(out, indent + 2);
            return;
    }
}

}  // namespace hyvox::farm
