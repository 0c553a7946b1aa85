# docs/shaders.md is what the shipped plugins declare: regenerate it with
#   patina-render --list-shaders --format markdown > docs/shaders.md
# when a parameter, its default, range or help text changes.
include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")

expect_success("${PATINA_RENDER}" --list-shaders --format markdown --no-bundled-plugins
               --plugin-path "${PLUGIN_DIR}")
file(READ "${SOURCE_DIR}/docs/shaders.md" committed)
if(NOT LAST_STDOUT STREQUAL committed)
  file(WRITE "${WORK_DIR}/shaders.md" "${LAST_STDOUT}")
  message(FATAL_ERROR "docs/shaders.md differs from the plugins' metadata; the generated "
          "reference is ${WORK_DIR}/shaders.md (regenerate with patina-render --list-shaders "
          "--format markdown > docs/shaders.md)")
endif()

# The text listing stays the default, and --format needs --list-shaders.
expect_success("${PATINA_RENDER}" --list-shaders --no-bundled-plugins --plugin-path "${PLUGIN_DIR}")
expect_in("${LAST_STDOUT}" "layered_km (bsdf)")
expect_failure("--format" "${PATINA_RENDER}" --format markdown)
