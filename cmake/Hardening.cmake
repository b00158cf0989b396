# SPDX-License-Identifier: Apache-2.0
# Hardening for the project's own targets, the set Debian's dpkg-buildflags gives packages
# with "hardening=+all": stack protector, fortified libc calls, full RELRO with immediate
# binding, position-independent executables (ASLR), stack-clash probes and CET branch markers.
#
# artcam_hardening is an INTERFACE library carried by artcam_warnings, which every target of
# the project links (core, ui, app, tests, fuzz), so a new target is hardened without a CMake
# change. Included before any target is created: CMAKE_POSITION_INDEPENDENT_CODE only sets the
# property of targets made after it.

# PIE: -fPIE/-fPIC on every object and -pie on every executable's link (policy CMP0083 is NEW
# with cmake_minimum_required 3.25); check_pie_supported fails the configure early on a
# toolchain that cannot link one, instead of building a non-PIE binary unnoticed.
include(CheckPIESupported)
check_pie_supported(OUTPUT_VARIABLE _artcam_pie_output LANGUAGES CXX)
if(NOT CMAKE_CXX_LINK_PIE_SUPPORTED)
  message(FATAL_ERROR "ARTcam: the C++ toolchain cannot link position-independent executables:\n"
                      "${_artcam_pie_output}")
endif()
set(CMAKE_POSITION_INDEPENDENT_CODE ON)

add_library(artcam_hardening INTERFACE)
target_compile_options(artcam_hardening INTERFACE -fstack-protector-strong)
target_link_options(artcam_hardening INTERFACE LINKER:-z,relro,-z,now)

# The two further flags of dpkg-buildflags' hardening on amd64, where the compiler has them:
# stack-clash probes (a large alloca or frame cannot jump over the guard page) and CET's
# indirect-branch and return markers (-fcf-protection is x86 only, hence the check).
include(CheckCXXCompilerFlag)
foreach(_flag -fstack-clash-protection -fcf-protection)
  string(MAKE_C_IDENTIFIER "ARTCAM_HAS${_flag}" _var)
  check_cxx_compiler_flag(${_flag} ${_var})
  if(${_var})
    target_compile_options(artcam_hardening INTERFACE ${_flag})
  endif()
endforeach()

# _FORTIFY_SOURCE needs optimisation (glibc warns at -O0, and -Werror turns that into a
# failure), so it is on only in the optimised configurations. Not in the fuzzing build, and not
# on the sources a sanitizer build instruments (cmake/Sanitizers.cmake undoes it per source):
# the fortified __*_chk variants of memcpy, strcpy ... are not all intercepted by ASan, so
# fortification would hide the very overflows those builds look for. -U first: some compilers
# predefine it, and a redefinition warns.
if(NOT ARTCAM_FUZZ)
  target_compile_options(artcam_hardening INTERFACE
    "$<$<CONFIG:Release,RelWithDebInfo,MinSizeRel>:-U_FORTIFY_SOURCE;-D_FORTIFY_SOURCE=2>")
endif()

target_link_libraries(artcam_warnings INTERFACE artcam_hardening)
