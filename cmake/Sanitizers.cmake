# SPDX-License-Identifier: Apache-2.0
# Sanitizer and fuzzing builds, each in its own build directory:
#
#   cmake -S . -B build-asan -G Ninja -DARTCAM_SANITIZE=address,undefined
#   cmake -S . -B build-tsan -G Ninja -DARTCAM_SANITIZE=thread -DARTCAM_SANITIZE_ONLY="ui;tests/ui"
#   CXX=clang++-14 cmake -S . -B build-fuzz -G Ninja -DARTCAM_FUZZ=ON -DARTCAM_BUILD_GUI=OFF
#
# ARTCAM_FUZZ builds fuzz/ (libFuzzer targets, one per reader of untrusted files) with clang,
# everything instrumented with -fsanitize=fuzzer-no-link,address,undefined. docs/robustness.md
# ("Fuzzing", "Sanitizers") has the commands to run them.
#
# Decision: in these builds warnings no longer stop the build (-Wno-error). The GCC release
# build is the warning gate; instrumented code at other optimisation levels, or clang's own
# warning set, must not block a sanitizer run on a warning the gate does not see.

set(ARTCAM_SANITIZE "" CACHE STRING
    "Sanitizers: address,undefined | thread | empty (none)")
set(ARTCAM_SANITIZE_ONLY "" CACHE STRING
    "Source folders (from the repository root, ;-separated) to instrument; empty: all of them")
set(ARTCAM_SANITIZE_FLAGS "" CACHE STRING
    "Further compile flags for instrumented sources only (CI: -O1 -g1)")
option(ARTCAM_FUZZ "Build the libFuzzer targets in fuzz/ (clang only; ASan+UBSan)" OFF)

if(ARTCAM_SANITIZE AND ARTCAM_FUZZ)
  message(FATAL_ERROR "ARTCAM_FUZZ already builds with address,undefined; leave ARTCAM_SANITIZE empty")
endif()

