# SPDX-License-Identifier: Apache-2.0
# The engine's layers, lowest first. A file in core/<layer>/ may include its own layer and the
# layers before it, never one after it: the order is what keeps core free of include cycles
# (docs/architecture.md explains what lives where). Configuring fails on a violation.
set(ARTCAM_CORE_LAYERS util model colour depth fit mapping sampling render cameras cloud effects piecewise io lens pipeline project)

function(artcam_check_core_layers sources)
  set(_violations "")
  foreach(_src IN LISTS sources)
    string(REGEX MATCH "core/([a-z_]+)/[^/]+$" _m "${_src}")
    set(_own "${CMAKE_MATCH_1}")
    list(FIND ARTCAM_CORE_LAYERS "${_own}" _own_rank)
    if(_own_rank LESS 0)
      list(APPEND _violations "${_src}: core/${_own}/ is not a layer of cmake/CoreLayers.cmake")
      continue()
    endif()
    file(STRINGS "${_src}" _includes REGEX "#[ \t]*include[ \t]*\"core/[a-z_]+/")
    foreach(_line IN LISTS _includes)
      string(REGEX MATCH "\"core/([a-z_]+)/" _m2 "${_line}")
      set(_used "${CMAKE_MATCH_1}")
      list(FIND ARTCAM_CORE_LAYERS "${_used}" _used_rank)
      if(_used_rank GREATER _own_rank)
        list(APPEND _violations "${_src}: core/${_own}/ includes core/${_used}/ (a higher layer)")
      endif()
    endforeach()
  endforeach()
  if(_violations)
    list(JOIN _violations "\n  " _text)
    message(FATAL_ERROR "core/ layer order (${ARTCAM_CORE_LAYERS}) broken:\n  ${_text}")
  endif()
endfunction()

# Script mode, for the tests: cmake -DARTCAM_LAYER_ROOT=DIR -P CoreLayers.cmake checks DIR/core.
if(CMAKE_SCRIPT_MODE_FILE AND DEFINED ARTCAM_LAYER_ROOT)
  file(GLOB_RECURSE _layer_sources "${ARTCAM_LAYER_ROOT}/core/*.h" "${ARTCAM_LAYER_ROOT}/core/*.cpp")
  artcam_check_core_layers("${_layer_sources}")
  message(STATUS "core/ layers hold (${ARTCAM_LAYER_ROOT})")
endif()
