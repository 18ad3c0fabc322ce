// SPDX-License-Identifier: GPL-3.0-or-later
#include "os/shared_library.h"

#include <dlfcn.h>
#include <sys/stat.h>

#include <cstdlib>

namespace hyvox::os {

void* openLibrary(const std::string& path, std::string& error) {
    // RTLD_LOCAL: its symbols never stand in for anyone else's. RTLD_NOW: a missing symbol
    // fails here, not at its first call.
    void* library = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!library) {
        const char* why = ::dlerror();
        error = why ? why : "unknown error";
    }
    return library;
}

void closeLibrary(void* library) { ::dlclose(library); }

void* librarySymbol(void* library, const char* symbol) {
    ::dlerror();
    return ::dlsym(library, symbol);
}

std::string thisBinaryPath() {
    Dl_info self{};
    if (!::dladdr(reinterpret_cast<void*>(&thisBinaryPath), &self) || !self.dli_fname || !*self.dli_fname) return "";
    // dli_fname is the path the binary was loaded by (absolute for shared objects; for a
    // program, as it was started): resolved, so a symlink to the CLI finds its plugins.
    std::string binary = self.dli_fname;
    if (char* real = ::realpath(binary.c_str(), nullptr)) {
        binary = real;
        std::free(real);
    }
    return binary;
}

bool isRegularFile(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

}  // namespace hyvox::os
