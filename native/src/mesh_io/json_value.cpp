// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh_io/json_value.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_set>

#include "mesh_io/parse_number.h"

namespace hyvox::mesh_io {

const JsonValue* JsonValue::find(std::string_view key) const {
    for (const auto& [name, value] : members_)
        if (name == key) return &value;
    return nullptr;
}

class JsonParser {
public:
    JsonParser(const char* data, std::size_t size) : begin_(data), pos_(data), end_(data + size) {}

    JsonValue parseDocument() {
        JsonValue value = parseValue(0);
        skipSpace();
        if (pos_ != end_) fail("text after the JSON value");
        return value;
    }

private:
    static constexpr int kMaxDepth = 64;
    // About 100 bytes each: a glTF's JSON holds thousands; millions would be data, not a
    // scene description, and could take 50 times the text.
    static constexpr std::size_t kMaxValues = std::size_t(1) << 23;

    [[noreturn]] void fail(const std::string& what) const {
        throw JsonError{"byte " + std::to_string(pos_ - begin_) + ": " + what};
    }

    void skipSpace() {
        while (pos_ < end_ && (*pos_ == ' ' || *pos_ == '\t' || *pos_ == '\n' || *pos_ == '\r')) ++pos_;
    }

    bool literal(const char* word) {
        const std::size_t n = std::strlen(word);
        if (std::size_t(end_ - pos_) < n || std::memcmp(pos_, word, n) != 0) return false;
        pos_ += n;
        return true;
    }

    JsonValue parseValue(int depth) {
        if (depth > kMaxDepth) fail("nested more than 64 deep");
        if (++values_ > kMaxValues) fail("more than 8388608 values");
        skipSpace();
        if (pos_ == end_) fail("the text ends where a value was expected");
        JsonValue value;
        switch (*pos_) {
            case '{': parseObject(value, depth); break;
            case '[': parseArray(value, depth); break;
            case '"':
                value.type_ = JsonValue::Type::String;
                value.string_ = parseString();
                break;
            case 't':
            case 'f':
                value.type_ = JsonValue::Type::Bool;
                value.boolean_ = *pos_ == 't';
                if (!literal(value.boolean_ ? "true" : "false")) fail("not a JSON value");
                break;
            case 'n':
                if (!literal("null")) fail("not a JSON value");
                break;
            default: value.type_ = JsonValue::Type::Number; value.number_ = parseNumber();
        }
        return value;
    }

    void parseObject(JsonValue& value, int depth) {
        value.type_ = JsonValue::Type::Object;
        ++pos_;
        skipSpace();
        if (pos_ < end_ && *pos_ == '}') {
            ++pos_;
            return;
        }
        std::unordered_set<std::string> keys;
        for (;;) {
            skipSpace();
            if (pos_ == end_ || *pos_ != '"') fail("an object member needs a string key");
            std::string key = parseString();
            if (!keys.insert(key).second) fail("the key \"" + key.substr(0, 40) + "\" appears twice");
            skipSpace();
            if (pos_ == end_ || *pos_ != ':') fail("':' expected after an object key");
            ++pos_;
            JsonValue member = parseValue(depth + 1);
            value.members_.emplace_back(std::move(key), std::move(member));
            skipSpace();
            if (pos_ == end_) fail("the text ends inside an object");
            if (*pos_ == ',') {
                ++pos_;
                continue;
            }
            if (*pos_ != '}') fail("',' or '}' expected in an object");
            ++pos_;
            return;
        }
    }

    void parseArray(JsonValue& value, int depth) {
        value.type_ = JsonValue::Type::Array;
        ++pos_;
        skipSpace();
        if (pos_ < end_ && *pos_ == ']') {
            ++pos_;
            return;
        }
        for (;;) {
            value.items_.push_back(parseValue(depth + 1));
            skipSpace();
            if (pos_ == end_) fail("the text ends inside an array");
            if (*pos_ == ',') {
                ++pos_;
                continue;
            }
            if (*pos_ != ']') fail("',' or ']' expected in an array");
            ++pos_;
            return;
        }
    }

    // The grammar's number: -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?
    double parseNumber() {
        const char* start = pos_;
        auto digits = [&] {
            const char* first = pos_;
            while (pos_ < end_ && *pos_ >= '0' && *pos_ <= '9') ++pos_;
            return pos_ > first;
        };
        if (pos_ < end_ && *pos_ == '-') ++pos_;
        if (pos_ < end_ && *pos_ == '0')
            ++pos_;
        else if (!digits())
            fail("not a JSON value");
        if (pos_ < end_ && *pos_ == '.') {
            ++pos_;
            if (!digits()) fail("a number needs digits after its '.'");
        }
        if (pos_ < end_ && (*pos_ == 'e' || *pos_ == 'E')) {
            ++pos_;
            if (pos_ < end_ && (*pos_ == '+' || *pos_ == '-')) ++pos_;
            if (!digits()) fail("a number needs digits in its exponent");
        }
        double value = 0;
        // Out of range (1e999): not a number glTF could use.
        if (!parseWholeNumber(start, pos_, value) || !std::isfinite(value)) fail("a number out of range");
        return value;
    }

