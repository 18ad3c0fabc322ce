// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A strict JSON parser (RFC 8259) for the glTF reader: the whole text must be one value,
// strings must be valid UTF-8 with valid escapes, numbers as the grammar writes them, no
// duplicate keys, nesting at most 64 deep, at most 2^23 values. Any other text is a JsonError saying where, never
// a crash or a hang; the tree takes memory in proportion to the text.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hyvox::mesh_io {

struct JsonError {
    std::string what;  // "byte N: ..."
};

class JsonValue {
public:
    enum class Type { Null, Bool, Number, String, Array, Object };

    Type type() const { return type_; }
    bool isNumber() const { return type_ == Type::Number; }
    bool isString() const { return type_ == Type::String; }
    bool isArray() const { return type_ == Type::Array; }
    bool isObject() const { return type_ == Type::Object; }

    double number() const { return number_; }
    bool boolean() const { return boolean_; }
    const std::string& string() const { return string_; }
    const std::vector<JsonValue>& items() const { return items_; }                              // an array's
    const std::vector<std::pair<std::string, JsonValue>>& members() const { return members_; }  // an object's

    // An object's member, or null when it has none of that name (or is not an object).
    const JsonValue* find(std::string_view key) const;

private:
    friend class JsonParser;
    Type type_ = Type::Null;
    bool boolean_ = false;
    double number_ = 0;
    std::string string_;
    std::vector<JsonValue> items_;
    std::vector<std::pair<std::string, JsonValue>> members_;
};

// Parses [data, data + size) as one JSON value (whitespace around it allowed).
JsonValue parseJson(const char* data, std::size_t size);

}  // namespace hyvox::mesh_io
