# Finds every third-party package Patina uses (all Debian 12 packages installed by
# scripts/bootstrap.sh) and mends the two broken config files Debian ships.
include_guard(GLOBAL)
include(CMakeFindDependencyMacro)

# Used both in the build and from an installed PatinaConfig.cmake (find_dependency).
macro(_patina_find name)
  if(CMAKE_FIND_PACKAGE_NAME)
    find_dependency(${name} ${ARGN})
  else()
    find_package(${name} ${ARGN} REQUIRED)
  endif()
endmacro()

find_package(Threads REQUIRED)
_patina_find(Imath 3.1 CONFIG)
_patina_find(OpenEXR 3.1 CONFIG)
_patina_find(TBB CONFIG)
_patina_find(embree 3 CONFIG)
_patina_find(assimp CONFIG)
_patina_find(fmt CONFIG)
_patina_find(tomlplusplus 3 CONFIG)
_patina_find(CLI11 CONFIG)

# OpenImageIO's target lists /usr/include/opencv4; drop include dirs that do not exist so a
# machine without OpenCV headers still configures.
_patina_find(OpenImageIO 2.4 CONFIG)
foreach(_tgt OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util)
  foreach(_prop INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
    get_target_property(_dirs ${_tgt} ${_prop})
    if(_dirs)
      set(_kept)
      foreach(_d IN LISTS _dirs)
        if(_d MATCHES "^\\$<" OR EXISTS "${_d}")
          list(APPEND _kept "${_d}")
        endif()
      endforeach()
      set_target_properties(${_tgt} PROPERTIES ${_prop} "${_kept}")
    endif()
  endforeach()
endforeach()

# OpenColorIO 2.1's config sits in /usr/share/cmake and computes an empty prefix; build our
# own imported target from the library and header instead.
if(NOT TARGET Patina_OpenColorIO)
  find_library(PATINA_OCIO_LIBRARY NAMES OpenColorIO REQUIRED)
  find_path(PATINA_OCIO_INCLUDE_DIR OpenColorIO/OpenColorIO.h REQUIRED)
  add_library(Patina_OpenColorIO UNKNOWN IMPORTED GLOBAL)
  set_target_properties(Patina_OpenColorIO PROPERTIES
    IMPORTED_LOCATION "${PATINA_OCIO_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${PATINA_OCIO_INCLUDE_DIR}")
endif()
