# Warnings and sanitizers per target, never global flags.
function(eco_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wshadow -Wconversion -Wno-sign-conversion)
  if(ECO_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=all -O1)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
  if(ECO_THREAD_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=thread -fno-omit-frame-pointer -O1)
    target_link_options(${target} PRIVATE -fsanitize=thread)
  endif()
endfunction()

# eco_fuzz_coverage(<target> [SOURCES files...]): libFuzzer's coverage counters (ECO_FUZZ) in what
# the fuzzers parse: a whole target, or some of its sources (then compiled without the target's
# precompiled headers, whose flags differ). Only there: the fuzzers are built beside the unit tests,
# whose running time counters everywhere would add to.
function(eco_fuzz_coverage target)
  if(NOT ECO_FUZZ)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES" ${ARGN})
  if(ARG_SOURCES)
    set_source_files_properties(${ARG_SOURCES} TARGET_DIRECTORY ${target} PROPERTIES
                                COMPILE_OPTIONS -fsanitize=fuzzer-no-link SKIP_PRECOMPILE_HEADERS ON)
  else()
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link)
  endif()
endfunction()

# eco_precompiled_headers(<target>): the headers nearly every source of ours parses (Eigen, the
# standard containers), compiled once a target: parsing them was about half of each source's
# compile time, and builds were most of `make test`'s.
set(ECO_PRECOMPILED_HEADERS <Eigen/Core> <Eigen/Geometry> <algorithm> <cstdint> <memory> <optional> <span> <string>
    <vector>)
function(eco_precompiled_headers target)
  target_precompile_headers(${target} PRIVATE ${ECO_PRECOMPILED_HEADERS})
endfunction()

# eco_library(<target> <export-name> SOURCES ... LINK ...): one of the libraries beside the core,
# reachable as eco::<export-name> in this build and after install; LINK takes
# target_link_libraries' arguments (PUBLIC ... PRIVATE ...).
function(eco_library target export_name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LINK" ${ARGN})
  add_library(${target} ${ARG_SOURCES})
  add_library(eco::${export_name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${export_name} POSITION_INDEPENDENT_CODE ON)
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(${target} ${ARG_LINK})
  eco_target_defaults(${target})
  eco_precompiled_headers(${target})
endfunction()
