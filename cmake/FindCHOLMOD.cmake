# FindCHOLMOD.cmake — locates CHOLMOD and the SuiteSparse libraries it needs.
#
# Debian 12 ships SuiteSparse 5.12 without a CMake config or a .pc file, so we look for the
# headers and libraries by hand. SuiteSparse >= 7 exports SuiteSparse::CHOLMOD itself; we try
# that first and define the same target name otherwise.
#
# Result: CHOLMOD_FOUND and the imported target SuiteSparse::CHOLMOD.
if(TARGET SuiteSparse::CHOLMOD)
  set(CHOLMOD_FOUND TRUE)
  return()
endif()

find_package(CHOLMOD CONFIG QUIET)
if(TARGET SuiteSparse::CHOLMOD)
  set(CHOLMOD_FOUND TRUE)
  return()
endif()

find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
set(_cholmod_components cholmod amd colamd camd ccolamd suitesparseconfig)
set(_cholmod_libraries)
foreach(_component IN LISTS _cholmod_components)
  string(TOUPPER ${_component} _upper)
  find_library(CHOLMOD_${_upper}_LIBRARY ${_component})
  list(APPEND _cholmod_libraries CHOLMOD_${_upper}_LIBRARY)
endforeach()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(CHOLMOD REQUIRED_VARS CHOLMOD_INCLUDE_DIR ${_cholmod_libraries})

if(CHOLMOD_FOUND)
  add_library(SuiteSparse::CHOLMOD INTERFACE IMPORTED)
  set(_cholmod_link)
  foreach(_lib IN LISTS _cholmod_libraries)
    list(APPEND _cholmod_link ${${_lib}})
  endforeach()
  # CHOLMOD's supernodal path calls LAPACK/BLAS; SuiteSparse's shared libraries carry that
  # dependency themselves, so nothing else is linked here.
  set_target_properties(SuiteSparse::CHOLMOD PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${_cholmod_link}")
endif()
mark_as_advanced(CHOLMOD_INCLUDE_DIR ${_cholmod_libraries})
