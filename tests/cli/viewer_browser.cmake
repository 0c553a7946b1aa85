# patina-texgen view in a real browser: Debian's chromium driven by Playwright
# (tests/clients/viewer_page.mjs; WebGL through SwiftShader), on the rural strip of D&H 1996
# §5.1 at 0, 15 and 30 years. The page loads from its folder (file://) with no console
# error, its canvas is not blank, and moving the age slider from 0 to 30 years turns the
# strip from copper to green (CIELAB hue angle), by about as much as patina-render shows,
# and under the Un-tone-mapped view the strip's colour is within a stated dE2000 of
# patina-render's display PNG of the same step, sky and camera. Without data.js or without
# WebGL the page says so. The screenshots at 0, 15 and 30 years also go to out/viewer/.
include(${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(page "${SOURCE_DIR}/tests/clients/viewer_page.mjs")

expect_success("${PATINA_TEXGEN}" patina "${SOURCE_DIR}/samples/copper_strips/rural.patina"
               --times 0,15,30 --resolution 64 -q -o "${WORK_DIR}/rural")
expect_success("${PATINA_TEXGEN}" export "${WORK_DIR}/rural" -o "${WORK_DIR}/rural.glb" --quiet)
expect_success("${PATINA_TEXGEN}" view "${WORK_DIR}/rural.glb" -o "${WORK_DIR}/viewer")
expect_in("${LAST_STDERR}" "view: 3 ages (0 y, 15 y, 30 y), views ACES 1.0 - SDR Video, Un-tone-mapped, Raw")
foreach(f index.html viewer.js data.js)
  if(NOT EXISTS "${WORK_DIR}/viewer/${f}")
    message(FATAL_ERROR "view wrote no ${f}")
  endif()
endforeach()

# The page at three ages; not blank (the strip against the sky).
file(MAKE_DIRECTORY "${SOURCE_DIR}/out/viewer")
foreach(age 0 15 30)
  set(shot "${WORK_DIR}/viewer_${age}y.png")
  expect_success(node "${page}" "${WORK_DIR}/viewer" screenshot "${shot}" ${age})
  expect_success(oiiotool "${shot}" --printstats)
  string(REGEX MATCH "Stats StdDev: ([0-9.]+)" _ "${LAST_STDOUT}")
  if(NOT CMAKE_MATCH_1 OR CMAKE_MATCH_1 LESS 0.02)
    message(FATAL_ERROR "the viewer's canvas at ${age} years is blank (standard deviation "
                        "${CMAKE_MATCH_1}):\n${LAST_STDOUT}")
  endif()
  file(COPY "${shot}" DESTINATION "${SOURCE_DIR}/out/viewer")
endforeach()

# The age slider: the strip's middle, un-tone-mapped, from copper towards green.
foreach(age 0 30)
  expect_success(node "${page}" "${WORK_DIR}/viewer" probe ${age} 0.4 0.3 0.2 0.3 "Un-tone-mapped")
  string(JSON hue_${age} GET "${LAST_STDOUT}" hue_deg)
endforeach()
message(STATUS "hue angle of the strip: ${hue_0} degrees at 0 years, ${hue_30} at 30")
# Copper is orange (h about 45 degrees), the rural patina green (h about 165).
if(hue_0 GREATER 90 OR hue_30 LESS 120 OR hue_30 GREATER 200)
  message(FATAL_ERROR "the slider from 0 to 30 years should turn the strip from copper "
                      "(hue ${hue_0}) to green (hue ${hue_30})")
endif()

# The asset framed in view, beside the controls: at a small and a large window its drawn
# bounding box lies inside the canvas and clear of the control panel.
foreach(size "800;500" "1920;1080")
  expect_success(node "${page}" "${WORK_DIR}/viewer" layout ${size})
  message(STATUS "layout at ${size}: ${LAST_STDOUT}")
  foreach(i 0 1 2 3)
    string(JSON a${i} GET "${LAST_STDOUT}" asset ${i})
    string(JSON c${i} GET "${LAST_STDOUT}" canvas ${i})
  endforeach()
  string(JSON panel_top GET "${LAST_STDOUT}" panel 1)
  execute_process(COMMAND node -e "const [a0,a1,a2,a3,c0,c1,c2,c3,p]=process.argv.slice(1).map(Number);
    process.exit(a0 >= c0 && a1 >= c1 && a2 <= c2 && a3 <= c3 && a3 <= p ? 0 : 1)"
    ${a0} ${a1} ${a2} ${a3} ${c0} ${c1} ${c2} ${c3} ${panel_top} RESULT_VARIABLE inside)
  if(NOT inside EQUAL 0)
    message(FATAL_ERROR "at ${size} the asset is not wholly in view above the controls: "
                        "${LAST_STDOUT}")
  endif()
endforeach()

# Antialiasing: the staircase corners of the strip's slanted edges, with and without it
# (228 without, 0 with FXAA measured at 1280x720).
expect_success(node "${page}" "${WORK_DIR}/viewer" aliasing)
string(JSON corners_off GET "${LAST_STDOUT}" off)
string(JSON corners_on GET "${LAST_STDOUT}" on)
message(STATUS "staircase corners: ${corners_off} without antialiasing, ${corners_on} with")
math(EXPR quarter "${corners_off} / 4")
if(corners_off LESS 50 OR corners_on GREATER quarter)
  message(FATAL_ERROR "antialiasing should remove most staircase corners (${corners_off} "
                      "without, ${corners_on} with; at most a quarter, of at least 50)")
endif()

# The viewer against patina-render: the same strip and step, the same sky (the viewer's
# lookdev sky is `patina-texgen sky` with its defaults, scaled alike), camera and view
# (Un-tone-mapped: the OCIO shader, no tone mapping), the strip's middle measured in both.
# They differ by what export does to a stack (its layers flattened into one PBR material,
# docs/export.md) and by three.js's shading (a prefiltered environment, its BRDF). Under the
# clear lookdev sky in the Un-tone-mapped view and in the default view at 0 EV (the exposure
# the viewer opens with), and under the overcast sky (the viewer's second light) in the
# default view.
expect_success("${PATINA_TEXGEN}" sky -o "${WORK_DIR}/sky.exr")
set(sky_toml "${LAST_STDOUT}")
expect_success("${PATINA_TEXGEN}" sky --sky overcast -o "${WORK_DIR}/overcast.exr")
set(overcast_toml "${LAST_STDOUT}")
# Export lays a strip in the xy plane facing +z (a swatch facing glTF's default camera);
# patina-render's plane faces +y, so it is turned to match. Both are seen head-on.
set(camera 0 0 0.25 0 0 0 25)
foreach(age 0 30)
  if(age EQUAL 0)
    set(step t00)
  else()
    set(step t30)
  endif()
  foreach(light clear_untonemapped clear_default overcast_default)
    if(light STREQUAL "clear_untonemapped")
      set(view "Un-tone-mapped")
      set(env 0)
      set(sky "${sky_toml}")
    elseif(light STREQUAL "clear_default")
      set(view "ACES 1.0 - SDR Video")
      set(env 0)
      set(sky "${sky_toml}")
    else()
      set(view "ACES 1.0 - SDR Video")
      set(env 1)
      set(sky "${overcast_toml}")
    endif()
    file(WRITE "${WORK_DIR}/strip_${age}_${light}.toml" "[film]
width = 320
height = 180
spp = 64
seed = 1
[camera]
from = [0, 0, 0.25]
to = [0, 0, 0]
fov_deg = 25
[output]
view = \"${view}\"
[[shader]]
name = \"strip\"
type = \"layered_km\"
stack = \"rural/${step}/stack.toml\"
[[object]]
shape = \"plane\"
size = 0.1
bsdf = \"strip\"
transform = { rotate_deg = [90, 0, 0] }
${sky}")
    expect_success("${PATINA_RENDER}" "${WORK_DIR}/strip_${age}_${light}.toml" --quiet
                   --output "${WORK_DIR}/strip_${age}_${light}.exr")
    expect_success(node "${page}" "${WORK_DIR}/viewer" compare ${age} "${view}"
                   "${WORK_DIR}/strip_${age}_${light}.png" 0.42 0.4 0.16 0.2 ${camera} ${env})
    string(JSON de GET "${LAST_STDOUT}" de2000)
    string(JSON lightness_viewer GET "${LAST_STDOUT}" viewer 0)
    string(JSON lightness_render GET "${LAST_STDOUT}" render 0)
    message(STATUS "${age} years, ${light}: viewer against patina-render dE2000 ${de}, L* "
                   "${lightness_viewer} against ${lightness_render}")
    if(light STREQUAL "clear_untonemapped")
      string(JSON hue_viewer_${age} GET "${LAST_STDOUT}" hue_viewer)
      string(JSON hue_render_${age} GET "${LAST_STDOUT}" hue_render)
    endif()
    # Measured 0.14-1.45 (export flattens the stack on the optics the renderer uses and
    # fits the glTF material for glTF's reference BRDF, docs/flatten.md); 4 leaves room for the software rasteriser's rounding, not for a wrong colour pipeline,
    # exposure or light (a missing sRGB decode, view or sky is over 10).
    if(de GREATER 4.0)
      message(FATAL_ERROR "the viewer's strip at ${age} years (${light}) is dE2000 ${de} "
                          "from patina-render's display PNG (at most 4)")
    endif()
  endforeach()
endforeach()
# The slider moves the colour by about as much as the renders do: the hue's change from 0 to
# 30 years within 20 degrees of patina-render's (measured 118 against 107).
execute_process(COMMAND node -e "const [a,b,c,d]=process.argv.slice(1).map(Number);
  console.log(Math.abs((b-a)-(d-c)).toFixed(3))" ${hue_viewer_0} ${hue_viewer_30}
  ${hue_render_0} ${hue_render_30} OUTPUT_VARIABLE hue_gap OUTPUT_STRIP_TRAILING_WHITESPACE)
message(STATUS "hue change: viewer against patina-render differ by ${hue_gap} degrees")
if(hue_gap GREATER 20)
  message(FATAL_ERROR "from 0 to 30 years the viewer's hue moves ${hue_gap} degrees more or "
                      "less than patina-render's (at most 20)")
endif()

# Without data.js, and without WebGL, the page says what is wrong (and nothing else fails).
file(COPY "${WORK_DIR}/viewer/" DESTINATION "${WORK_DIR}/no_data")
file(REMOVE "${WORK_DIR}/no_data/data.js")
execute_process(COMMAND node "${page}" "${WORK_DIR}/no_data" screenshot "${WORK_DIR}/x.png"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT out MATCHES "data.js is missing")
  message(FATAL_ERROR "a folder without data.js should say so:\n${out}${err}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -E env PATINA_NO_WEBGL=1
                        node "${page}" "${WORK_DIR}/viewer" screenshot "${WORK_DIR}/x.png"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT out MATCHES "needs WebGL2")
  message(FATAL_ERROR "a browser without WebGL should be told the viewer needs WebGL2:\n${out}${err}")
endif()

# Bad input: a .glb without variants, one message, nothing written.
expect_success("${PATINA_TEXGEN}" patina "${SOURCE_DIR}/samples/copper_strips/rural.patina"
               --times 30 --resolution 16 -q -o "${WORK_DIR}/one")
expect_success("${PATINA_TEXGEN}" export "${WORK_DIR}/one" -o "${WORK_DIR}/one.glb" --quiet)
expect_failure("has no material variants" "${PATINA_TEXGEN}" view "${WORK_DIR}/one.glb"
               -o "${WORK_DIR}/bad")
if(EXISTS "${WORK_DIR}/bad")
  message(FATAL_ERROR "a refused view wrote ${WORK_DIR}/bad")
endif()
