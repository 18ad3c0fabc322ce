// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Parts of hyvox that need a large shared library are built as shared objects of their own
// ("plugins": libhyvox_<name>.so) and loaded the first time they are used, so a run that
// does not need them never loads those libraries. Process start is a large part of a small
// run: an empty program linked with libassimp (which brings libdraco and 8 more) costs
// 2.7 ms of CPU in the dynamic linker, with libepoxy 1.8 ms, with neither 0.45 ms
// (bench/README.md, "Process start").
//
//   libhyvox_gl_methods.so  the GL methods: triangle, fragment, hybrid, tessellation
//                           (voxelize/gl_methods.h)
//
// The same folders hold the helper programs hyvox starts as processes of their own:
//   hyvox_assimp_reader     the mesh formats read through assimp (io/assimp_reader.h)
//
// Where a plugin is looked for, in order (the first folder that has the file is used):
//   - $HYVOX_PLUGIN_DIR, when set (only there: to point a relocated build at its plugins,
//     and for the tests of a missing plugin);
//   - the folder of the binary holding this code (the CLI, the Python module _core*.so),
//     and its parent (the wheel keeps the CLI in hyvox/bin/, the plugins in hyvox/);
//   - the build folder the plugins were built in (tests and benchmarks in the build tree).
//
// A plugin links its own copy of the hyvox code it uses (hidden): what crosses between it
// and its host are hyvox's plain types (meshes, jobs, stats: the same headers, one build),
// exceptions (GCC matches exception types by name across shared objects) and the host's
// Interrupter (a virtual call). State stays on one side: the GL worker threads, the cutoff
// cache and the GL object counts are the GL plugin's; the allocators hyvox uses are
// stateless (malloc, mmap). A plugin from another build is not detected: the search looks
// beside the binary first, where a package puts its own.
#include <string>

// A plugin's entry point: the only symbol it exports (its copies of hyvox's internals are
// hidden, hyvox_plugin() in CMakeLists.txt), declared extern "C" in a header both sides include.
#define HYVOX_PLUGIN_ENTRY __attribute__((visibility("default")))

namespace hyvox {

// The address of `symbol` in plugin `name` ("gl_methods" -> libhyvox_gl_methods.so), loading the
// plugin on first use (thread-safe; it stays loaded). BackendError when the plugin or a
// library it needs cannot be loaded: "<purpose> needs libhyvox_<name>.so, ...: <reason>".
void* pluginSymbol(const std::string& name, const char* symbol, const std::string& purpose);

// The path of `file` (a plugin or a helper program) in the first of the folders above that
// has it. BackendError when none has: "<purpose> needs <file>, which is not installed with
// hyvox (looked in ...)".
std::string pluginFile(const std::string& file, const std::string& purpose);

// Whether plugin `name` was loaded by this process (nothing is loaded to answer).
bool pluginLoaded(const std::string& name);

}  // namespace hyvox
