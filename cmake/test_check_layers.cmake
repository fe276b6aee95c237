# ctest layer_check_rejects_upward_include: the layer check must reject an upward include. Copies engine/ to
# WORK_DIR, plants one include that goes up (vk → app_cli) in a copy of vk/pipeline.cpp, and expects the check
# to fail naming that file and line; a second planted case puts a new folder in no layer. The unmodified copy
# must pass, so a check that fails everything does not pass this test.
#
#   cmake -DENGINE_DIR=engine -DWORK_DIR=dir -P cmake/test_check_layers.cmake
cmake_minimum_required(VERSION 3.20)
set(check ${CMAKE_CURRENT_LIST_DIR}/check_layers.cmake)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
file(COPY ${ENGINE_DIR}/ DESTINATION ${WORK_DIR}/engine)

function(run_check expect_failure expected_text)
  execute_process(COMMAND ${CMAKE_COMMAND} -DENGINE_DIR=${WORK_DIR}/engine -P ${check}
                  RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(expect_failure AND result EQUAL 0)
    message(FATAL_ERROR "the layer check accepted a planted violation:\n${out}")
  elseif(NOT expect_failure AND NOT result EQUAL 0)
    message(FATAL_ERROR "the layer check rejected the unmodified engine:\n${out}")
  endif()
  string(FIND "${out}" "${expected_text}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the layer check's output lacks '${expected_text}':\n${out}")
  endif()
  message(STATUS "as expected:\n${out}")
endfunction()

run_check(FALSE "no upward include")

# An upward include, planted after the file's own lines: its line number is known.
set(planted ${WORK_DIR}/engine/vk/pipeline.cpp)
file(READ ${planted} text)
string(REGEX MATCHALL "\n" newlines "${text}")
list(LENGTH newlines line)
math(EXPR line "${line} + 1")
file(APPEND ${planted} "#include \"app/cli/session.h\"\n")
run_check(TRUE "engine/vk/pipeline.cpp:${line}: error: upward include: layer 'vk' includes \"app/cli/session.h\"")

# A folder the table does not know.
file(WRITE ${planted} "${text}")
file(WRITE ${WORK_DIR}/engine/util/helpers.h "#pragma once\n")
run_check(TRUE "engine/util/helpers.h:1: error: folder engine/util/ is in no layer")
file(REMOVE_RECURSE ${WORK_DIR})
