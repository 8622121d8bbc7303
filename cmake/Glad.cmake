# The OpenGL loader is generated at configure time into the build tree by the glad2 generator from PyPI
# (pinned in scripts/setup).  --reproducible makes glad use the specifications bundled with that version
# instead of downloading them, so the loader never changes under us and is never committed.
find_package(Python3 REQUIRED COMPONENTS Interpreter)

set(CUDAHULL_GLAD_DIR "${CMAKE_BINARY_DIR}/glad")
set(CUDAHULL_GLAD_API "gl:core=4.5")
set(_glad_stamp "${CUDAHULL_GLAD_DIR}/stamp-${CUDAHULL_GLAD_API}")
string(REPLACE ":" "_" _glad_stamp "${_glad_stamp}")

if(NOT EXISTS "${_glad_stamp}")
  execute_process(
    COMMAND "${Python3_EXECUTABLE}" -m glad --api "${CUDAHULL_GLAD_API}" --out-path "${CUDAHULL_GLAD_DIR}"
            --reproducible --quiet c
    RESULT_VARIABLE _glad_result
    OUTPUT_VARIABLE _glad_output
    ERROR_VARIABLE _glad_output)
  if(NOT _glad_result EQUAL 0)
    message(FATAL_ERROR "glad2 could not generate the OpenGL loader (run scripts/setup, which installs "
                        "glad2 from PyPI):\n${_glad_output}")
  endif()
  file(WRITE "${_glad_stamp}" "")
endif()

add_library(glad STATIC "${CUDAHULL_GLAD_DIR}/src/gl.c")
target_include_directories(glad PUBLIC "${CUDAHULL_GLAD_DIR}/include")
set_target_properties(glad PROPERTIES POSITION_INDEPENDENT_CODE ON)
