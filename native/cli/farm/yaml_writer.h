// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Just enough YAML for the job templates: maps that keep their order, lists, quoted
// scalars and literal blocks (the embedded scripts, kept readable as they are).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace hyvox::farm {

class Yaml {
public:
    static Yaml text(const std::string& value);  // "a \"quoted\" string"
    static Yaml integer(std::int64_t value);
    static Yaml number(double value);  // shortest text that reads back the same
    static Yaml boolean(bool value);
    static Yaml block(const std::string& lines);  // |  (a script; kept line for line)
    static Yaml map();
    static Yaml list();
    static Yaml texts(const std::vector<std::string>& values);  // a list of text scalars

    Yaml& add(const std::string& key, Yaml value);  // map: the next entry
    Yaml& push(Yaml value);                         // list: the next item

    std::string render() const;  // the document, ending in a newline

private:
    enum class Kind { Scalar, Block, Map, List };
    explicit Yaml(Kind kind, std::string scalar = {}) : kind_(kind), scalar_(std::move(scalar)) {}
    void renderInto(std::string& out, int indent) const;
    void renderValue(std::string& out, int indent) const;  // after "key:" or "- "

    Kind kind_;
    std::string scalar_;
    std::vector<std::pair<std::string, Yaml>> entries_;  // Map
    std::vector<Yaml> items_;                            // List
};

// "a \"quoted\" string" (JSON's escapes, which YAML's double-quoted scalars share; the job
// type's JavaScript uses them too).
std::string quoted(const std::string& value);
// The shortest decimal that reads back as `value` (finite values only).
std::string shortestNumber(double value);

}  // namespace hyvox::farm
