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
    # With precompiled headers ccache caches only when told the header's macros and time stamps may be trusted
    # (ccache's manual, "Precompiled headers").
    set(CMAKE_CXX_COMPILER_LAUNCHER ${CMAKE_COMMAND} -E env
                                    CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime
                                    ${LDV_CCACHE_PROGRAM})
  endif()
endif()

# Precompiled headers (GCC): the standard and third-party headers nearly every file includes, parsed once per
# family of targets instead of once per batch. GCC takes a precompiled header only where the macros it was built
# with are the same (e.g. -pthread defines _REENTRANT, GoogleTest defines GTEST_HAS_PTHREAD) and otherwise
# silently parses the headers itself, so each family gets its own: a target's family is whether it links
# GoogleTest and whether it links LCM (whose glib flags carry -pthread). Call ldv_precompile_headers() once,
# after every target is defined. Clang (the libFuzzer build) refuses a precompiled header built with other
# macros instead of ignoring it, so it builds without.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  set(_ldv_pch_default ON)
else()
  set(_ldv_pch_default OFF)
endif()
option(LDV_PRECOMPILE_HEADERS "precompile the heavy third-party headers (GCC)" ${_ldv_pch_default})
if(LDV_PRECOMPILE_HEADERS)
  add_compile_options(-Winvalid-pch)  # a target whose family was guessed wrong says so in the build
endif()
set(LDV_PCH_HEADERS
    <algorithm> <array> <chrono> <cmath> <cstdint> <cstdio> <filesystem> <fstream> <functional> <map> <memory>
    <optional> <sstream> <string> <string_view> <vector> <Eigen/Dense> <spdlog/spdlog.h> <yaml-cpp/yaml.h>)

# Every target a target links, directly or through the libraries it links (names as written, aliases kept).
function(_ldv_link_closure target out_var)
  set(seen "")
  set(todo ${target})
  while(todo)
    list(POP_FRONT todo t)
    if(t IN_LIST seen OR NOT TARGET ${t})
      continue()
    endif()
    list(APPEND seen ${t})
    get_target_property(type ${t} TYPE)
    set(libs "")
    if(NOT type STREQUAL "INTERFACE_LIBRARY")
      get_target_property(direct ${t} LINK_LIBRARIES)
      if(direct)
        list(APPEND libs ${direct})
      endif()
    endif()
    get_target_property(iface ${t} INTERFACE_LINK_LIBRARIES)
    if(iface)
      list(APPEND libs ${iface})
    endif()
    foreach(lib ${libs})
      string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" lib "${lib}")
      if(TARGET ${lib})
        list(APPEND todo ${lib})
      endif()
    endforeach()
  endwhile()
  set(${out_var} ${seen} PARENT_SCOPE)
endfunction()

function(_ldv_targets_under dir out_var)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(sub ${subdirs})
    _ldv_targets_under(${sub} more)
    list(APPEND targets ${more})
  endforeach()
  set(${out_var} ${targets} PARENT_SCOPE)
endfunction()

# The targets of this tree that compile sources (executables and libraries, not interface or custom targets).
function(_ldv_compiled_targets out_var)
  _ldv_targets_under(${CMAKE_SOURCE_DIR} targets)
  set(compiled "")
  foreach(t ${targets})
    get_target_property(type ${t} TYPE)
    if(type MATCHES "^(EXECUTABLE|STATIC_LIBRARY|SHARED_LIBRARY|OBJECT_LIBRARY)$")
      list(APPEND compiled ${t})
    endif()
  endforeach()
  set(${out_var} ${compiled} PARENT_SCOPE)
endfunction()

