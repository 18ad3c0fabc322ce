# SPDX-License-Identifier: GPL-3.0-or-later
# cmake -P script: the Blender 4.2+ extension ZIP: the add-on sources (no loose compiled
# module: the add-on imports hyvox from a bundled wheel), blender_manifest.toml and
# wheels/<each wheel>, all at the top of the zip as Blender's `extension build` lays them out.
# Blender installs the wheel that fits its Python and platform. Inputs: SOURCE_DIR
# (addon/hyvox_blender), MANIFEST_IN, WHEELS (a ;-list of wheels) or WHEEL_DIR (holding
# exactly one hyvox-*.whl: the build tree's own), PLATFORMS (a ;-list of Blender platform
# names, default linux-x64), VERSION, STAGE_DIR, ZIP.
if(NOT DEFINED WHEELS)
  file(GLOB WHEELS ${WHEEL_DIR}/hyvox-*.whl)
  list(LENGTH WHEELS count)
  if(NOT count EQUAL 1)
    message(FATAL_ERROR "expected one hyvox wheel in ${WHEEL_DIR}, found ${count}")
  endif()
endif()
if(NOT WHEELS)
  message(FATAL_ERROR "no wheels for the extension")
endif()
if(NOT DEFINED PLATFORMS)
  set(PLATFORMS linux-x64)
endif()
set(HYVOX_VERSION ${VERSION})
set(wheel_entries "")
foreach(wheel IN LISTS WHEELS)
  get_filename_component(name ${wheel} NAME)
  list(APPEND wheel_entries "\"./wheels/${name}\"")
endforeach()
list(JOIN wheel_entries ", " HYVOX_WHEEL_ENTRIES)
set(platform_entries "")
foreach(platform IN LISTS PLATFORMS)
  list(APPEND platform_entries "\"${platform}\"")
endforeach()
list(JOIN platform_entries ", " HYVOX_PLATFORM_ENTRIES)

file(REMOVE_RECURSE ${STAGE_DIR})
file(MAKE_DIRECTORY ${STAGE_DIR}/wheels)
file(COPY ${SOURCE_DIR}/ DESTINATION ${STAGE_DIR}
     FILES_MATCHING PATTERN "*.py" PATTERN "*.md"
     PATTERN "__pycache__" EXCLUDE PATTERN "hyvox" EXCLUDE)
file(COPY ${WHEELS} DESTINATION ${STAGE_DIR}/wheels)
configure_file(${MANIFEST_IN} ${STAGE_DIR}/blender_manifest.toml @ONLY)

file(REMOVE ${ZIP})
file(GLOB entries RELATIVE ${STAGE_DIR} ${STAGE_DIR}/*)
execute_process(
  COMMAND ${CMAKE_COMMAND} -E tar cf ${ZIP} --format=zip ${entries}
  WORKING_DIRECTORY ${STAGE_DIR}
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "could not write ${ZIP}")
endif()
