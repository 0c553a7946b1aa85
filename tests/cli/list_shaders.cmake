include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
# The bundled plugins are found next to the executable without any path being given.
expect_success("${PATINA_RENDER}" --list-shaders)
foreach(expect lambert reflectance conductor eta roughness dielectric emitter intensity
               "patina_basic.so")
  string(FIND "${LAST_STDOUT}" "${expect}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "--list-shaders lacks '${expect}':\n${LAST_STDOUT}")
  endif()
endforeach()
