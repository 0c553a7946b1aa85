# scripts/make_movie.sh, which makes the lookdev sample's copper.mp4: the movie is tagged
# BT.709 (primaries, transfer, matrix, limited range) as ffprobe reads it, its Y'CbCr is
# the BT.709 matrix's (a saturated colour decoded with BT.709 comes back within 3 codes, as
# a player honouring the tags shows it), and a wrong frame count leaves no movie behind.
include(${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
foreach(tool ffmpeg ffprobe oiiotool)
  find_program(found_${tool} ${tool})
  if(NOT found_${tool})
    message(FATAL_ERROR "${tool} not found: install ffmpeg and openimageio-tools "
                        "(scripts/bootstrap.sh does)")
  endif()
endforeach()

# Three 64x36 frames of a saturated red (sRGB codes 204, 38, 38).
foreach(f 1 2 3)
  expect_success(oiiotool --pattern constant:color=0.8,0.15,0.15 64x36 3 -d uint8
    -o "${WORK_DIR}/frame.000${f}.png")
endforeach()
set(movie "${WORK_DIR}/movie.mp4")
expect_success("${SOURCE_DIR}/scripts/make_movie.sh" "${WORK_DIR}/frame.%04d.png" 2 "${movie}" 3)

expect_success(ffprobe -v error -select_streams v:0 -count_frames -show_entries
  stream=color_primaries,color_transfer,color_space,color_range,nb_read_frames
  -of default=noprint_wrappers=1 "${movie}")
message(STATUS "ffprobe: ${LAST_STDOUT}")
foreach(tag color_range=tv color_space=bt709 color_transfer=bt709 color_primaries=bt709
            nb_read_frames=3)
  expect_in("${LAST_STDOUT}" "${tag}")
endforeach()

# Decoded with the BT.709 matrix the tags name: the frame's colour, to x264's rounding.
expect_success(ffmpeg -y -loglevel error -i "${movie}" -frames:v 1
  -vf scale=in_color_matrix=bt709:in_range=tv,format=rgb24 "${WORK_DIR}/back.png")
expect_success(oiiotool "${WORK_DIR}/back.png" --printstats)
string(REGEX MATCH "Stats Avg: ([0-9.]+) ([0-9.]+) ([0-9.]+)" avg "${LAST_STDOUT}")
if(NOT avg)
  message(FATAL_ERROR "no average in oiiotool's stats:\n${LAST_STDOUT}")
endif()
set(got "${CMAKE_MATCH_1}" "${CMAKE_MATCH_2}" "${CMAKE_MATCH_3}")
set(want 204 38 38)
foreach(c 1 2 3)
  math(EXPR i "${c} - 1")
  list(GET want ${i} w)
  list(GET got ${i} g)
  # oiiotool prints an 8-bit image's averages in codes.
  math(EXPR lo "${w} - 3")
  math(EXPR hi "${w} + 3")
  execute_process(COMMAND awk "BEGIN { v = ${g}; exit !(v >= ${lo} && v <= ${hi}) }"
                  RESULT_VARIABLE inside)
  if(NOT inside EQUAL 0)
    message(FATAL_ERROR "channel ${c} decoded as ${g}, not ${w} +- 3: "
                        "the movie's matrix is not the BT.709 its tags say")
  endif()
endforeach()

# A wrong frame count: an error, and no movie (nor a temporary) left.
execute_process(COMMAND "${SOURCE_DIR}/scripts/make_movie.sh" "${WORK_DIR}/frame.%04d.png" 2
                        "${WORK_DIR}/short.mp4" 4
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "make_movie.sh accepted 3 frames as 4")
endif()
expect_in("${err}" "would hold 3 frames, not 4")
file(GLOB left "${WORK_DIR}/short*")
if(left)
  message(FATAL_ERROR "make_movie.sh left ${left}")
endif()
