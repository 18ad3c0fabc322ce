# SPDX-License-Identifier: GPL-3.0-or-later
# cmake -P script: OpenVDB's version.h from its version.h.in, for a headers-only install
# (scripts/release/build_deps.sh), with the settings the release compiles against: ABI and
# version from OpenVDB's own CMakeLists.txt (CMAKE_LISTS), Imath's half, blosc and zlib, and no
# explicit template instantiation (it would declare the templates as the library's, and the
# release has no library: every template is instantiated in hyvox's own code).
# Inputs: IN (version.h.in), OUT, CMAKE_LISTS.
file(STRINGS ${CMAKE_LISTS} version_lines REGEX "^set\\(OpenVDB_(MAJOR|MINOR|PATCH)_VERSION [0-9]+\\)")
foreach(line IN LISTS version_lines)
  string(REGEX REPLACE "^set\\((OpenVDB_[A-Z]+_VERSION) ([0-9]+)\\)$" "\\1;\\2" pair "${line}")
  list(GET pair 0 name)
  list(GET pair 1 value)
  set(${name} ${value})
endforeach()
if(NOT DEFINED OpenVDB_MAJOR_VERSION OR NOT DEFINED OpenVDB_MINOR_VERSION OR NOT DEFINED OpenVDB_PATCH_VERSION)
  message(FATAL_ERROR "no OpenVDB version in ${CMAKE_LISTS}")
endif()
set(OPENVDB_ABI_VERSION_NUMBER ${OpenVDB_MAJOR_VERSION})
math(EXPR OPENVDB_PACKED_VERSION "(${OpenVDB_MAJOR_VERSION} << 24) | ((${OpenVDB_MINOR_VERSION} & 0xFF) << 16) | (${OpenVDB_PATCH_VERSION} & 0xFFFF)")
set(OPENVDB_NAMESPACE_SUFFIX "")
set(OPENVDB_USE_IMATH_HALF 1)
set(OPENVDB_IMATH_VERSION 1)
set(OPENVDB_USE_BLOSC 1)
set(OPENVDB_USE_ZLIB 1)
set(OPENVDB_PACKAGE_URL "")
set(OPENVDB_PACKAGE_REVISION "")
configure_file(${IN} ${OUT})
