// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// JSON text for the hand-written writers: the stats JSON, the benchmarks' results, and the
/// CLI's farm templates (a YAML double-quoted string is written as a JSON one).
#include <cstdio>
#include <string>

namespace hyvox {

/// `text` as a JSON string: quoted, with quotes, backslashes and control characters escaped.
inline std::string jsonQuote(const std::string& text) {
    std::string out = "\"";
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\r': out += "\\r"; break;
            case '\t': out += "\\t"; break;
            default:
                if (c < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", c);
                    out += buf;
                } else {
                    out += ch;
                }
        }
    }
    return out + "\"";
}

}  // namespace hyvox
