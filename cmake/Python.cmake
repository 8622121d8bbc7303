# The Python module (python/) is built with the Python named by Python_EXECUTABLE, which needs nanobind:
# scripts/build names build-venv's (scripts/setup fills it).  ON (the default) fails at configure time where
# it cannot be built, so that its tests never vanish unseen; OFF leaves it out on purpose, and AUTO builds
# it where nanobind is found.
# A module is a shared object, so every library it links is then compiled as position-independent code.
set(CUDAHULL_PYTHON ON CACHE STRING "Build the Python module: ON (fail without nanobind), OFF, or AUTO (when found)")
set(CUDAHULL_WITH_PYTHON OFF)
if(NOT CUDAHULL_PYTHON STREQUAL "OFF")
  # In a sanitizer build the module is instrumented too: it needs the runtime preloaded into the
  # interpreter, which tests/python_sanitizer.sh does (tests/CMakeLists.txt registers no Python test there).
  # SKBUILD_SABI_COMPONENT: Development.SABIModule where the wheel is abi3 (pyproject's wheel.py-api), so
  # that nanobind's STABLE_ABI builds a module every later Python loads.
  find_package(Python 3.9 COMPONENTS Interpreter Development.Module ${SKBUILD_SABI_COMPONENT})
  if(Python_FOUND)
    execute_process(COMMAND "${Python_EXECUTABLE}" -m nanobind --cmake_dir
                    OUTPUT_VARIABLE _nanobind_dir OUTPUT_STRIP_TRAILING_WHITESPACE
                    RESULT_VARIABLE _nanobind_result ERROR_QUIET)
    if(_nanobind_result EQUAL 0)
      set(nanobind_ROOT "${_nanobind_dir}")
      set(CUDAHULL_WITH_PYTHON ON)
    endif()
  endif()
  if(NOT CUDAHULL_WITH_PYTHON)
    if(CUDAHULL_PYTHON STREQUAL "ON")
      message(FATAL_ERROR "the Python module cannot be built: ${Python_EXECUTABLE} has no nanobind (pip install "
                          "nanobind, or -DPython_EXECUTABLE=build-venv/bin/python after scripts/setup); "
                          "-DCUDAHULL_PYTHON=OFF builds without it")
    endif()
    message(STATUS "Python module: off (no nanobind for ${Python_EXECUTABLE}; scripts/setup prepares build-venv)")
  endif()
endif()
if(CUDAHULL_WITH_PYTHON)
  message(STATUS "Python module: on (${Python_EXECUTABLE})")
  set(CMAKE_POSITION_INDEPENDENT_CODE ON)
endif()
