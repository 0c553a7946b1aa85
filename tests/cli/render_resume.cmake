# patina-render --checkpoint and --resume: a render stopped early (fewer samples, a time
# limit, a terminate signal) and continued from its own EXR is bitwise the render that never
# stopped, its sums included, whether continued once or twice; a tile too. A continuation of another scene,
# seed or tile, of an EXR without sums, or to no more samples is refused.
include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/lib/two_objects_scene.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
write_two_objects_scene("${WORK_DIR}/scene.toml" 16 [=["albedo", "normal", "depth"]=])
set(R "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --quiet --checkpoint)

expect_success(${R} --output "${WORK_DIR}/full.exr")
expect_success(oiiotool --info -a "${WORK_DIR}/full.exr")
expect_in("${LAST_STDOUT}" "2 subimages")

# 6 samples, then the other 10.
expect_success(${R} --spp 6 --output "${WORK_DIR}/six.exr")
expect_success(${R} --resume "${WORK_DIR}/six.exr" --output "${WORK_DIR}/resumed.exr")
expect_bitwise("${WORK_DIR}/full.exr" "${WORK_DIR}/resumed.exr")
# Twice: 3, then 9, then 16 (the EXR continued in place).
expect_success(${R} --spp 3 --output "${WORK_DIR}/twice.exr")
expect_success(${R} --spp 9 --resume "${WORK_DIR}/twice.exr" --output "${WORK_DIR}/twice.exr")
expect_success(${R} --resume "${WORK_DIR}/twice.exr" --output "${WORK_DIR}/twice.exr")
expect_bitwise("${WORK_DIR}/full.exr" "${WORK_DIR}/twice.exr")
# Stopped by a time limit after its first pass of 4 samples.
expect_success(${R} --time-limit 0.000001 --output "${WORK_DIR}/limited.exr")
expect_success(oiiotool --info -v "${WORK_DIR}/limited.exr")
expect_in("${LAST_STDOUT}" "patina:spp: 4")
expect_success(${R} --resume "${WORK_DIR}/limited.exr" --output "${WORK_DIR}/limited.exr")
expect_bitwise("${WORK_DIR}/full.exr" "${WORK_DIR}/limited.exr")
# A tile.
expect_success(${R} --tile 1/3 --output "${WORK_DIR}/tile_full.exr")
expect_success(${R} --tile 1/3 --spp 5 --output "${WORK_DIR}/tile.exr")
expect_success(${R} --tile 1/3 --resume "${WORK_DIR}/tile.exr" --output "${WORK_DIR}/tile.exr")
expect_bitwise("${WORK_DIR}/tile_full.exr" "${WORK_DIR}/tile.exr")
# A terminate signal (what a farm sends to a preempted task; here the fault injection of
# core/cancel.h, half-way through the render): the whole passes are written with their sums,
# the exit status is 130, and --resume finishes the render bitwise.
execute_process(COMMAND "${CMAKE_COMMAND}" -E env PATINA_TEST_SIGNAL_AT=compute
                        ${R} --output "${WORK_DIR}/signalled.exr"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 130 OR NOT err MATCHES "continue with --resume")
  message(FATAL_ERROR "a signalled --checkpoint render exited ${rc}:\n${err}")
endif()
expect_success(oiiotool --info -v "${WORK_DIR}/signalled.exr")
string(REGEX MATCH "patina:spp: ([0-9]+)" _ "${LAST_STDOUT}")
if(NOT CMAKE_MATCH_1 GREATER 0 OR NOT CMAKE_MATCH_1 LESS 16)
  message(FATAL_ERROR "the signalled render kept ${CMAKE_MATCH_1} samples, not 1 to 15")
endif()
expect_success(${R} --resume "${WORK_DIR}/signalled.exr" --output "${WORK_DIR}/signalled.exr")
expect_bitwise("${WORK_DIR}/full.exr" "${WORK_DIR}/signalled.exr")

# The sums matter: 6 samples alone are not the render.
execute_process(COMMAND oiiotool "${WORK_DIR}/full.exr" "${WORK_DIR}/six.exr" --diff --fail 0
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(rc EQUAL 0)
  message(FATAL_ERROR "6 samples equal 16: the comparison proves nothing")
endif()

# Refused.
expect_success("${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --quiet --spp 4
               --output "${WORK_DIR}/plain.exr")
expect_failure("holds no sums" ${R} --resume "${WORK_DIR}/plain.exr" --output "${WORK_DIR}/bad1.exr")
expect_failure("rendered with seed 3, this render has seed 4" ${R} --seed 4
  --resume "${WORK_DIR}/six.exr" --output "${WORK_DIR}/bad2.exr")
expect_failure("other pixels" ${R} --tile 0/3 --resume "${WORK_DIR}/six.exr"
  --output "${WORK_DIR}/bad3.exr")
expect_failure("ask for more with --spp" ${R} --spp 6 --resume "${WORK_DIR}/six.exr"
  --output "${WORK_DIR}/bad4.exr")
file(READ "${WORK_DIR}/scene.toml" text)
string(REPLACE "seed = 3" "seed = 3\n# another scene" text "${text}")
file(WRITE "${WORK_DIR}/other.toml" "${text}")
expect_failure("a render of another scene" "${PATINA_RENDER}" "${WORK_DIR}/other.toml" --quiet
  --resume "${WORK_DIR}/six.exr" --output "${WORK_DIR}/bad5.exr")
foreach(f bad1 bad2 bad3 bad4 bad5)
  if(EXISTS "${WORK_DIR}/${f}.exr")
    message(FATAL_ERROR "a refused --resume wrote ${f}.exr")
  endif()
endforeach()
