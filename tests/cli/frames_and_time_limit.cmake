# --frames substitutes '#' runs in the scene and output paths; --time-limit stops early and
# records the samples actually taken.
include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
foreach(frame 1 2)
  file(WRITE "${WORK_DIR}/scene.00${frame}.toml" "
[film]
width = 16
height = 8
spp = 2
[environment]
color = [${frame}, ${frame}, ${frame}]
[[shader]]
name = 'grey'
type = 'lambert'
[[object]]
shape = 'sphere'
bsdf = 'grey'
")
endforeach()
expect_success("${PATINA_RENDER}" "${WORK_DIR}/scene.###.toml" --frames 1-2 --quiet
               --output "${WORK_DIR}/out.####.exr")
foreach(f out.0001.exr out.0002.exr out.0001.png out.0002.png)
  if(NOT EXISTS "${WORK_DIR}/${f}")
    message(FATAL_ERROR "--frames did not write ${f}")
  endif()
endforeach()
expect_failure("scene file '${WORK_DIR}/scene.003.toml' does not exist"
  "${PATINA_RENDER}" "${WORK_DIR}/scene.###.toml" --frames 3 --quiet --output "${WORK_DIR}/x.exr")

# A time limit far below what a million samples per pixel need.
expect_success("${PATINA_RENDER}" "${WORK_DIR}/scene.001.toml" --spp 1000000 --time-limit 0.5
               --quiet --output "${WORK_DIR}/limited.exr")
expect_success(oiiotool --info -v "${WORK_DIR}/limited.exr")
string(REGEX MATCH "patina:spp: ([0-9]+)" m "${LAST_STDOUT}")
if(NOT CMAKE_MATCH_1 OR CMAKE_MATCH_1 GREATER_EQUAL 1000000)
  message(FATAL_ERROR "the time limit did not stop the render early:\n${LAST_STDOUT}")
endif()
