// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Numbers out of text, the same way on every platform: integers by std::from_chars, floating
// point by fast_float (libc++, the C++ runtime of the release builds, has no floating-point
// std::from_chars). Strict (all of [first, last) must be the one number), locale-independent and
// correctly rounded. A value too large for the type, or one that rounds to zero though it has a
// non-zero digit, is out of range (false), as the C++ standard library's from_chars says; the
// words inf and nan are numbers (the mesh checks refuse such vertices with their own message).
#include <charconv>
#include <cmath>
#include <system_error>
#include <type_traits>

#include <fast_float/fast_float.h>

namespace hyvox::mesh_io {

namespace detail {
// Whether the digits before any exponent hold a non-zero one: "0.000" is zero, "1e-400" is not.
inline bool hasNonZeroDigit(const char* first, const char* last) {
    for (; first != last && *first != 'e' && *first != 'E'; ++first)
        if (*first >= '1' && *first <= '9') return true;
    return false;
}
inline bool isWord(const char* first, const char* last, char letter) {  // inf, infinity, nan
    for (; first != last; ++first)
        if (*first == letter || *first == letter - 'a' + 'A') return true;
    return false;
}
}  // namespace detail

template <typename T>
bool parseWholeNumber(const char* first, const char* last, T& out) {
    if constexpr (std::is_floating_point_v<T>) {
        T value = 0;
        const auto result = fast_float::from_chars(first, last, value);
        if (result.ptr != last || first == last) return false;
        // fast_float releases differ in what they call out of range: decide it here.
        if (result.ec != std::errc() && result.ec != std::errc::result_out_of_range) return false;
        if (std::isinf(value) && !detail::isWord(first, last, 'i')) return false;  // overflow
        if (value == 0 && detail::hasNonZeroDigit(first, last)) return false;      // underflow
        out = value;
        return true;
    } else {
        const auto [ptr, error] = std::from_chars(first, last, out);
        return error == std::errc() && ptr == last;
    }
}

}  // namespace hyvox::mesh_io
