# Every error of the command line is one line in the tools' form, `patina-<tool>: error:`,
# CLI11's own ones included, with short bounds and the unknown sub-command named; control
# characters of echoed input are escaped so that they cannot break the line or drive the
# terminal.
include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

function(expect_exit_code code)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  if(NOT rc EQUAL ${code})
    message(FATAL_ERROR "expected exit ${code}, got ${rc}: ${ARGN}")
  endif()
endfunction()

# CLI11's range check used to print the 309 digits of DBL_MAX as the bound.
expect_failure("--spp: must be a number > 0, got '-4'"
  "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --spp -4)
expect_exit_code(2 "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --spp -4)
expect_failure("--threads: must be a number >= 0, got '-1'"
  "${PATINA_TEXGEN}" ao --mesh x.obj --threads -1)
expect_failure("--strip-size: must be a number > 0, got 'nan'"
  "${PATINA_TEXGEN}" patina "${CMAKE_CURRENT_LIST_FILE}" --strip-size nan)
# An unknown sub-command is named, with the known ones (was "A subcommand is required").
expect_failure("unknown command 'bakee' (the commands are mesh, uv-check, ao"
  "${PATINA_TEXGEN}" bakee --mesh x.obj)
expect_exit_code(2 "${PATINA_TEXGEN}" bakee)
# --help still prints and succeeds.
expect_exit_code(0 "${PATINA_TEXGEN}" --help)
expect_exit_code(0 "${PATINA_RENDER}" --help)
# A control character in an echoed option value is escaped.
string(ASCII 27 esc)
expect_failure("got '\\x1b[31mred'" "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --spp "${esc}[31mred")
