# patina_add_plugin(<name> SOURCES <files...> [OUTPUT_DIRECTORY <dir>] [NO_INSTALL])
# Builds a Patina shading plugin: a MODULE library that sees only Patina::abi, exports only
# the two ABI symbols (hidden visibility for everything else) and has no "lib" prefix.
# Works in Patina's own tree and out of tree after find_package(Patina).
include_guard(GLOBAL)

function(patina_add_plugin name)
  cmake_parse_arguments(ARG "NO_INSTALL" "OUTPUT_DIRECTORY" "SOURCES" ${ARGN})
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "patina_add_plugin(${name}): no SOURCES given")
  endif()
  add_library(${name} MODULE ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE Patina::abi)
  if(TARGET patina_warnings)
    target_link_libraries(${name} PRIVATE patina_warnings)
  endif()
  set_target_properties(${name} PROPERTIES
    PREFIX ""
    OUTPUT_NAME "patina_${name}"
    C_VISIBILITY_PRESET hidden
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  if(ARG_OUTPUT_DIRECTORY)
    set_target_properties(${name} PROPERTIES LIBRARY_OUTPUT_DIRECTORY "${ARG_OUTPUT_DIRECTORY}")
  elseif(PATINA_BUILD_PLUGIN_DIR)
    set_target_properties(${name} PROPERTIES LIBRARY_OUTPUT_DIRECTORY "${PATINA_BUILD_PLUGIN_DIR}")
  endif()
  # Only the two ABI symbols leave the plugin: hidden visibility does not cover the unique
  # objects of inline C++ library code (std::to_string's digit table), a version script does.
  if(CMAKE_SYSTEM_NAME STREQUAL "Linux")
    set(_script "${CMAKE_CURRENT_BINARY_DIR}/${name}_exports.map")
    file(WRITE "${_script}"
         "{ global: patina_plugin_abi_version; patina_plugin_entry; local: *; };\n")
    target_link_options(${name} PRIVATE "LINKER:--version-script=${_script}")
    set_property(TARGET ${name} APPEND PROPERTY LINK_DEPENDS "${_script}")
  endif()
  set_property(GLOBAL APPEND PROPERTY PATINA_PLUGINS ${name})
  if(PROJECT_NAME STREQUAL "Patina" AND NOT ARG_NO_INSTALL)
    install(TARGETS ${name} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/patina/plugins)
  endif()
endfunction()
