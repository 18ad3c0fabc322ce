// SPDX-License-Identifier: GPL-3.0-or-later
// libhyvox.so is made of the static libraries of native/src (linked whole, CMakeLists.txt
// here); a shared library needs one source of its own, and this is it.
#include "hyvox/hyvox.h"
