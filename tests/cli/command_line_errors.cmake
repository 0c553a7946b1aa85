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
expect_failure("unknown command 'bakee' (the commands are mesh, uv-check, unwrap, ao"
  "${PATINA_TEXGEN}" bakee --mesh x.obj)
expect_exit_code(2 "${PATINA_TEXGEN}" bakee)
# --help still prints and succeeds.
expect_exit_code(0 "${PATINA_TEXGEN}" --help)
expect_exit_code(0 "${PATINA_RENDER}" --help)
# A control character in an echoed option value is escaped.
string(ASCII 27 esc)
expect_failure("got '\\x1b[31mred'" "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --spp "${esc}[31mred")

# Values that used to be reported as something else.
expect_failure("--dose must be a finite number of J/m^2 >= 0, got -5"
  "${PATINA_TEXGEN}" fade --dose -5 --material congo_red --out "${WORK_DIR}/f")
file(WRITE "${WORK_DIR}/octaves.patina"
  "new copper\ncoat tarnish 1 0.3 texture(noise linear 1 30 octaves=1e10)\n")
# (a double outside int's range converted to int is undefined; it printed -2147483648)
expect_failure("octaves.patina:2:46: texture parameter 'octaves' must be a whole number (got 10000000000)"
  "${PATINA_TEXGEN}" patina "${WORK_DIR}/octaves.patina" -o "${WORK_DIR}/o" --resolution 8)
# Assimp reads a 'nan' coordinate of an OBJ file as 0: it is refused with its line.
file(WRITE "${WORK_DIR}/nan_uv.obj" "v -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\n"
  "vt 0 0\nvt nan 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n")
expect_failure("nan_uv.obj': line 6: 'vt' has a non-finite or malformed coordinate 'nan'"
  "${PATINA_TEXGEN}" uv-check "${WORK_DIR}/nan_uv.obj")

# NaN and infinities are refused by every number option of every tool, whatever range checks
# it has (the review found sky, sun, exposure and export options taking them and writing NaN
# maps or printing NaN angles with exit 0).
foreach(args "sky;-o;${WORK_DIR}/x.exr;--linke-turbidity;nan"
             "sky;-o;${WORK_DIR}/x.exr;--sun-azimuth;inf"
             "sun;--latitude;nan;--longitude;0;--date;2026-06-21"
             "sun;--latitude;45;--longitude;0;--date;2026-06-21;--delta-t;nan"
             "export;${WORK_DIR}/none;-o;${WORK_DIR}/x.glb;--normal-scale;nan")
  expect_failure("must be a finite number" "${PATINA_TEXGEN}" ${args})
endforeach()
expect_failure("--spp" "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --spp nan)
if(EXISTS "${WORK_DIR}/x.exr" OR EXISTS "${WORK_DIR}/x.glb")
  message(FATAL_ERROR "a refused command wrote its output")
endif()
