# patina-texgen stone: a sandstone cube under rain as a time series (volumes, eroded mesh and
# surface maps per snapshot), and bad options failing with one message and writing nothing.
include(${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

write_uv_cube_obj("${WORK_DIR}/cube.obj")

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
