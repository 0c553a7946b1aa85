# Bounded inputs: requests for huge work are refused before anything is allocated, with one
# message naming the option (or the script's line and column) and the limit. Each of these
# crashed (stack overflow) or ended in std::bad_alloc, or ran for minutes, before the limits.
include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# A command that must fail quickly: a limit is checked before the work, not after it.
function(expect_quick_failure message_part)
  string(TIMESTAMP t0 "%s")
  expect_failure("${message_part}" ${ARGN})
  string(TIMESTAMP t1 "%s")
  math(EXPR seconds "${t1} - ${t0}")
  if(seconds GREATER 20)
    message(FATAL_ERROR "refusing took ${seconds} s: ${ARGN}")
  endif()
endfunction()

# --- the patina script parser: nesting depth ----------------------------------------------
string(REPEAT "(" 4000 open)
string(REPEAT ")" 4000 close)
file(WRITE "${WORK_DIR}/parens.patina" "new copper\ncoat tarnish 1 ${open}1${close}\n")
# The expression starts at column 16 (its first level); the 257th level opens at the
# 257th "(", column 15 + 257 of line 2.
expect_quick_failure("parens.patina:2:272: expression nested more than 256 levels deep"
  "${PATINA_TEXGEN}" patina "${WORK_DIR}/parens.patina" -o "${WORK_DIR}/p" --resolution 8 --quiet)
string(REPEAT "-" 200000 minus)
file(WRITE "${WORK_DIR}/minus.patina" "new copper\ncoat tarnish 1 ${minus}1\n")
expect_quick_failure("minus.patina:2:"
  "${PATINA_TEXGEN}" patina "${WORK_DIR}/minus.patina" -o "${WORK_DIR}/p" --resolution 8 --quiet)
string(REPEAT "1 + " 100000 chain)
file(WRITE "${WORK_DIR}/chain.patina" "new copper\ncoat tarnish 1 (${chain}1)\n")
expect_quick_failure("nested more than 256 levels deep"
  "${PATINA_TEXGEN}" patina "${WORK_DIR}/chain.patina" -o "${WORK_DIR}/p" --resolution 8 --quiet)

# --- patina: layers and time steps --------------------------------------------------------
set(coats "new copper\n")
foreach(i RANGE 1 300)
  string(APPEND coats "coat tarnish 1 0.01\n")
endforeach()
file(WRITE "${WORK_DIR}/coats.patina" "${coats}")
# The 257th coat is on line 258.
expect_quick_failure("coats.patina:258:"
  "${PATINA_TEXGEN}" patina "${WORK_DIR}/coats.patina" -o "${WORK_DIR}/p" --resolution 8 --quiet)
expect_failure("256 layers already"
  "${PATINA_TEXGEN}" patina "${WORK_DIR}/coats.patina" -o "${WORK_DIR}/p" --resolution 8 --quiet)
set(times "0")
foreach(i RANGE 1 1000)
  string(APPEND times ",${i}")
endforeach()
file(WRITE "${WORK_DIR}/one.patina" "new copper\ncoat tarnish 1 0.01\n")
expect_quick_failure("--times: 1001 times, more than the limit of 1000"
  "${PATINA_TEXGEN}" patina "${WORK_DIR}/one.patina" -o "${WORK_DIR}/p" --resolution 8
  --times "${times}" --quiet)
if(EXISTS "${WORK_DIR}/p")
  message(FATAL_ERROR "a refused patina run left '${WORK_DIR}/p' behind")
endif()

# --- fade: the wavelength grid ------------------------------------------------------------
expect_quick_failure("--wavelengths '300:830:0.000001': 5.3e+08 wavelengths, more than the limit of 4096"
  "${PATINA_TEXGEN}" fade --dose 1e6 --material congo_red --out "${WORK_DIR}/f"
  --wavelengths 300:830:0.000001 --quiet)

# --- stone: the world grid ----------------------------------------------------------------
write_small_cube_obj("${WORK_DIR}/cube.obj")
# 2048^3 voxels: more than a stone volume may hold (formats/stone_volume/stone_volume.h, what the
# slab_volume medium loads), refused before the run.
expect_quick_failure("a 2048x2048x2048 world volume is more than the 512^3 voxels"
  "${PATINA_TEXGEN}" stone --mesh "${WORK_DIR}/cube.obj" --grid 2048 --cycles 1
  --out "${WORK_DIR}/s" --quiet)

# --- exposure: the period's steps ---------------------------------------------------------
write_unit_square_obj("${WORK_DIR}/square.obj")
expect_quick_failure("--step-minutes 0.1: the period from 2000-01-01"
  "${PATINA_TEXGEN}" exposure --mesh "${WORK_DIR}/square.obj" -o "${WORK_DIR}/e"
  --resolution 8 --latitude 45 --longitude 0 --timezone 0 --start 2000-01-01
  --end 3000-01-01 --step-minutes 0.1 --quiet)

# --- patina-render: the film --------------------------------------------------------------
file(WRITE "${WORK_DIR}/scene.toml" "
[film]
width = 8
height = 8
[environment]
color = [1, 1, 1]
")
expect_quick_failure("--resolution"
  "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --resolution 1000000 1000000 --quiet
  --output "${WORK_DIR}/r.exr")
# Sample counts: the scene's own limit of 2^20 samples per pixel holds for the options too
# (--spp 2000000000 rendered nothing and replaced the EXR with NaN).
expect_quick_failure("--spp: Value 2000000000 not in range 1 to 1048576"
  "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --spp 2000000000 --quiet --output "${WORK_DIR}/r.exr")
expect_quick_failure("--samples '0-2000000000': B is at most 1048576"
  "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --samples 0-2000000000 --quiet
  --output "${WORK_DIR}/r.exr")
if(EXISTS "${WORK_DIR}/r.exr")
  message(FATAL_ERROR "a refused render wrote ${WORK_DIR}/r.exr")
endif()
