# SPDX-License-Identifier: GPL-3.0-or-later
# cmake -P script: copy the add-on sources and the compiled module into ADDON_DIR and zip it.
# Starts from an empty folder so files deleted from the sources do not linger.
set(target ${ADDON_DIR}/hyvox_blender)
file(REMOVE_RECURSE ${target})
file(MAKE_DIRECTORY ${target})
file(COPY ${SOURCE_DIR}/ DESTINATION ${target}
     FILES_MATCHING PATTERN "*.py" PATTERN "*.md"
     PATTERN "__pycache__" EXCLUDE)
if(EXISTS ${MODULE_DIR}/__init__.py)
  file(COPY ${MODULE_DIR}/ DESTINATION ${target}/hyvox
       PATTERN "__pycache__" EXCLUDE PATTERN "*.pyc" EXCLUDE)
else()
  message(WARNING "hyvox module not built at ${MODULE_DIR}: the add-on will need an installed hyvox")
endif()
get_filename_component(zip_dir ${ZIP} DIRECTORY)
file(REMOVE ${ZIP})
# Paths inside the zip start with hyvox_blender/, as Blender's installer expects.
execute_process(
  COMMAND ${CMAKE_COMMAND} -E tar cf ${ZIP} --format=zip hyvox_blender
  WORKING_DIRECTORY ${ADDON_DIR}
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "could not write ${ZIP}")
endif()
