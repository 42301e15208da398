# Build speed without changing what is built or how it runs (issue 45); the measured times are in the
# README's set-up section.
#
# Unity build: each target's sources compiled in batches, one translation unit a batch, so the heavy headers
# (Eigen, spdlog/fmt, yaml-cpp, CLI11, GoogleTest) are parsed and their templates instantiated and optimised
# once a batch instead of once a file. File-local names must then be unique within a batch:
# tests/layering/check_unity_batches.sh (a default-suite test) lists any two files of a batch that define the
# same one, so no shared helper silently becomes an overload. LDV_UNITY_BUILD=OFF builds file by file.
option(LDV_UNITY_BUILD "compile each target's sources in batches (faster cold build)" ON)
set(LDV_UNITY_BATCH_SIZE 8 CACHE STRING "source files in one unity batch")
if(LDV_UNITY_BUILD)
  set(CMAKE_UNITY_BUILD ON)
  set(CMAKE_UNITY_BUILD_BATCH_SIZE ${LDV_UNITY_BATCH_SIZE})
endif()

# ccache when it is installed (scripts/install_deps.sh installs it): a rebuild of what was built before, on
# this machine, in any build directory (build/, build-sanitize/, build-fuzz/), costs a cache lookup.
option(LDV_CCACHE "compile through ccache when it is installed" ON)
if(LDV_CCACHE AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  find_program(LDV_CCACHE_PROGRAM ccache)
  if(LDV_CCACHE_PROGRAM)
    set(CMAKE_CXX_COMPILER_LAUNCHER ${LDV_CCACHE_PROGRAM})
  endif()
endif()
