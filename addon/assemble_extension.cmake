# SPDX-License-Identifier: GPL-3.0-or-later
# cmake -P script: the Blender 4.2+ extension ZIP: the add-on sources (no loose compiled
# module: the add-on imports hyvox from the bundled wheel), blender_manifest.toml and
# wheels/<the self-contained wheel>, all at the top of the zip as Blender's
# `extension build` lays them out. Inputs: SOURCE_DIR (addon/hyvox_blender), MANIFEST_IN,
# WHEEL_DIR (holds exactly one hyvox-*.whl), VERSION, STAGE_DIR, ZIP.
file(GLOB wheels ${WHEEL_DIR}/hyvox-*.whl)
list(LENGTH wheels count)
if(NOT count EQUAL 1)
  message(FATAL_ERROR "expected one hyvox wheel in ${WHEEL_DIR}, found ${count}")
endif()
get_filename_component(HYVOX_WHEEL_NAME ${wheels} NAME)
set(HYVOX_VERSION ${VERSION})

file(REMOVE_RECURSE ${STAGE_DIR})
file(MAKE_DIRECTORY ${STAGE_DIR}/wheels)
file(COPY ${SOURCE_DIR}/ DESTINATION ${STAGE_DIR}
     FILES_MATCHING PATTERN "*.py" PATTERN "*.md"
     PATTERN "__pycache__" EXCLUDE PATTERN "hyvox" EXCLUDE)
file(COPY ${wheels} DESTINATION ${STAGE_DIR}/wheels)
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
