# Thin find module for TetGen 1.5 (Debian libtet1.5-dev ships tetgen.h + libtet, no CMake config).
# Defines TetGen::tetgen. TETLIBRARY must be defined by users of tetgen.h.
find_path(TetGen_INCLUDE_DIR tetgen.h)
find_library(TetGen_LIBRARY tet)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(TetGen REQUIRED_VARS TetGen_LIBRARY TetGen_INCLUDE_DIR)
if(TetGen_FOUND AND NOT TARGET TetGen::tetgen)
  add_library(TetGen::tetgen UNKNOWN IMPORTED)
  set_target_properties(TetGen::tetgen PROPERTIES IMPORTED_LOCATION "${TetGen_LIBRARY}"
                        INTERFACE_INCLUDE_DIRECTORIES "${TetGen_INCLUDE_DIR}"
                        INTERFACE_COMPILE_DEFINITIONS TETLIBRARY)
endif()
mark_as_advanced(TetGen_INCLUDE_DIR TetGen_LIBRARY)
