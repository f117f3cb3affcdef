# Defines the imported target SuiteSparse::KLU, used by the build and by
# the installed package (slipcontConfig.cmake).  SuiteSparse 7 ships a CMake
# package for KLU; SuiteSparse 5.x (Debian 12) does not, so the headers and
# libraries are then found by hand.
if(NOT TARGET SuiteSparse::KLU)
  find_package(KLU CONFIG QUIET)
endif()
if(NOT TARGET SuiteSparse::KLU)
  find_path(SLIPCONT_KLU_INCLUDE_DIR klu.h PATH_SUFFIXES suitesparse)
  set(_sc_klu_libs)
  set(_sc_klu_ok TRUE)
  if(NOT SLIPCONT_KLU_INCLUDE_DIR)
    set(_sc_klu_ok FALSE)
  endif()
  foreach(_sc_lib klu amd colamd btf suitesparseconfig)
    find_library(SLIPCONT_SS_${_sc_lib} ${_sc_lib})
    if(SLIPCONT_SS_${_sc_lib})
      list(APPEND _sc_klu_libs ${SLIPCONT_SS_${_sc_lib}})
    else()
      set(_sc_klu_ok FALSE)
    endif()
  endforeach()
  if(_sc_klu_ok)
    add_library(SuiteSparse::KLU INTERFACE IMPORTED)
    set_target_properties(SuiteSparse::KLU PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${SLIPCONT_KLU_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${_sc_klu_libs}")
  endif()
  unset(_sc_klu_libs)
  unset(_sc_klu_ok)
endif()
