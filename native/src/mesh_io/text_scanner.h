// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Words and numbers out of a text mesh file (ASCII PLY, OBJ), with the line number kept so
// every error can say where the file is wrong. Numbers are parsed by parse_number.h:
// strict (the whole word must be the number, "a" is never 0), locale-independent and
// correctly rounded.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "mesh_io/parse_number.h"

namespace hyvox::mesh_io {

class TextScanner {
public:
    TextScanner(const char* begin, const char* end, std::size_t first_line = 1)
        : pos_(begin), end_(end), line_(first_line) {}

    // The next word on the current line; false (and the scanner still on that line) when
    // the line has no more words.
    bool wordOnLine(std::string_view& word) {
        while (pos_ < end_ && (*pos_ == ' ' || *pos_ == '\t' || *pos_ == '\r')) ++pos_;
        if (pos_ == end_ || *pos_ == '\n') return false;
        const char* start = pos_;
        while (pos_ < end_ && !isSpace(*pos_)) ++pos_;
        word = std::string_view(start, std::size_t(pos_ - start));
        return true;
    }

    // The next word, on this line or a later one; false at the end of the text.
    bool word(std::string_view& out) {
        for (;;) {
            if (wordOnLine(out)) return true;
            if (!nextLine()) return false;
        }
    }

    // Skips the rest of the current line; false when there is no next line.
    bool nextLine() {
        while (pos_ < end_ && *pos_ != '\n') ++pos_;
        if (pos_ == end_) return false;
        ++pos_;
        ++line_;
        return true;
    }

    std::size_t line() const { return line_; }

private:
    static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

    const char* pos_;
    const char* end_;
    std::size_t line_;
};

// Whether the text ends inside a word (its last byte is no space or line end). A text mesh
// file cut inside its last number reads as another number, so the readers of formats without
// an end marker (ASCII PLY, OFF) refuse a last line that has no line end.
inline bool endsInsideAWord(const char* begin, const char* end) {
    if (begin == end) return false;
    const char last = end[-1];
    return last != ' ' && last != '\t' && last != '\r' && last != '\n';
}

inline constexpr const char* kCutInsideTheLastLine =
    "the file ends inside its last line, with no line end after it: it may have been cut there";

// Whole-word number parsing; false for anything that is not exactly one number in range.
// A leading '+' is accepted (from_chars does not, some exporters write it).
inline std::string_view withoutPlus(std::string_view word) {
    return word.size() > 1 && word[0] == '+' && word[1] != '-' ? word.substr(1) : word;
}

template <typename T>
bool parseNumber(std::string_view word, T& out) {
    word = withoutPlus(word);
    return parseWholeNumber(word.data(), word.data() + word.size(), out);
}

// A word from the file as it may appear in an error message: at most 40 characters, so a
// 300-digit number or a binary blob does not flood the message.
inline std::string quoteWord(std::string_view word) {
    std::string text(word.substr(0, 40));
    for (char& c : text)
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
    return "'" + text + (word.size() > 40 ? "...'" : "'");
}

}  // namespace hyvox::mesh_io
