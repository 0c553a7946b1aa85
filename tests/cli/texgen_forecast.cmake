# patina-texgen forecast, restore and fade --time-step: the conservation tools from the
# command line. A Blue Wool category under three policies (an LED, a halogen lamp behind a UV
# filter, a measured SPD file), per-texel maps from an exposure map baked on a plane, the
# simulation's depth profiles, a restoration, and bad inputs: one message each, nothing written.
include(${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# A "measured" lamp: a warm spectrum from 380 to 780 nm, and a broken copy of it
file(WRITE "${WORK_DIR}/lamp.csv" "# a measured lamp, relative\nwavelength_nm,warm\n380,5\n480,40\n580,80\n680,100\n780,110\n")
file(WRITE "${WORK_DIR}/broken.csv" "wavelength_nm,warm\n380,5\n480,40\n580,x\n780,110\n")
file(WRITE "${WORK_DIR}/policies.toml" "[[policy]]
name = \"LED 3000 K 50 lx\"
lamp = \"LED-B2\"
lux = 50

[[policy]]
name = \"halogen 50 lx UV filter\"
lamp = \"A\"
lux = 50
uv_filter = 400

[[policy]]
name = \"measured 100 lx\"
lamp = \"lamp.csv\"
lux = 100
hours_per_day = 10
days_per_year = 300
")
expect_success("${PATINA_TEXGEN}" forecast --blue-wool 3 --policies "${WORK_DIR}/policies.toml"
  --threshold 1.6 --years 40 -o "${WORK_DIR}/bw3")
# CIE 157:2004: Blue Wool 3 reaches a just-noticeable fade at 1.5 Mlx h; at 50 lx, 8 h a day,
# 365 days (146 klx h a year) that is 10.3 years under the LED it was defined with
expect_in("${LAST_STDOUT}" "LED 3000 K 50 lx")
string(REGEX MATCH "LED 3000 K 50 lx[^\n]*" led "${LAST_STDOUT}")
expect_in("${led}" " 1.5 ")
expect_in("${led}" " 10.3 ")
expect_in("${LAST_STDOUT}" "Reciprocity")
foreach(f policies.csv forecast.csv forecast.png)
  if(NOT EXISTS "${WORK_DIR}/bw3/${f}")
    message(FATAL_ERROR "forecast wrote no ${f}")
  endif()
endforeach()
file(READ "${WORK_DIR}/bw3/policies.csv" table)
expect_in("${table}" "threshold_mlx_h,years_to_threshold")
expect_in("${table}" "\"measured 100 lx\",\"warm\"")
file(STRINGS "${WORK_DIR}/bw3/forecast.csv" curve)
list(LENGTH curve rows)
if(NOT rows EQUAL 202)
  message(FATAL_ERROR "forecast.csv has ${rows} lines, expected a header and 201 points")
endif()

# Log-spaced years: four decades up to --years
expect_success("${PATINA_TEXGEN}" forecast --blue-wool 3 --lamp LED-B2 --lux 50 --threshold 1.6
  --years 100 --log-years -o "${WORK_DIR}/log")
file(STRINGS "${WORK_DIR}/log/forecast.csv" log_curve)
list(GET log_curve 1 first)
list(GET log_curve 201 last)
expect_in("${first}" "0.01,")
expect_in("${last}" "100,")

# One policy from options, twice the lux: half the years
expect_success("${PATINA_TEXGEN}" forecast --blue-wool 3 --lamp LED-B2 --lux 100 --threshold 1.6)
expect_in("${LAST_STDOUT}" " 5.14 ")

# Per texel: a clear June day on a 16x16 plane, repeated over a year
write_unit_square_obj("${WORK_DIR}/plane.obj")
expect_success("${PATINA_TEXGEN}" exposure --mesh "${WORK_DIR}/plane.obj" -o "${WORK_DIR}/maps"
  --resolution 16 --latitude 43.5 --longitude -80.5 --timezone -5 --start 2026-06-21
  --end 2026-06-22 --sun-bins-deg 5 --sky-samples 16 --quiet)
expect_success("${PATINA_TEXGEN}" forecast --material congo_red --exposure "${WORK_DIR}/maps/exposure.exr"
  --scale 0.58 --after 0.01 --wavelengths 300:830:10 --preview -o "${WORK_DIR}/texels")
expect_in("${LAST_STDERR}" "16x16 maps of congo_red")
file(READ "${WORK_DIR}/texels/stack.toml" stack)
expect_in("${stack}" "[maps.fade_forecast]")
expect_in("${stack}" "channels = [ 'years_to_threshold', 'delta_e_after', 'coverage.A' ]")
expect_in("${stack}" "baker = 'forecast'")
execute_process(COMMAND iinfo -v "${WORK_DIR}/texels/fade_forecast.exr" OUTPUT_VARIABLE info)
expect_in("${info}" "years_to_threshold")
expect_in("${info}" "delta_e_after")
expect_in("${info}" "coverage.A")
foreach(f fade_forecast_years.png fade_forecast_delta_e.png)
  if(NOT EXISTS "${WORK_DIR}/texels/${f}")
    message(FATAL_ERROR "forecast --preview wrote no ${f}")
  endif()
endforeach()
# The forecast on the plane it was baked on, as glTF: two variants, checked by the Khronos
# validator
include(${CMAKE_CURRENT_LIST_DIR}/lib/gltf_validator.cmake)
expect_success("${PATINA_TEXGEN}" export "${WORK_DIR}/texels" -o "${WORK_DIR}/texels.glb")
expect_in("${LAST_STDERR}" "a forecast of 16x16")
expect_valid_gltf("${WORK_DIR}/texels.glb")
expect_in("${LAST_VALIDATOR_REPORT}" "KHR_materials_variants")
expect_in("${LAST_VALIDATOR_REPORT}" "materials: 2")
# The variants name the threshold and the years, as the forecast recorded them
file(STRINGS "${WORK_DIR}/texels.glb" glb_text LIMIT_COUNT 8)
expect_in("${glb_text}" "years to dE00 1")
expect_in("${glb_text}" "dE00 after 0.01 y")

# The simulation itself: fractions over depth at 6 h and a day
expect_success("${PATINA_TEXGEN}" fade --material newsprint --illuminant flat --irradiance 1
  --time-step 1h --steps 24 --profiles-at 6h,1d --sublayers 20 --wavelengths 300:830:10
  -o "${WORK_DIR}/profiles" --quiet)
file(STRINGS "${WORK_DIR}/profiles/profiles.csv" profile)
list(GET profile 0 profile_header)
expect_in("${profile_header}" "time_s,sublayer,depth_um,fibre,lignin,newsprint_other,o_quinone")
list(LENGTH profile rows)
if(NOT rows EQUAL 61)
  message(FATAL_ERROR "profiles.csv has ${rows} lines, expected 1 + 3 times x 20 sublayers")
endif()
foreach(f profiles.png reflectance.csv reflectance.png)
  if(NOT EXISTS "${WORK_DIR}/profiles/${f}")
    message(FATAL_ERROR "fade --time-step wrote no ${f}")
  endif()
endforeach()

# A restoration, round trip: newsprint yellowed by the June day above (a fade stack), exported
# as a glTF base-colour texture (sRGB), restored with the stack's doses; the result is the
# unexposed newsprint's base colour (a --dose 0 stack exported the same way). The tint of
# newsprint ("newsprint_other") is gone at these doses, so the lignin alone is solved for.
expect_success("${PATINA_TEXGEN}" fade --exposure "${WORK_DIR}/maps/exposure.exr" --scale 0.58
  --duration 1d --material newsprint -o "${WORK_DIR}/yellowed" --quiet)
expect_success("${PATINA_TEXGEN}" export "${WORK_DIR}/yellowed" --separate -o "${WORK_DIR}/yellowed.gltf" -q)
expect_success("${PATINA_TEXGEN}" fade --dose 0 --material newsprint -o "${WORK_DIR}/fresh" --quiet)
expect_success("${PATINA_TEXGEN}" export "${WORK_DIR}/fresh" --separate -o "${WORK_DIR}/fresh.gltf" -q)
expect_success("${PATINA_TEXGEN}" restore --image "${WORK_DIR}/yellowed_yellowed_base_color.png"
  --material newsprint --dose-map "${WORK_DIR}/yellowed/dose.exr" --colorants lignin
  -o "${WORK_DIR}/restored")
expect_in("${LAST_STDERR}" "100.0% of the texels unique")
foreach(f restored.png restored.exr confidence.png confidence.exr amounts.exr)
  if(NOT EXISTS "${WORK_DIR}/restored/${f}")
    message(FATAL_ERROR "restore wrote no ${f}")
  endif()
endforeach()
function(mean_rgb file out)
  execute_process(COMMAND oiiotool "${file}" --printstats OUTPUT_VARIABLE stats RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "oiiotool cannot read ${file} (install openimageio-tools)")
  endif()
  string(REGEX MATCH "Avg: ([0-9]+)[.0-9]* ([0-9]+)[.0-9]* ([0-9]+)" m "${stats}")
  set(${out} "${CMAKE_MATCH_1};${CMAKE_MATCH_2};${CMAKE_MATCH_3}" PARENT_SCOPE)
endfunction()
mean_rgb("${WORK_DIR}/restored/restored.png" restored)
mean_rgb("${WORK_DIR}/fresh_fresh_base_color.png" fresh)
mean_rgb("${WORK_DIR}/yellowed_yellowed_base_color.png" yellowed)
foreach(c 0 1 2)
  list(GET restored ${c} r)
  list(GET fresh ${c} f)
  math(EXPR d "${r} - ${f}" OUTPUT_FORMAT DECIMAL)
  if(d GREATER 2 OR d LESS -2)
    message(FATAL_ERROR "restored ${restored} (of 255), the unexposed newsprint ${fresh}, faded ${yellowed}")
  endif()
endforeach()
list(GET yellowed 2 yb)
list(GET fresh 2 fb)
if(NOT fb GREATER yb)
  message(FATAL_ERROR "the day did not yellow the newsprint: ${yellowed} against ${fresh}")
endif()
# Both colorants at that dose: the tint is gone, so nothing is unique
expect_success("${PATINA_TEXGEN}" restore --image "${WORK_DIR}/yellowed_yellowed_base_color.png"
  --material newsprint --dose-map "${WORK_DIR}/yellowed/dose.exr" -o "${WORK_DIR}/restored_both")
expect_in("${LAST_STDERR}" " 0.0% of the texels unique")

# Bad inputs: one message each, no output folder
function(expect_forecast_error name message_part)
  expect_failure("${message_part}" "${PATINA_TEXGEN}" forecast ${ARGN} -o "${WORK_DIR}/bad_${name}")
  if(EXISTS "${WORK_DIR}/bad_${name}")
    message(FATAL_ERROR "a failed forecast (${name}) left ${WORK_DIR}/bad_${name} behind")
  endif()
endfunction()
expect_forecast_error(category "the ISO Blue Wool categories are 1" --blue-wool 9 --lamp A --lux 50)
expect_forecast_error(lux "--lux must be a finite number >= 0" --blue-wool 2 --lamp A --lux -50)
expect_forecast_error(spd "broken.csv:4" --blue-wool 2 --lamp "${WORK_DIR}/broken.csv" --lux 50)
expect_forecast_error(lamp "unknown illuminant 'LED-X'" --blue-wool 2 --lamp LED-X --lux 50)
expect_forecast_error(nolight "no lighting" --blue-wool 2)
file(WRITE "${WORK_DIR}/bad.toml" "[[policy]]\nname = \"a\"\nlamp = \"A\"\nlux = 50\nhours = 8\n")
expect_forecast_error(key "bad.toml:5:9: policy[0].hours: unknown key" --blue-wool 2
  --policies "${WORK_DIR}/bad.toml")
expect_failure("--profiles-at" "${PATINA_TEXGEN}" fade --material newsprint --irradiance 1
  --time-step 1h --steps 4 --profiles-at 90min -o "${WORK_DIR}/bad_profiles" --quiet)
expect_failure("give the light the image has had" "${PATINA_TEXGEN}" restore
  --image "${WORK_DIR}/fresh_fresh_base_color.png" --material newsprint -o "${WORK_DIR}/bad_restore")
foreach(d bad_profiles bad_restore)
  if(EXISTS "${WORK_DIR}/${d}")
    message(FATAL_ERROR "a failed command left ${WORK_DIR}/${d} behind")
  endif()
endforeach()
