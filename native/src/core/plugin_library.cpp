// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/plugin_library.h"

#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <vector>

#include "hyvox/errors.h"
#include "hyvox_build_id.h"
#include "os/shared_library.h"

namespace hyvox {
namespace {

std::string folderOf(const std::string& path) {
    const auto slash = path.find_last_of('/');
    return slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
}

// The folders to look in (plugin_library.h), in order.
std::vector<std::string> searchFolders() {
    if (const char* forced = std::getenv("HYVOX_PLUGIN_DIR"); forced && *forced) return {forced};
    std::vector<std::string> folders;
    if (const std::string binary = os::thisBinaryPath(); !binary.empty()) {
        folders.push_back(folderOf(binary));
        folders.push_back(folderOf(folders.back()));
    }
#ifdef HYVOX_BUILD_PLUGIN_DIR
    folders.push_back(HYVOX_BUILD_PLUGIN_DIR);
#endif
    return folders;
}

// Refuses (and unloads) a plugin that is not of this build: nothing of it has been called yet
// but its static initializers, which see none of the host's types.
void checkBuildId(void* handle, const std::string& path, const std::string& purpose) {
    const auto* id = static_cast<const char*>(os::librarySymbol(handle, "hyvox_plugin_build_id"));
    if (id && std::strcmp(id, HYVOX_BUILD_ID) == 0) return;
    const std::string what = id
        ? std::string("is from another hyvox build (") + id + "; this hyvox is " + HYVOX_BUILD_ID + ")"
        : std::string("has no hyvox build id (not a hyvox plugin)");
    os::closeLibrary(handle);
    throw BackendError(purpose + " needs " + path + ", which " + what +
                       ": install hyvox and its plugins from one build");
}

std::mutex mutex;
std::map<std::string, void*> loaded;  // name -> open library, never closed

void* load(const std::string& name, const std::string& purpose) {
    const std::string path = pluginFile("libhyvox_" + name + ".so", purpose);
    // Its symbols (its own copy of hyvox's internals, all hidden but the entry point) are
    // kept to itself.
    std::string why;
    void* handle = os::openLibrary(path, why);
    if (!handle) throw BackendError(purpose + " needs " + path + ", which cannot be loaded: " + why);
    checkBuildId(handle, path, purpose);
    return handle;
}

}  // namespace

std::string pluginFile(const std::string& file, const std::string& purpose) {
    std::string looked;
    for (const std::string& folder : searchFolders()) {
        const std::string path = folder + "/" + file;
        if (os::isRegularFile(path)) return path;
        looked += (looked.empty() ? "" : ", ") + folder;
    }
    throw BackendError(purpose + " needs " + file + ", which is not installed with hyvox (looked in " +
                       (looked.empty() ? std::string("no folder") : looked) + ")");
}

void* pluginSymbol(const std::string& name, const char* symbol, const std::string& purpose) {
    std::lock_guard<std::mutex> lock(mutex);
    void*& handle = loaded[name];
    if (!handle) {
        try {
            handle = load(name, purpose);
        } catch (...) {
            loaded.erase(name);
            throw;
        }
    }
    void* address = os::librarySymbol(handle, symbol);
    if (!address)
        throw BackendError(purpose + " needs the symbol " + symbol + " of libhyvox_" + name +
                           ".so, which does not have it (a plugin from another hyvox build?)");
    return address;
}

const char* buildId() { return HYVOX_BUILD_ID; }

bool pluginLoaded(const std::string& name) {
    std::lock_guard<std::mutex> lock(mutex);
    return loaded.count(name) != 0;
}

}  // namespace hyvox
