// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// GoogleTest printers for hyvox's option enums, found by argument-dependent lookup, so a
// parameterized test shows "thin" instead of "4-byte object <01-00 00-00>" in its name
// and in failure messages.
#include <ostream>

#include "hyvox/options.h"

namespace hyvox {

inline void PrintTo(Mode mode, std::ostream* os) { *os << toString(mode); }
inline void PrintTo(Method method, std::ostream* os) { *os << toString(method); }

}  // namespace hyvox
