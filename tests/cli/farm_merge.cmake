# patina-farm merge: three tiles merge bitwise into the whole-frame render; four sample
# ranges (patina-render --samples) merge into the full-spp render to float rounding, with
# the total sample count in the header; parts that do not belong together (another seed,
# a gap or an overlap in the samples, two parts holding one pixel, a hole) are refused with
# the files named, and nothing is written.
include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/lib/two_objects_scene.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
write_two_objects_scene("${WORK_DIR}/scene.toml" 16 [=["albedo", "depth"]=])
set(R "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --quiet)
expect_success(${R} --output "${WORK_DIR}/full.exr")
foreach(i 0 1 2)
  expect_success(${R} --tile ${i}/3 --output "${WORK_DIR}/tile${i}.exr")
endforeach()
expect_success("${PATINA_FARM}" merge "${WORK_DIR}/tile2.exr" "${WORK_DIR}/tile0.exr"
               "${WORK_DIR}/tile1.exr" -o "${WORK_DIR}/tiles.exr")
expect_in("${LAST_STDERR}" "3 part(s), samples 0-16, pixels [0, 40) x [0, 23)")
execute_process(COMMAND oiiotool "${WORK_DIR}/full.exr" "${WORK_DIR}/tiles.exr" --diff
                        --fail 0 --failpercent 0 --warn 0
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "PASS")
  message(FATAL_ERROR "merged tiles differ from the whole frame:\n${out}${err}")
endif()
# The merged frame gets the display image the parts have, through the same display and
# view (patina:display, patina:view in their headers): the whole frame's, pixel for pixel.
if(NOT EXISTS "${WORK_DIR}/tiles.png")
  message(FATAL_ERROR "the merge wrote no display image tiles.png")
endif()
execute_process(COMMAND oiiotool "${WORK_DIR}/full.png" "${WORK_DIR}/tiles.png" --diff
                        --fail 0 --failpercent 0 --warn 0
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "PASS")
  message(FATAL_ERROR "the merged display image differs from the whole frame's:\n${out}${err}")
endif()

# Four sample ranges of 4: the same random streams as the 16-sample render, so the mean of
# their means is the full render up to the order of the sums (float rounding).
foreach(r 0-4 4-8 8-12 12-16)
  expect_success(${R} --samples ${r} --output "${WORK_DIR}/samples_${r}.exr")
endforeach()
expect_success("${PATINA_FARM}" merge "${WORK_DIR}/samples_0-4.exr" "${WORK_DIR}/samples_4-8.exr"
               "${WORK_DIR}/samples_8-12.exr" "${WORK_DIR}/samples_12-16.exr"
               -o "${WORK_DIR}/samples.exr")
# The bound is relative, as float rounding is: |merged − full| / max(|full|, 1e-3) at every
# pixel and channel, held to 1e-5 (a sum of 16 floats in another order differs by at most
# about 16 ulps, 1e-6 relative; highlights of 100 and more differ by 1e-5 absolute and more).
execute_process(COMMAND oiiotool "${WORK_DIR}/samples.exr" "${WORK_DIR}/full.exr" --absdiff
                        "${WORK_DIR}/full.exr" --abs --maxc 1e-3 --div --printstats
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCH "Stats Max: ([0-9.e+-]+) ([0-9.e+-]+) ([0-9.e+-]+)" _ "${out}")
if(NOT rc EQUAL 0 OR NOT CMAKE_MATCH_1)
  message(FATAL_ERROR "cannot compare the merged sample ranges with the full render:\n${out}${err}")
endif()
foreach(c ${CMAKE_MATCH_1} ${CMAKE_MATCH_2} ${CMAKE_MATCH_3})
  if(c GREATER 1e-5)
    message(FATAL_ERROR "merged sample ranges differ from the full render by ${c} relative "
                        "(at most 1e-5):\n${out}")
  endif()
endforeach()
message(STATUS "merged sample ranges against the full render: largest relative difference "
               "${CMAKE_MATCH_1} ${CMAKE_MATCH_2} ${CMAKE_MATCH_3}")
expect_success(oiiotool --info -v "${WORK_DIR}/samples.exr")
expect_in("${LAST_STDOUT}" "patina:spp: 16")
expect_in("${LAST_STDOUT}" "patina:merged_parts: 4")
# A range alone differs from the full render (the test can tell them apart).
execute_process(COMMAND oiiotool "${WORK_DIR}/full.exr" "${WORK_DIR}/samples_0-4.exr" --diff
                        --fail 1e-5 RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(rc EQUAL 0)
  message(FATAL_ERROR "4 samples of 16 match the full render: the comparison proves nothing")
endif()

# Parts that do not belong together.
expect_failure("samples 8-12 are in no part" "${PATINA_FARM}" merge
  "${WORK_DIR}/samples_0-4.exr" "${WORK_DIR}/samples_4-8.exr" "${WORK_DIR}/samples_12-16.exr"
  -o "${WORK_DIR}/bad1.exr")
expect_success(${R} --samples 2-6 --output "${WORK_DIR}/samples_2-6.exr")
expect_failure("overlap" "${PATINA_FARM}" merge "${WORK_DIR}/samples_0-4.exr"
  "${WORK_DIR}/samples_2-6.exr" -o "${WORK_DIR}/bad2.exr")
expect_success(${R} --seed 4 --tile 1/3 --output "${WORK_DIR}/seed4.exr")
expect_failure("has seed 4" "${PATINA_FARM}" merge "${WORK_DIR}/tile0.exr" "${WORK_DIR}/seed4.exr"
  -o "${WORK_DIR}/bad3.exr")
expect_failure("both hold pixel" "${PATINA_FARM}" merge "${WORK_DIR}/tile0.exr"
  "${WORK_DIR}/tile0.exr" -o "${WORK_DIR}/bad4.exr")
expect_failure("is in no part, inside the merged window" "${PATINA_FARM}" merge
  "${WORK_DIR}/tile0.exr" "${WORK_DIR}/tile2.exr" -o "${WORK_DIR}/bad5.exr")
expect_failure("--samples and --spp exclude each other" ${R} --samples 0-4 --spp 8
  --output "${WORK_DIR}/bad6.exr")
expect_failure("expected 0 <= A < B" ${R} --samples 4-4 --output "${WORK_DIR}/bad7.exr")
foreach(f bad1 bad2 bad3 bad4 bad5 bad6 bad7)
  if(EXISTS "${WORK_DIR}/${f}.exr")
    message(FATAL_ERROR "a refused merge or render left ${f}.exr behind")
  endif()
endforeach()

# A job folder reused for another split: the parts of the 2-tile job are not taken for the
# 4-tile job's (other bands), so the 4-tile job renders them and merges the frame bitwise.
expect_success("${PATINA_FARM}" submit "${WORK_DIR}/scene.toml" --tiles 2 --job "${WORK_DIR}/reused"
               --dry-run)
expect_success(bash "${WORK_DIR}/reused/run_local.sh")
expect_success("${PATINA_FARM}" submit "${WORK_DIR}/scene.toml" --tiles 4 --job "${WORK_DIR}/reused"
               --dry-run)
expect_success(bash "${WORK_DIR}/reused/run_local.sh")
execute_process(COMMAND oiiotool "${WORK_DIR}/full.exr" "${WORK_DIR}/reused/frames/frame.0000.exr"
                        --diff --fail 0 --failpercent 0 --warn 0
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "PASS")
  message(FATAL_ERROR "the reused job's frame differs from the whole frame:\n${out}${err}")
endif()

# Plugins: a part rendered with another build of a plugin (here the bundled basic plugin
# with a byte appended: another fingerprint) is refused by the merge; a job submitted with
# one plugin set refuses, at its merge, parts rendered with another.
file(COPY "${PLUGIN_DIR}/" DESTINATION "${WORK_DIR}/other_plugins")
file(APPEND "${WORK_DIR}/other_plugins/patina_basic.so" "x")
expect_success(${R} --tile 1/3 --no-bundled-plugins --plugin-path "${WORK_DIR}/other_plugins"
               --output "${WORK_DIR}/tile1_other.exr")
expect_failure("has plugins" "${PATINA_FARM}" merge "${WORK_DIR}/tile0.exr"
  "${WORK_DIR}/tile1_other.exr" "${WORK_DIR}/tile2.exr" -o "${WORK_DIR}/bad8.exr")
expect_success("${PATINA_FARM}" submit "${WORK_DIR}/scene.toml" --tiles 2 --job "${WORK_DIR}/job"
               --dry-run)
file(READ "${WORK_DIR}/job/job.toml" manifest)
if(NOT manifest MATCHES "plugins = 'basic [^']* ABI [0-9]+\\.[0-9]+ [0-9a-f]+'")
  message(FATAL_ERROR "job.toml records no plugin set:\n${manifest}")
endif()
string(REGEX REPLACE "plugins = '[^']*'" "plugins = 'basic 0.1.0 ABI 1.1 0000000000000000'"
       manifest "${manifest}")
file(WRITE "${WORK_DIR}/job/job.toml" "${manifest}")
expect_failure("was rendered with the plugins" bash "${WORK_DIR}/job/run_local.sh")
if(EXISTS "${WORK_DIR}/job/frames/frame.0000.exr" OR EXISTS "${WORK_DIR}/bad8.exr")
  message(FATAL_ERROR "a merge of parts with other plugins wrote its output")
endif()
# job.toml is read strictly: a key misspelt by hand is named with its line, not defaulted.
string(REPLACE "sample_splits = " "sample_split = " misspelt "${manifest}")
file(WRITE "${WORK_DIR}/job/job.toml" "${misspelt}")
expect_failure("job.sample_split: unknown key" "${PATINA_FARM}" status "${WORK_DIR}/job")
string(REPLACE "tiles = 2" "tiles = 'two'" mistyped "${manifest}")
file(WRITE "${WORK_DIR}/job/job.toml" "${mistyped}")
expect_failure("job.tiles: wrong type" "${PATINA_FARM}" status "${WORK_DIR}/job")
file(WRITE "${WORK_DIR}/job/job.toml" "${manifest}")
