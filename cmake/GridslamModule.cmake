# Maps dependency names to targets: a gridslam module name becomes gridslam::<name> (skipped if
# that module has not landed yet); anything else is taken as an imported target.
function(gridslam_resolve_deps out)
  set(result "")
  foreach(dep IN LISTS ARGN)
    if(TARGET gridslam_${dep})
      list(APPEND result gridslam::${dep})
    elseif(dep IN_LIST GRIDSLAM_MODULES)
      # module not present (yet): nothing to link
    else()
      list(APPEND result ${dep})
    endif()
  endforeach()
  set(${out} ${result} PARENT_SCOPE)
endfunction()

# gridslam_add_module(<name> SOURCES ... [DEPS ...] [SYSTEM_DEPS ...])
#   One static library per module, exported as gridslam::<name>. DEPS are other modules
#   (given without the gridslam:: prefix) or imported targets; all are PUBLIC.
function(gridslam_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(gridslam_${name} STATIC ${ARG_SOURCES})
  add_library(gridslam::${name} ALIAS gridslam_${name})
  target_include_directories(gridslam_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
  set(deps "")
  gridslam_resolve_deps(deps ${ARG_DEPS})
  target_link_libraries(gridslam_${name} PUBLIC ${deps})
  gridslam_set_warnings(gridslam_${name})
endfunction()

# gridslam_add_test(<name> SOURCES ... [DEPS ...] [LABELS ...])
#   A GoogleTest executable; its tests are discovered and labelled (default label: unit).
#   Tests run with GRIDSLAM_DATA set (default ../shared/data beside the project root).
function(gridslam_add_test name)
  if(NOT GRIDSLAM_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;LABELS" ${ARGN})
  if(NOT ARG_LABELS)
    set(ARG_LABELS unit)
  endif()
  add_executable(${name} ${ARG_SOURCES})
  set(deps "")
  gridslam_resolve_deps(deps ${ARG_DEPS})
  target_link_libraries(${name} PRIVATE ${deps} gridslam::testing GTest::gtest GTest::gmock GTest::gtest_main)
  gridslam_set_warnings(${name})
  gtest_discover_tests(${name} PROPERTIES LABELS "${ARG_LABELS}" DISCOVERY_TIMEOUT 60
                       WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
endfunction()

# gridslam_add_bench(<name> SOURCES ... [DEPS ...])
function(gridslam_add_bench name)
  if(NOT GRIDSLAM_BUILD_BENCH)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  set(deps "")
  gridslam_resolve_deps(deps ${ARG_DEPS})
  target_link_libraries(${name} PRIVATE ${deps} benchmark::benchmark_main)
  gridslam_set_warnings(${name})
endfunction()

# gridslam_glob_module(<name> [DEPS ...] [TEST_DEPS ...] [TEST_LABELS ...])
#   The module's library from every *.cpp in the current folder that is not a *_test.cpp, and
#   one test executable per *_test.cpp (named after the file), so files can be added without
#   touching CMake.
function(gridslam_glob_module name)
  cmake_parse_arguments(ARG "" "" "DEPS;TEST_DEPS;TEST_LABELS" ${ARGN})
  file(GLOB all_sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp
       ${CMAKE_CURRENT_SOURCE_DIR}/internal/*.cpp)
  file(GLOB test_sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*_test.cpp)
  set(sources ${all_sources})
  if(test_sources)
    list(REMOVE_ITEM sources ${test_sources})
  endif()
  gridslam_add_module(${name} SOURCES ${sources} DEPS ${ARG_DEPS})
  # One executable per test file, so a test being edited never blocks the module's others.
  foreach(test_source IN LISTS test_sources)
    get_filename_component(test_name ${test_source} NAME_WE)
    set(labels ${ARG_TEST_LABELS})
    if(test_name MATCHES "_integration_test$")
      set(labels integration)  # real data or long runs: not rerun under the sanitizers
    endif()
    gridslam_add_test(${test_name} SOURCES ${test_source} DEPS ${name} ${ARG_TEST_DEPS}
                      LABELS ${labels})
  endforeach()
endfunction()
