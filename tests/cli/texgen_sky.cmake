# patina-texgen sky: the sky EXR and the [sun] it prints, pasted into a scene as they are,
# light a white Lambertian floor to radiance 1 (sky and sun give a horizontal surface the
# irradiance pi: L = R E / pi), for a clear sky with its sun and for an overcast sky alone.
# Bad options get one message and write nothing.
include(${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

foreach(sky clear overcast)
  expect_success("${PATINA_TEXGEN}" sky --sky ${sky} --sun-elevation 35 --sun-azimuth 150
                 --resolution 256 -o "${WORK_DIR}/${sky}.exr")
  set(snippet "${LAST_STDOUT}")
  if(sky STREQUAL "clear")
    expect_in("${snippet}" "[sun]")
  elseif(snippet MATCHES "\\[sun\\]")
    message(FATAL_ERROR "an overcast sky has no sun:\n${snippet}")
  endif()
  file(WRITE "${WORK_DIR}/${sky}_floor.toml" "[film]
width = 48
height = 48
spp = 64
seed = 1
[camera]
from = [0, 5, 0.01]
to = [0, 0, 0]
fov_deg = 20
[[shader]]
name = \"white\"
type = \"lambert\"
reflectance = 1
[[object]]
shape = \"plane\"
size = 1000
bsdf = \"white\"
${snippet}")
  expect_success("${PATINA_RENDER}" "${WORK_DIR}/${sky}_floor.toml" --quiet
                 --output "${WORK_DIR}/${sky}_floor.exr")
  expect_success(oiiotool "${WORK_DIR}/${sky}_floor.exr" --printstats)
  string(REGEX MATCH "Stats Avg: ([0-9.]+) ([0-9.]+) ([0-9.]+)" _ "${LAST_STDOUT}")
  foreach(c ${CMAKE_MATCH_1} ${CMAKE_MATCH_2} ${CMAKE_MATCH_3})
    if(c LESS 0.98 OR c GREATER 1.02)
      message(FATAL_ERROR "the ${sky} sky lights the white floor to ${c}, not 1 (+-2 %):\n${LAST_STDOUT}")
    endif()
  endforeach()
endforeach()

expect_failure("not above the horizon" "${PATINA_TEXGEN}" sky --sun-elevation -5
               -o "${WORK_DIR}/bad.exr")
expect_failure("--sky: " "${PATINA_TEXGEN}" sky --sky rainbow -o "${WORK_DIR}/bad.exr")
expect_failure("must be an .exr file" "${PATINA_TEXGEN}" sky -o "${WORK_DIR}/bad.png")
if(EXISTS "${WORK_DIR}/bad.exr" OR EXISTS "${WORK_DIR}/bad.png")
  message(FATAL_ERROR "a refused sky wrote a file")
endif()
