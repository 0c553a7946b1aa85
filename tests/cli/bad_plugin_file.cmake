include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(WRITE "${WORK_DIR}/plugins/patina_broken.so" "not an ELF shared object\n")
expect_failure("patina_broken.so': cannot be loaded as a shared library"
  "${PATINA_RENDER}" --list-shaders --plugin-path "${WORK_DIR}/plugins")
# The same through the environment variable.
expect_failure("PATINA_PLUGIN_PATH"
  ${CMAKE_COMMAND} -E env "PATINA_PLUGIN_PATH=${WORK_DIR}/plugins"
  "${PATINA_RENDER}" --list-shaders)
