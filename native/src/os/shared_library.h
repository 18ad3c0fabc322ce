// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Shared libraries opened at run time (the plugins: core/plugin_library.h), and the file this
// code was loaded from (where the plugins are looked for).
#include <string>

namespace hyvox::os {

// Opens the shared library at `path` with every symbol resolved now and kept to itself (none
// of them stands in for anyone else's); null, with `error` saying why, when it cannot.
void* openLibrary(const std::string& path, std::string& error);
void closeLibrary(void* library);
// The address of `symbol` in an open library, or null when it has none.
void* librarySymbol(void* library, const char* symbol);

// The file of the binary holding this code (the program, or the shared library it is linked
// into), symlinks resolved; "" when the system does not say.
std::string thisBinaryPath();

// Whether `path` names a regular file (or a symlink to one).
bool isRegularFile(const std::string& path);

}  // namespace hyvox::os