# Decision: the flags go on each instrumented SOURCE, never on the tree (no add_compile_options,
# no change to artcam_warnings). A source left out is then compiled with exactly the normal
# build's command line, so ccache hands over the object the normal build just made, and an
# instrumented tree costs only what it instruments. CI instruments what reads and renders
# untrusted input under ASan, and the GUI's threads under TSan (packaging/ci-sanitizers.sh).
# Source-level options also come last on the command line, after the hardening's
# -D_FORTIFY_SOURCE=2, so -U_FORTIFY_SOURCE undoes it where ASan looks (fortified __memcpy_chk
# and friends are not all intercepted, and would hide the overflows ASan is there to see).
# Sources Qt generates at build time (moc) are not instrumented (they are glue, not logic), except
# in a target whose every source is, which carries the flags itself (below).
function(_artcam_instrument_sources)
  separate_arguments(_extra UNIX_COMMAND "${ARTCAM_SANITIZE_FLAGS}")
  set(_flags -fsanitize=${ARTCAM_SANITIZE} -fno-omit-frame-pointer -U_FORTIFY_SOURCE -Wno-error
      ${_extra})
  if(ARTCAM_SANITIZE MATCHES "undefined")
    # Stop at the first undefined behaviour instead of printing and going on, so a test fails.
    list(APPEND _flags -fno-sanitize-recover=undefined)
  endif()
  if(ARTCAM_SANITIZE MATCHES "address")
    # Eigen frees its own aligned blocks and picks how by __SANITIZE_ADDRESS__: plain malloc
    # when glibc's is 16-aligned, else an offset block of its own. With instrumented and plain
    # sources in one program a matrix made on one side and freed on the other is a bad free,
    # so both sides take the plain-malloc choice (ASan's malloc is 16-aligned on x86-64, as
    # glibc's is; a misaligned block would fault in the first vectorised load of a test).
    list(APPEND _flags -DEIGEN_MALLOC_ALREADY_ALIGNED=1)
  endif()
  set(_only ${ARTCAM_SANITIZE_ONLY})
  if(NOT _only)
    set(_only core app ui tests)
  endif()
  set(_dirs ${PROJECT_SOURCE_DIR})
  set(_count 0)
  while(_dirs)
    list(POP_FRONT _dirs _dir)
    get_property(_subdirs DIRECTORY ${_dir} PROPERTY SUBDIRECTORIES)
    list(APPEND _dirs ${_subdirs})
    get_property(_targets DIRECTORY ${_dir} PROPERTY BUILDSYSTEM_TARGETS)
    foreach(_target IN LISTS _targets)
      get_target_property(_type ${_target} TYPE)
      if(_type STREQUAL "INTERFACE_LIBRARY" OR _type STREQUAL "UTILITY")
        continue()
      endif()
      get_target_property(_sources ${_target} SOURCES)
      get_target_property(_target_dir ${_target} SOURCE_DIR)
      set(_hits "")
      set(_all TRUE)
      foreach(_src IN LISTS _sources)
        if(NOT _src MATCHES "\\.cpp$" OR _src MATCHES "^\\$<")
          continue()
        endif()
        cmake_path(ABSOLUTE_PATH _src BASE_DIRECTORY ${_target_dir} NORMALIZE OUTPUT_VARIABLE _abs)
        cmake_path(RELATIVE_PATH _abs BASE_DIRECTORY ${PROJECT_SOURCE_DIR} OUTPUT_VARIABLE _rel)
        set(_hit FALSE)
        foreach(_prefix IN LISTS _only)
          if(_rel MATCHES "^${_prefix}/")
            set(_hit TRUE)
          endif()
        endforeach()
        if(_hit)
          list(APPEND _hits ${_abs})
        else()
          set(_all FALSE)
        endif()
      endforeach()
      if(NOT _hits)
        continue()
      endif()
      list(LENGTH _hits _n)
      math(EXPR _count "${_count} + ${_n}")
      get_target_property(_pch ${_target} PRECOMPILE_HEADERS)
      if(_all AND _pch)
        # Every source of a target with its own precompiled header (the studio's library under
        # TSan): the flags go on the target, so its precompiled header is built with them too
        # and each source keeps it.
        set_property(TARGET ${_target} APPEND PROPERTY COMPILE_OPTIONS ${_flags})
        continue()
      endif()
      foreach(_abs IN LISTS _hits)
        set_property(SOURCE ${_abs} TARGET_DIRECTORY ${_target} APPEND PROPERTY COMPILE_OPTIONS
                     ${_flags})
        # The target's precompiled header (or the one it reuses) is built without the sanitizer:
        # GCC would refuse it here (-Winvalid-pch) and parse the headers anyway.
        set_property(SOURCE ${_abs} TARGET_DIRECTORY ${_target} PROPERTY SKIP_PRECOMPILE_HEADERS ON)
      endforeach()
    endforeach()
  endwhile()
  message(STATUS "ARTcam: ${ARTCAM_SANITIZE} on ${_count} sources under ${_only}")
endfunction()

if(ARTCAM_SANITIZE)
  if(ARTCAM_SANITIZE MATCHES "thread" AND ARTCAM_SANITIZE MATCHES "address")
    message(FATAL_ERROR "ARTCAM_SANITIZE: thread cannot be combined with address")
  endif()
  if(NOT ARTCAM_SANITIZE MATCHES "^(address|undefined|thread|leak)(,(address|undefined|leak))*$")
    message(FATAL_ERROR "ARTCAM_SANITIZE=${ARTCAM_SANITIZE}: expected address,undefined or thread")
  endif()
  # Every executable links the runtime; which sources are instrumented is decided once all
  # targets exist (deferred to the end of the root CMakeLists).
  set(_artcam_san_link -fsanitize=${ARTCAM_SANITIZE})
  if(ARTCAM_SANITIZE MATCHES "undefined")
    list(APPEND _artcam_san_link -fno-sanitize-recover=undefined)
  endif()
  add_link_options(${_artcam_san_link})
  cmake_language(DEFER DIRECTORY ${PROJECT_SOURCE_DIR} CALL _artcam_instrument_sources)
endif()

if(ARTCAM_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "ARTCAM_FUZZ needs clang (libFuzzer): CXX=clang++-14 cmake ... in a new build dir")
  endif()
  set(_artcam_fuzz_flags -fsanitize=fuzzer-no-link,address,undefined
      -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  add_compile_options(${_artcam_fuzz_flags})
  add_link_options(-fsanitize=address,undefined)
  set_property(TARGET artcam_warnings APPEND PROPERTY INTERFACE_COMPILE_OPTIONS
               -Wno-error -Wno-unknown-warning-option)
  add_subdirectory(${PROJECT_SOURCE_DIR}/fuzz ${PROJECT_BINARY_DIR}/fuzz)
endif()