function(ldv_precompile_headers)
  if(NOT LDV_PRECOMPILE_HEADERS)
    return()
  endif()
  _ldv_compiled_targets(targets)  # before the family targets below exist
  set(pch_source ${CMAKE_BINARY_DIR}/ldv_pch_origin.cpp)
  file(WRITE ${pch_source} "// The target that builds a family's precompiled header (cmake/fast_build.cmake).\n")
  foreach(t ${targets})
    _ldv_link_closure(${t} closure)
    if(NOT ldv_common IN_LIST closure)
      continue()  # not ours (e.g. a pure LCM type test): its flags are none of the families'
    endif()
    set(family_libs Eigen3::Eigen spdlog::spdlog yaml-cpp)  # what ldv_common brings (it reuses the header too)
    set(family lib)
    if(GTest::gtest IN_LIST closure OR GTest::gtest_main IN_LIST closure)
      list(APPEND family_libs GTest::gtest)
      set(family tests)
    endif()
    if(PkgConfig::LCM IN_LIST closure)
      list(APPEND family_libs PkgConfig::LCM)
      string(APPEND family _pthread)
    endif()
    if(NOT TARGET ldv_pch_${family})
      add_library(ldv_pch_${family} OBJECT ${pch_source})
      target_link_libraries(ldv_pch_${family} PRIVATE ${family_libs})
      set(headers ${LDV_PCH_HEADERS})
      if(family MATCHES "^tests")
        list(APPEND headers <gtest/gtest.h>)
      endif()
      target_precompile_headers(ldv_pch_${family} PRIVATE ${headers})
      set_target_properties(ldv_pch_${family} PROPERTIES UNITY_BUILD OFF)
    endif()
    target_precompile_headers(${t} REUSE_FROM ldv_pch_${family})
  endforeach()
endfunction()

# A unity batch recompiles whole when any of its files' headers changes. The files that include the filter's
# class (estimator/filter/nav_filter.hpp, directly or through another header of ours) are listed first in
# their target, so they fill batches of their own: a change of the filter's header recompiles those batches,
# not every batch a single user of the filter happened to fall into. Call after every target is defined.
set(LDV_UNITY_VOLATILE_HEADERS estimator/filter/nav_filter.hpp)

# Whether `file` includes one of LDV_UNITY_VOLATILE_HEADERS through `#include "..."` lines of this tree
# (memoised in the global property _ldv_reaches_<path>).
function(_ldv_reaches_volatile file out_var)
  string(MAKE_C_IDENTIFIER "_ldv_reaches_${file}" key)
  get_property(known GLOBAL PROPERTY ${key} SET)
  if(known)
    get_property(answer GLOBAL PROPERTY ${key})
    set(${out_var} ${answer} PARENT_SCOPE)
    return()
  endif()
  set_property(GLOBAL PROPERTY ${key} FALSE)  # a cycle of includes ends here
  set(answer FALSE)
  if(EXISTS ${file})
    file(STRINGS ${file} lines REGEX "^#include \"")
    foreach(line ${lines})
      string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" inc "${line}")
      if(inc IN_LIST LDV_UNITY_VOLATILE_HEADERS)
        set(answer TRUE)
        break()
      endif()
      if(EXISTS ${CMAKE_SOURCE_DIR}/${inc})
        _ldv_reaches_volatile(${CMAKE_SOURCE_DIR}/${inc} deeper)
        if(deeper)
          set(answer TRUE)
          break()
        endif()
      endif()
    endforeach()
  endif()
  set_property(GLOBAL PROPERTY ${key} ${answer})
  set(${out_var} ${answer} PARENT_SCOPE)
endfunction()

function(ldv_unity_group_volatile_sources)
  if(NOT LDV_UNITY_BUILD)
    return()
  endif()
  _ldv_compiled_targets(targets)
  foreach(t ${targets})
    get_target_property(sources ${t} SOURCES)
    get_target_property(dir ${t} SOURCE_DIR)
    set(first "")
    set(rest "")
    foreach(s ${sources})
      cmake_path(ABSOLUTE_PATH s BASE_DIRECTORY ${dir} OUTPUT_VARIABLE path)
      _ldv_reaches_volatile(${path} reaches)
      if(reaches)
        list(APPEND first ${s})
      else()
        list(APPEND rest ${s})
      endif()
    endforeach()
    if(first AND rest)
      set_property(TARGET ${t} PROPERTY SOURCES ${first} ${rest})
    endif()
  endforeach()
endfunction()
