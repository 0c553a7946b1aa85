# patina-texgen stone --checkpoint / --resume / --until: a run cut into segments (as a farm
# runs it), and a run stopped by SIGTERM and resumed, write every snapshot bitwise as the run
# that never stopped. A checkpoint of other inputs, a damaged one and one past the run's end
# are refused with the file named.
include(${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
write_uv_cube_obj("${WORK_DIR}/cube.obj")

# 12 cycles on 8^3-voxel slabs: enough for the caches (halo marks, ghost hits, seam marks)
# to be in use when a segment ends.
set(S "${PATINA_TEXGEN}" stone --mesh "${WORK_DIR}/cube.obj" --stone sandstone
  --feature-size 0.05 --tangential-res 8 --depth-res 8 --cycles 12 --steps 3 --rain-dir 0 -1 0
  --deposit-value 0.3 --grid 16 --map-resolution 32 --quiet)
set(steps cycle_0000 cycle_0004 cycle_0008 cycle_0012)
function(expect_same_series a b)
  foreach(step IN LISTS steps)
    foreach(f volume.exr slabs.exr stone_colour.exr stone_crust.exr)
      expect_bitwise("${a}/${step}/${f}" "${b}/${step}/${f}")
    endforeach()
    file(SHA256 "${a}/${step}/eroded.obj" x)
    file(SHA256 "${b}/${step}/eroded.obj" y)
    if(NOT x STREQUAL y)
      message(FATAL_ERROR "${b}/${step}/eroded.obj differs from ${a}'s")
    endif()
  endforeach()
endfunction()

expect_success(${S} --out "${WORK_DIR}/whole")

# Three segments, each from the last one's checkpoint.
expect_success(${S} --out "${WORK_DIR}/seg" --until 4 --checkpoint "${WORK_DIR}/c4.stone")
if(EXISTS "${WORK_DIR}/seg/cycle_0008")
  message(FATAL_ERROR "the segment to cycle 4 wrote cycle 8")
endif()
expect_success(${S} --out "${WORK_DIR}/seg" --resume "${WORK_DIR}/c4.stone" --until 8
  --checkpoint "${WORK_DIR}/c8.stone")
expect_success(${S} --out "${WORK_DIR}/seg" --resume "${WORK_DIR}/c8.stone")
expect_same_series("${WORK_DIR}/whole" "${WORK_DIR}/seg")

# SIGTERM half-way (PATINA_TEST_SIGNAL_AT=compute: at 6 of 12 cycles): the snapshots so far
# and a checkpoint are kept, exit status 130; the resumed run finishes the series.
execute_process(COMMAND "${CMAKE_COMMAND}" -E env PATINA_TEST_SIGNAL_AT=compute
  ${S} --out "${WORK_DIR}/sig" --checkpoint "${WORK_DIR}/sig.stone" --checkpoint-every 5
  RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 130 OR NOT err MATCHES "stopped at cycle 6" OR NOT EXISTS "${WORK_DIR}/sig.stone"
   OR NOT EXISTS "${WORK_DIR}/sig/cycle_0004/volume.exr" OR EXISTS "${WORK_DIR}/sig/cycle_0008")
  message(FATAL_ERROR "a signalled run should stop at cycle 6 with its checkpoint and cycle 4 "
    "(status ${rc}):\n${err}")
endif()
expect_success(${S} --out "${WORK_DIR}/sig" --resume "${WORK_DIR}/sig.stone")
expect_same_series("${WORK_DIR}/whole" "${WORK_DIR}/sig")

# Refused: other inputs (another seed), a damaged checkpoint, a resume past the run's end.
expect_failure("written by a run with other inputs" ${S} --seed 2 --out "${WORK_DIR}/bad"
  --resume "${WORK_DIR}/c4.stone")
file(WRITE "${WORK_DIR}/cut.stone" "patina stone checkpoint\n")
expect_failure("cut.stone': not a stone checkpoint" ${S} --out "${WORK_DIR}/bad"
  --resume "${WORK_DIR}/cut.stone")
file(SIZE "${WORK_DIR}/c4.stone" size)
math(EXPR keep "${size} - 100")
execute_process(COMMAND head -c ${keep} "${WORK_DIR}/c4.stone"
  OUTPUT_FILE "${WORK_DIR}/damaged.stone")  # cut short: the checksum no longer matches
expect_failure("damaged.stone': damaged" ${S} --out "${WORK_DIR}/bad"
  --resume "${WORK_DIR}/damaged.stone")
expect_failure("is at cycle 8, past the last cycle 4" ${S} --out "${WORK_DIR}/bad" --until 4
  --resume "${WORK_DIR}/c8.stone")
expect_failure("--checkpoint-every needs --checkpoint" ${S} --out "${WORK_DIR}/bad"
  --checkpoint-every 2)
if(EXISTS "${WORK_DIR}/bad")
  message(FATAL_ERROR "a refused run wrote ${WORK_DIR}/bad")
endif()
