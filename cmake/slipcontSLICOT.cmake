# Defines the imported target SLICOT::SLICOT (the periodic Schur routines
# of the multipliers, continuation/product_eigs.c), used by the build and by
# the installed package (slipcontConfig.cmake).  Debian ships SLICOT as
# libslicot-dev without a CMake or pkg-config file, so the library is found
# by hand; it is Fortran and links LAPACK, BLAS and libgfortran itself.
if(NOT TARGET SLICOT::SLICOT)
  find_library(SLIPCONT_SLICOT_LIBRARY slicot)
  if(SLIPCONT_SLICOT_LIBRARY)
    add_library(SLICOT::SLICOT INTERFACE IMPORTED)
    set_target_properties(SLICOT::SLICOT PROPERTIES
      INTERFACE_LINK_LIBRARIES "${SLIPCONT_SLICOT_LIBRARY};LAPACK::LAPACK")
  endif()
endif()
