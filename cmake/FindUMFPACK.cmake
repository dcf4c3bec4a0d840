# FindUMFPACK: SuiteSparse's UMFPACK (Debian's libsuitesparse-dev 5.x ships no CMake package).
# Defines UMFPACK_FOUND and the imported target SuiteSparse::UMFPACK (header umfpack.h in
# /usr/include/suitesparse, library libumfpack). Its dense kernels call BLAS: with Debian's
# reference BLAS they are slower than Eigen's SparseLU, with OpenBLAS (libopenblas0-serial,
# which install_dependencies.sh installs) faster (docs/performance/sdirk-step.md).
find_path(UMFPACK_INCLUDE_DIR umfpack.h PATH_SUFFIXES suitesparse)
find_library(UMFPACK_LIBRARY umfpack)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(UMFPACK REQUIRED_VARS UMFPACK_LIBRARY UMFPACK_INCLUDE_DIR)
if(UMFPACK_FOUND AND NOT TARGET SuiteSparse::UMFPACK)
  add_library(SuiteSparse::UMFPACK UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::UMFPACK PROPERTIES
    IMPORTED_LOCATION "${UMFPACK_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${UMFPACK_INCLUDE_DIR}")
endif()
mark_as_advanced(UMFPACK_INCLUDE_DIR UMFPACK_LIBRARY)
