# SPDX-License-Identifier: Apache-2.0
# Sanitizer and fuzzing builds. Both instrument EVERY target of the build
# (core, ui, app, tests), so each gets its own build directory:
#
#   cmake -S . -B build-asan -G Ninja -DARTCAM_SANITIZE=address,undefined
#   cmake -S . -B build-tsan -G Ninja -DARTCAM_SANITIZE=thread
#   CXX=clang++-14 cmake -S . -B build-fuzz -G Ninja -DARTCAM_FUZZ=ON -DARTCAM_BUILD_GUI=OFF
#
# ARTCAM_FUZZ builds fuzz/ (libFuzzer targets, one per reader of untrusted files) with clang,
# everything instrumented with -fsanitize=fuzzer-no-link,address,undefined. README, "Hostile
# input, fuzzing and sanitizers", has the commands to run them.
#
# Decision: in these builds warnings no longer stop the build (-Wno-error). The GCC release
# build is the warning gate; instrumented code at other optimisation levels, or clang's own
# warning set, must not block a sanitizer run on a warning the gate does not see.

set(ARTCAM_SANITIZE "" CACHE STRING
    "Sanitizers for every target: address,undefined | thread | empty (none)")
option(ARTCAM_FUZZ "Build the libFuzzer targets in fuzz/ (clang only; ASan+UBSan)" OFF)

if(ARTCAM_SANITIZE AND ARTCAM_FUZZ)
  message(FATAL_ERROR "ARTCAM_FUZZ already builds with address,undefined; leave ARTCAM_SANITIZE empty")
endif()

if(ARTCAM_SANITIZE)
  if(ARTCAM_SANITIZE MATCHES "thread" AND ARTCAM_SANITIZE MATCHES "address")
    message(FATAL_ERROR "ARTCAM_SANITIZE: thread cannot be combined with address")
  endif()
  if(NOT ARTCAM_SANITIZE MATCHES "^(address|undefined|thread|leak)(,(address|undefined|leak))*$")
    message(FATAL_ERROR "ARTCAM_SANITIZE=${ARTCAM_SANITIZE}: expected address,undefined or thread")
  endif()
  # Stop at the first undefined behaviour instead of printing and going on, so a test fails.
  set(_artcam_san_flags -fsanitize=${ARTCAM_SANITIZE} -fno-omit-frame-pointer)
  if(ARTCAM_SANITIZE MATCHES "undefined")
    list(APPEND _artcam_san_flags -fno-sanitize-recover=undefined)
  endif()
  add_compile_options(${_artcam_san_flags})
  add_link_options(${_artcam_san_flags})
  set_property(TARGET artcam_warnings APPEND PROPERTY INTERFACE_COMPILE_OPTIONS -Wno-error)
  if(ARTCAM_SANITIZE MATCHES "thread")
    # GCC makes an ifunc resolver for every target_clones function (runtime CPU dispatch); TSan
    # instruments it, and the dynamic loader runs it before the TSan runtime exists: the
    # program dies before main. Those files are built without TSan (their races go unseen).
    file(GLOB_RECURSE _artcam_sources ${PROJECT_SOURCE_DIR}/core/*.cpp)
    set(_artcam_clones "")
    foreach(_src IN LISTS _artcam_sources)
      file(STRINGS ${_src} _hit REGEX "target_clones")
      if(_hit)
        list(APPEND _artcam_clones ${_src})
      endif()
    endforeach()
    if(_artcam_clones)
      # Deferred to the end of the root CMakeLists: core/ is not added yet at this point.
      cmake_language(DEFER CALL set_source_files_properties ${_artcam_clones}
                     DIRECTORY ${PROJECT_SOURCE_DIR}/core
                     PROPERTIES COMPILE_OPTIONS -fno-sanitize=thread)
      message(STATUS "ARTcam: without TSan (target_clones): ${_artcam_clones}")
    endif()
  endif()
  message(STATUS "ARTcam: sanitizers ${ARTCAM_SANITIZE} on every target")
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
