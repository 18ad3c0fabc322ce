// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Parts of hyvox that need a large shared library are built as shared objects of their own
// ("plugins": libhyvox_<name>.so) and loaded the first time they are used, so a run that
// does not need them never loads those libraries. Process start is a large part of a small
// run, and the dynamic linker's work for those libraries (libassimp brings libdraco and more)
// is most of it (docs/why/startup.md).
//
//   libhyvox_gl_methods.so  the GL methods: triangle, fragment, hybrid, tessellation
//                           (core/gl_methods.h)
//
// The same folders hold the helper programs hyvox starts as processes of their own:
//   hyvox_assimp_reader     the mesh formats read through assimp (mesh_io/assimp_reader.h)
//
// Where a plugin is looked for, in order (the first folder that has the file is used):
//   - $HYVOX_PLUGIN_DIR, when set (only there: to point a relocated build at its plugins,
//     and for the tests of a missing plugin);
//   - the folder of the binary holding this code (the CLI, the Python module _core*.so),
//     and its parent (the wheel keeps the CLI in hyvox/bin/, the plugins in hyvox/);
//   - the build folder the plugins were built in (tests and benchmarks in the build tree).
//
// A plugin links its own copy of the hyvox code it uses (hidden): what crosses between it
// and its host are hyvox's plain types (meshes, jobs, stats, std::string and std::vector in
// its table: the same headers, compiler and flags), exceptions (GCC matches exception types
// by name across shared objects) and the host's Interrupter (a virtual call). State stays on
// one side: the GL worker threads, the cutoff cache and the GL object counts are the GL
// plugin's; the allocators hyvox uses are stateless (malloc, mmap).
//
// That the types are the same is checked before any of them crosses: every plugin carries
// the build id (hyvox_plugin_build_id, a plain C string), a hash of the compiler, its flags
// and the headers of native/include/hyvox and native/src/core (core/build_id.cmake), and a
// plugin whose id is not the host's is refused with an error naming both ids.
#include <string>

// A plugin's exported symbols: its entry point and its build id, the only ones it exports (its
// copies of hyvox's internals are hidden, hyvox_plugin() in CMakeLists.txt), declared
// extern "C" in a header both sides include.
#define HYVOX_PLUGIN_ENTRY __attribute__((visibility("default")))

// "hyvox-plugin-build-id=<32 hex digits>": defined in each plugin by core/plugin_build_id.cpp.
extern "C" HYVOX_PLUGIN_ENTRY const char hyvox_plugin_build_id[];

namespace hyvox {

// The address of `symbol` in plugin `name` ("gl_methods" -> libhyvox_gl_methods.so), loading the
// plugin on first use (thread-safe; it stays loaded). BackendError when the plugin or a
// library it needs cannot be loaded, or the plugin is from another build:
// "<purpose> needs libhyvox_<name>.so, ...: <reason>".
void* pluginSymbol(const std::string& name, const char* symbol, const std::string& purpose);

// This build's id, which each of its plugins carries (core/build_id.cmake).
const char* buildId();
// The path of `file` (a plugin or a helper program) in the first of the folders above that
// has it. BackendError when none has: "<purpose> needs <file>, which is not installed with
// hyvox (looked in ...)".
std::string pluginFile(const std::string& file, const std::string& purpose);

// Whether plugin `name` was loaded by this process (nothing is loaded to answer).
bool pluginLoaded(const std::string& name);

}  // namespace hyvox
