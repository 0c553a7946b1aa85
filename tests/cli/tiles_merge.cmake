# Farm use: three tiles of a frame, merged with oiiotool, are bitwise the whole-frame render;
# the whole frame with 1 and 2 threads is bitwise the same; AOV channels are present.
include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/lib/two_objects_scene.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
write_two_objects_scene("${WORK_DIR}/scene.toml" 4 [=["albedo", "normal", "depth"]=])
set(R "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --quiet)
expect_success(${R} --threads 1 --output "${WORK_DIR}/full1.exr")
expect_success(${R} --threads 2 --output "${WORK_DIR}/full2.exr")
foreach(i 0 1 2)
  expect_success(${R} --tile ${i}/3 --output "${WORK_DIR}/tile${i}.exr")
endforeach()
expect_success(oiiotool "${WORK_DIR}/tile0.exr" "${WORK_DIR}/tile1.exr" --add
               "${WORK_DIR}/tile2.exr" --add -d float -o "${WORK_DIR}/merged.exr")

# idiff-style bitwise comparison: every channel, every pixel, zero difference.
foreach(other full2 merged)
  execute_process(COMMAND oiiotool "${WORK_DIR}/full1.exr" "${WORK_DIR}/${other}.exr" --diff
                          --fail 0 --failpercent 0 --warn 0
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT out MATCHES "PASS")
    message(FATAL_ERROR "${other}.exr differs from the 1-thread whole frame:\n${out}${err}")
  endif()
endforeach()

# The AOV channels are in the file, and a crop keeps the full frame as display window.
expect_success(oiiotool --info -v "${WORK_DIR}/tile1.exr")
foreach(expect "albedo\\.R" "N\\.X" "Z" "40 x +8," "full/display size: 40 x 23"
               "pixel data origin: x=0, y=8")
  if(NOT LAST_STDOUT MATCHES "${expect}")
    message(FATAL_ERROR "tile1.exr header lacks '${expect}':\n${LAST_STDOUT}")
  endif()
endforeach()
