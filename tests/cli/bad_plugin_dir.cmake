include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
expect_failure("'/nonexistent/patina-plugins' does not exist"
  "${PATINA_RENDER}" --list-shaders --plugin-path /nonexistent/patina-plugins)
