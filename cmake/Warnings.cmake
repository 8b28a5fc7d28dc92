# Warnings for project targets only (third-party headers are included as SYSTEM).
set(GRIDSLAM_WARNINGS -Wall -Wextra -Wpedantic -Wconversion -Wshadow -Wcast-align
    -Woverloaded-virtual -Wnon-virtual-dtor)
if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  # Clang's -Wconversion also turns on -Wsign-conversion, which gcc's does not for C++: keep the
  # same set of warnings with both compilers.
  list(APPEND GRIDSLAM_WARNINGS -Wno-sign-conversion)
endif()
if(GRIDSLAM_WERROR)
  list(APPEND GRIDSLAM_WARNINGS -Werror)
endif()
function(gridslam_set_warnings target)
  target_compile_options(${target} PRIVATE ${GRIDSLAM_WARNINGS})
endfunction()
