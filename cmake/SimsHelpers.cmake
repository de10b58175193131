# Helper functions shared by src/, apps/ and tests/.

# Routes compilations through ccache when it is installed; PCH needs relaxed ccache checks.
function(sims_enable_ccache)
  find_program(SIMS_CCACHE ccache)
  if(SIMS_CCACHE)
    set(CMAKE_CXX_COMPILER_LAUNCHER
        ${CMAKE_COMMAND} -E env
        "CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime"
        ${SIMS_CCACHE} PARENT_SCOPE)
    set(CMAKE_C_COMPILER_LAUNCHER ${SIMS_CCACHE} PARENT_SCOPE)
  endif()
endfunction()

# sims_module(<name> SOURCES ... [DEPS ...] [PRIVATE_DEPS ...] [TORCH])
# Declares the static library sims_<name>; TORCH precompiles <torch/torch.h> for it.
# A listed source that does not exist is a configure error naming the file: skipping it would
# only move the failure to link time (or silently drop tests).
function(sims_require_sources)
  foreach(src ${ARGN})
    if(IS_ABSOLUTE ${src})
      set(path ${src})
    else()
      set(path ${CMAKE_CURRENT_SOURCE_DIR}/${src})
    endif()
    if(NOT EXISTS ${path})
      message(FATAL_ERROR "${CMAKE_CURRENT_LIST_FILE}: listed source ${path} does not exist")
    endif()
  endforeach()
endfunction()

function(sims_module name)
  cmake_parse_arguments(M "TORCH" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  sims_require_sources(${M_SOURCES})
  add_library(sims_${name} STATIC ${M_SOURCES})
  target_include_directories(sims_${name} PUBLIC ${PROJECT_SOURCE_DIR}/include
                                          PRIVATE ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(sims_${name} PUBLIC ${M_DEPS} PRIVATE ${M_PRIVATE_DEPS})
  if(M_TORCH)
    target_precompile_headers(sims_${name} PRIVATE <torch/torch.h>)
  endif()
  set_property(GLOBAL APPEND PROPERTY SIMS_MODULES sims_${name})
endfunction()

# sims_app(<name>): apps/<name>.cpp linked against the whole library (apps never include torch).
function(sims_app name)
  add_executable(${name} ${name}.cpp)
  target_link_libraries(${name} PRIVATE sims CLI11::CLI11)
endfunction()

# sims_test(<module> SOURCES ... [TORCH] [FAST]): one GoogleTest binary per module. FAST adds
# the ctest label `fast` and puts the binary under the `fast_tests` target: the torch-free
# modules whose whole suite runs in seconds, which the sanitizer job (preset `asan`) builds
# and runs without the slow torch and training tests.
function(sims_test module)
  cmake_parse_arguments(T "TORCH;FAST" "" "SOURCES" ${ARGN})
  set(target ${module}_tests)
  sims_require_sources(${T_SOURCES})
  add_executable(${target} ${T_SOURCES})
  set_target_properties(${target} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests)
  target_link_libraries(${target} PRIVATE sims_${module} sims_test_main GTest::gtest GTest::gmock)
  if(T_TORCH)
    target_precompile_headers(${target} PRIVATE <torch/torch.h>)
  endif()
  gtest_discover_tests(${target} DISCOVERY_MODE PRE_TEST DISCOVERY_TIMEOUT 60
                       WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                       PROPERTIES LABELS ${module})
  if(T_FAST)
    # gtest_discover_tests passes one label value through, not a list: a second include file,
    # read by ctest after the discovered tests exist, relabels them.
    set(relabel ${CMAKE_CURRENT_BINARY_DIR}/${target}_fast_label.cmake)
    file(WRITE ${relabel}
         "foreach(t IN LISTS ${target}_TESTS)\n"
         "  set_tests_properties(\"\${t}\" PROPERTIES LABELS \"${module};fast\")\n"
         "endforeach()\n")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${relabel})
    set_property(GLOBAL APPEND PROPERTY SIMS_FAST_TESTS ${target})
  endif()
endfunction()
