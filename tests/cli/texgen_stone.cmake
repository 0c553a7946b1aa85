# patina-texgen stone: a sandstone cube under rain as a time series (volumes, eroded mesh and
# surface maps per snapshot), and bad options failing with one message and writing nothing.
include(${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# A closed 0.3 m cube, outward-wound, each face in its own cell of a 3 x 2 uv atlas.
set(obj "")
foreach(v "-1 -1 -1" "1 -1 -1" "1 1 -1" "-1 1 -1" "-1 -1 1" "1 -1 1" "1 1 1" "-1 1 1")
  string(REPLACE "1" "0.15" v "${v}")
  string(APPEND obj "v ${v}\n")
endforeach()
set(faces "5 6 7 8" "2 1 4 3" "6 2 3 7" "1 5 8 4" "8 7 3 4" "1 2 6 5")
set(cell 0)
foreach(f IN LISTS faces)
  math(EXPR c "${cell} % 3")
  math(EXPR r "${cell} / 3")
  math(EXPR u0 "${c} * 333 + 10")
  math(EXPR u1 "${c} * 333 + 323")
  math(EXPR v0 "${r} * 500 + 10")
  math(EXPR v1 "${r} * 500 + 490")
  string(APPEND obj "vt 0.${u0} 0.${v0}\nvt 0.${u1} 0.${v0}\nvt 0.${u1} 0.${v1}\nvt 0.${u0} 0.${v1}\n")
  string(REPLACE " " ";" idx "${f}")
  math(EXPR t0 "${cell} * 4 + 1")
  math(EXPR t1 "${cell} * 4 + 2")
  math(EXPR t2 "${cell} * 4 + 3")
  math(EXPR t3 "${cell} * 4 + 4")
  list(GET idx 0 a)
  list(GET idx 1 b)
  list(GET idx 2 cc)
  list(GET idx 3 d)
  string(APPEND obj "f ${a}/${t0} ${b}/${t1} ${cc}/${t2} ${d}/${t3}\n")
  math(EXPR cell "${cell} + 1")
endforeach()
# u0 "0.10" for cell 0 is 0.10, "0.343" for cell 1, "0.676" for cell 2: all inside [0, 1].
file(WRITE "${WORK_DIR}/cube.obj" "${obj}")

expect_success("${PATINA_TEXGEN}" stone --mesh "${WORK_DIR}/cube.obj" --stone sandstone
  --feature-size 0.05 --tangential-res 4 --depth-res 4 --cycles 4 --steps 2 --rain-dir 0 -1 0
  --grid 16 --map-resolution 32 --out "${WORK_DIR}/series")
expect_in("${LAST_STDERR}" "stone: 36 slabs of 4 x 4 x 4 voxels")
foreach(step cycle_0000 cycle_0002 cycle_0004)
  foreach(f volume.exr slabs.exr eroded.obj stone_colour.exr stone_crust.exr stack.toml)
    if(NOT EXISTS "${WORK_DIR}/series/${step}/${f}")
      message(FATAL_ERROR "stone wrote no ${step}/${f}")
    endif()
  endforeach()
endforeach()
file(READ "${WORK_DIR}/series/cycle_0004/stack.toml" stack)
expect_in("${stack}" "coverage = 'coverage.A'")
expect_in("${stack}" "stone_crust")
file(GLOB leftovers "${WORK_DIR}/series/*/*.tmp-*" "${WORK_DIR}/series/.patina-staging-*"
  "${WORK_DIR}/series/*/.patina-staging-*")
if(leftovers)
  message(FATAL_ERROR "temporary files left behind: ${leftovers}")
endif()

# Bad input: one message naming the fault, nothing written.
expect_failure("unknown stone 'basalt'" "${PATINA_TEXGEN}" stone --mesh "${WORK_DIR}/cube.obj"
  --stone basalt --out "${WORK_DIR}/bad1")
expect_failure("missing.exr" "${PATINA_TEXGEN}" stone --mesh "${WORK_DIR}/cube.obj"
  --wetness "${WORK_DIR}/missing.exr" --out "${WORK_DIR}/bad2" --quiet)
foreach(d bad1 bad2)
  if(EXISTS "${WORK_DIR}/${d}")
    message(FATAL_ERROR "a failed run created ${d}")
  endif()
endforeach()
