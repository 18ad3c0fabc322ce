// SPDX-License-Identifier: GPL-3.0-or-later
// The text readers' number parser (mesh_io/parse_number.h), which every platform's build uses,
// against glibc's strtod and strtof in the C locale: correctly rounded, so the oracle of the
// exact value. Edge cases (the limits, ties, subnormals, long digit strings, overflow and
// underflow, malformed words) and many random numbers, as doubles and as floats.
#include <cctype>
#include <cerrno>
#include <clocale>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include <gtest/gtest.h>

#include "mesh_io/parse_number.h"

namespace {

using hyvox::mesh_io::parseWholeNumber;

// What the parser must answer for `text`, from the C library: `ok == false` where the text is
// not one number or its value is out of range (overflow, or zero from non-zero digits).
template <typename T>
struct Expected {
    bool ok;
    T value;
};

template <typename T>
Expected<T> oracle(const std::string& text) {
    errno = 0;
    char* end = nullptr;
    const T value = std::is_same_v<T, float> ? T(std::strtof(text.c_str(), &end)) : T(std::strtod(text.c_str(), &end));
    if (text.empty() || end != text.c_str() + text.size()) return {false, 0};
    // strtod also takes leading blanks, a '+' and hexadecimal; a number word has none of them.
    if (std::isspace(static_cast<unsigned char>(text[0])) || text[0] == '+' ||
        text.find_first_of("xX") != std::string::npos)
        return {false, 0};
    // Out of range as the C library reports it: ERANGE with an infinite result (overflow) or a
    // zero one (underflow; a subnormal result sets ERANGE too, and is a number).
    if (errno == ERANGE && (std::isinf(value) || value == 0)) return {false, 0};
    return {true, value};
}

template <typename T>
std::uint64_t bitsOf(T value) {
    using Bits = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
    Bits bits;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

template <typename T>
void expectSame(const std::string& text) {
    const Expected<T> want = oracle<T>(text);
    T got = T(-12345);
    const bool ok = parseWholeNumber(text.data(), text.data() + text.size(), got);
    ASSERT_EQ(ok, want.ok) << "'" << text << "'";
    if (!ok) return;
    if (std::isnan(want.value)) {
        EXPECT_TRUE(std::isnan(got)) << text;
        return;
    }
    // Bit for bit: the same double, the sign of zero included.
    EXPECT_EQ(bitsOf(got), bitsOf(want.value)) << "'" << text << "': " << got << " vs " << want.value;
}

class ParseNumberTest : public ::testing::Test {
protected:
    void SetUp() override { std::setlocale(LC_NUMERIC, "C"); }
};

const std::vector<std::string> kEdgeCases = {
    "0",
    "-0",
    "0.0",
    "-0.0",
    "1",
    "-1",
    "0.1",
    "0.5",
    ".5",
    "5.",
    "1e0",
    "1E0",
    "1e+0",
    "1e-0",
    "123456789",
    "0.30000000000000004",
    "9007199254740993",
    "9007199254740992.5",
    "4503599627370496.5",
    "1.7976931348623157e308",
    "1.7976931348623158e308",
    "1.797693134862315807e308",
    "1.8e308",
    "1e309",
    "2.2250738585072014e-308",
    "2.2250738585072011e-308",
    "4.9406564584124654e-324",
    "2.4703282292062328e-324",
    "2.4703282292062327e-324",
    "1e-320",
    "1e-400",
    "-1e-400",
    "0e-400",
    "0e400",
    "1e400",
    "-1e400",
    "3.4028234663852886e38",
    "3.4028235677973366e38",
    "3.5e38",
    "1.17549435e-38",
    "1.4e-45",
    "7e-46",
    "1e-46",
    "inf",
    "-inf",
    "infinity",
    "INF",
    "nan",
    "-nan",
    "NaN",
    "",
    "e5",
    "1e",
    "1e+",
    "1.2.3",
    "--1",
    "+1",
    "1 ",
    " 1",
    "0x1p3",
    "1,5",
    "1e5x",
    ".",
    "-",
    "e",
    "1_0",
    std::string(800, '1'),
    "0." + std::string(400, '0') + "1",
    std::string(310, '9') + ".5",
    "1" + std::string(30, '0') + "e-30",
    "0.000000000000000000000000000000000000000000001e45",
};

TEST_F(ParseNumberTest, EdgeCasesAsDoubles) {
    for (const auto& text : kEdgeCases) expectSame<double>(text);
}

TEST_F(ParseNumberTest, EdgeCasesAsFloats) {
    for (const auto& text : kEdgeCases) expectSame<float>(text);
}

TEST_F(ParseNumberTest, RandomDoublesPrintedAndReadBack) {
    std::mt19937_64 random(20240501);
    char buffer[64];
    for (int i = 0; i < 200000; ++i) {
        double value;
        const std::uint64_t bits = random();
        std::memcpy(&value, &bits, sizeof value);
        if (!std::isfinite(value)) continue;
        const int digits = 1 + int(random() % 17);
        std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
        expectSame<double>(buffer);
        expectSame<float>(buffer);
    }
}

TEST_F(ParseNumberTest, RandomDecimalStrings) {
    std::mt19937_64 random(7);
    for (int i = 0; i < 100000; ++i) {
        std::string text = random() % 2 ? "-" : "";
        const int before = int(random() % 25), after = int(random() % 25);
        for (int d = 0; d < before; ++d) text += char('0' + random() % 10);
        if (after > 0 || before == 0) {
            text += '.';
            for (int d = 0; d < after; ++d) text += char('0' + random() % 10);
            if (after == 0) text += '0';
        }
        if (random() % 3) text += "e" + std::to_string(int(random() % 700) - 350);
        expectSame<double>(text);
        expectSame<float>(text);
    }
}

TEST_F(ParseNumberTest, Integers) {
    for (const char* text : {"0", "42", "-7", "2147483647", "4294967295", "18446744073709551615"}) {
        std::uint64_t u = 0;
        std::int64_t s = 0;
        const char* end = text + std::strlen(text);
        EXPECT_EQ(parseWholeNumber(text, end, u), text[0] != '-') << text;
        EXPECT_EQ(parseWholeNumber(text, end, s), std::strcmp(text, "18446744073709551615") != 0) << text;
    }
    int i = 0;
    for (const char* text : {"", "1.5", "1e3", "2147483648", "+1", "0x10", "1 "})
        EXPECT_FALSE(parseWholeNumber(text, text + std::strlen(text), i)) << text;
}

}  // namespace
