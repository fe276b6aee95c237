# Rejects an include that goes up the engine's layers (cmake/layers.cmake): every `#include "DIR/NAME"` in
# ENGINE_DIR must name a header of the includer's own layer or of a layer below it that the includer's layer
# depends on. Prints one line per violation, FILE:LINE first, and fails.
#
#   cmake -DENGINE_DIR=engine [-DSTAMP=file] -P cmake/check_layers.cmake
#
# Run by the build (target vct_layer_check, before the engine's libraries compile) and by ctest (layer_check;
# layer_check_rejects_upward_include plants a violation in a copy of engine/ and expects a failure).
cmake_minimum_required(VERSION 3.20)
if(NOT ENGINE_DIR)
  message(FATAL_ERROR "usage: cmake -DENGINE_DIR=DIR [-DSTAMP=FILE] -P check_layers.cmake")
endif()
get_filename_component(ENGINE_DIR "${ENGINE_DIR}" ABSOLUTE)
include(${CMAKE_CURRENT_LIST_DIR}/layers.cmake)

# The table itself: dependencies name layers declared before (so there is no cycle); each folder in one layer.
set(declared "")
foreach(layer ${VCT_LAYERS})
  set(allowed_${layer} ${layer})
  foreach(dep ${VCT_LAYER_${layer}_DEPENDS})
    if(NOT dep IN_LIST declared)
      message(FATAL_ERROR "cmake/layers.cmake: layer '${layer}' depends on '${dep}', which is not declared "
                          "below it (a layer may depend only on layers listed before it in VCT_LAYERS)")
    endif()
    list(APPEND allowed_${layer} ${allowed_${dep}})
  endforeach()
  list(REMOVE_DUPLICATES allowed_${layer})
  foreach(dir ${VCT_LAYER_${layer}_DIRS})
    if(DEFINED layer_of_${dir})
      message(FATAL_ERROR "cmake/layers.cmake: folder '${dir}' is in layers '${layer_of_${dir}}' and '${layer}'")
    endif()
    set(layer_of_${dir} ${layer})
  endforeach()
  list(APPEND declared ${layer})
endforeach()

file(GLOB_RECURSE sources RELATIVE ${ENGINE_DIR} ${ENGINE_DIR}/*.h ${ENGINE_DIR}/*.hpp ${ENGINE_DIR}/*.cpp)
list(SORT sources)
set(violations 0)
foreach(source ${sources})
  get_filename_component(dir "${source}" DIRECTORY)
  if(NOT DEFINED layer_of_${dir})
    message("${ENGINE_DIR}/${source}:1: error: folder engine/${dir}/ is in no layer (add it to cmake/layers.cmake)")
    math(EXPR violations "${violations} + 1")
    continue()
  endif()
  set(layer ${layer_of_${dir}})
  file(STRINGS ${ENGINE_DIR}/${source} includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"[^\"]*\"")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]*)\".*$" "\\1" header "${line}")
    get_filename_component(header_dir "${header}" DIRECTORY)
    if(header_dir STREQUAL "")
      set(header_dir ${dir})  # "name.h": a header next to the includer
    endif()
    if(NOT DEFINED layer_of_${header_dir})
      set(problem "includes \"${header}\", which is in no layer (cmake/layers.cmake)")
    elseif(NOT layer_of_${header_dir} IN_LIST allowed_${layer})
      string(REPLACE ";" ", " may "${allowed_${layer}}")
      string(CONCAT problem "upward include: layer '${layer}' includes \"${header}\" of layer "
                    "'${layer_of_${header_dir}}' (${layer} may include: ${may})")
    else()
      continue()
    endif()
    # Line number of the first such line: count the newlines before it.
    file(READ ${ENGINE_DIR}/${source} text)
    string(FIND "${text}" "${line}" at)
    string(SUBSTRING "${text}" 0 ${at} before)
    string(REGEX MATCHALL "\n" newlines "${before}")
    list(LENGTH newlines number)
    math(EXPR number "${number} + 1")
    message("${ENGINE_DIR}/${source}:${number}: error: ${problem}")
    math(EXPR violations "${violations} + 1")
  endforeach()
endforeach()

if(violations GREATER 0)
  message(FATAL_ERROR "${violations} include(s) against the layers of cmake/layers.cmake")
endif()
list(LENGTH sources count)
message(STATUS "layers: ${count} files in ${ENGINE_DIR}, no upward include")
if(STAMP)
  file(TOUCH ${STAMP})
endif()