    static void appendUtf8(std::string& out, std::uint32_t code) {
        if (code < 0x80) {
            out += char(code);
        } else if (code < 0x800) {
            out += char(0xC0 | (code >> 6));
            out += char(0x80 | (code & 0x3F));
        } else if (code < 0x10000) {
            out += char(0xE0 | (code >> 12));
            out += char(0x80 | ((code >> 6) & 0x3F));
            out += char(0x80 | (code & 0x3F));
        } else {
            out += char(0xF0 | (code >> 18));
            out += char(0x80 | ((code >> 12) & 0x3F));
            out += char(0x80 | ((code >> 6) & 0x3F));
            out += char(0x80 | (code & 0x3F));
        }
    }

    std::uint32_t hex4() {
        if (end_ - pos_ < 4) fail("the text ends inside a \\u escape");
        std::uint32_t code = 0;
        for (int i = 0; i < 4; ++i, ++pos_) {
            const char c = *pos_;
            const int digit = c >= '0' && c <= '9' ? c - '0'
                : c >= 'a' && c <= 'f'             ? c - 'a' + 10
                : c >= 'A' && c <= 'F'             ? c - 'A' + 10
                                                   : -1;
            if (digit < 0) fail("a \\u escape needs four hexadecimal digits");
            code = code * 16 + std::uint32_t(digit);
        }
        return code;
    }

    // One UTF-8 sequence at pos_, checked (no overlong forms, no surrogates, at most U+10FFFF).
    void copyUtf8(std::string& out) {
        const auto lead = static_cast<unsigned char>(*pos_);
        const int length = lead < 0x80 ? 1
            : (lead >> 5) == 0x6       ? 2
            : (lead >> 4) == 0xE       ? 3
            : (lead >> 3) == 0x1E      ? 4
                                       : 0;
        if (length == 0 || end_ - pos_ < length) fail("a string that is not valid UTF-8");
        std::uint32_t code = length == 1 ? lead : lead & (0x7F >> length);
        for (int i = 1; i < length; ++i) {
            const auto next = static_cast<unsigned char>(pos_[i]);
            if ((next >> 6) != 0x2) fail("a string that is not valid UTF-8");
            code = (code << 6) | (next & 0x3F);
        }
        static const std::uint32_t kLeast[5] = {0, 0, 0x80, 0x800, 0x10000};
        if (code < kLeast[length] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF))
            fail("a string that is not valid UTF-8");
        out.append(pos_, std::size_t(length));
        pos_ += length;
    }

    std::string parseString() {
        ++pos_;  // the opening quote
        std::string out;
        for (;;) {
            if (pos_ == end_) fail("the text ends inside a string");
            const char c = *pos_;
            if (c == '"') {
                ++pos_;
                return out;
            }
            if (static_cast<unsigned char>(c) < 0x20) fail("a control character inside a string");
            if (c != '\\') {
                copyUtf8(out);
                continue;
            }
            ++pos_;
            if (pos_ == end_) fail("the text ends inside a string");
            const char e = *pos_++;
            switch (e) {
                case '"': out += '"'; break;
                case '\\': out += '\\'; break;
                case '/': out += '/'; break;
                case 'b': out += '\b'; break;
                case 'f': out += '\f'; break;
                case 'n': out += '\n'; break;
                case 'r': out += '\r'; break;
                case 't': out += '\t'; break;
                case 'u': {
                    std::uint32_t code = hex4();
                    if (code >= 0xD800 && code <= 0xDBFF) {  // a high surrogate: its low one must follow
                        if (end_ - pos_ < 2 || pos_[0] != '\\' || pos_[1] != 'u')
                            fail("a lone surrogate in a \\u escape");
                        pos_ += 2;
                        const std::uint32_t low = hex4();
                        if (low < 0xDC00 || low > 0xDFFF) fail("a lone surrogate in a \\u escape");
                        code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
                    } else if (code >= 0xDC00 && code <= 0xDFFF) {
                        fail("a lone surrogate in a \\u escape");
                    }
                    appendUtf8(out, code);
                    break;
                }
                default: --pos_; fail("an unknown escape in a string");
            }
        }
    }

    const char* begin_;
    const char* pos_;
    const char* end_;
    std::size_t values_ = 0;
};

JsonValue parseJson(const char* data, std::size_t size) { return JsonParser(data, size).parseDocument(); }

}  // namespace hyvox::mesh_io
