# patina-texgen fade: a small exposure map (baked on a plane) into a fade stack, two maps
# whose doses add up, a uniform --dose with a plot, and bad inputs, each failing with one
# message and writing nothing.
include(${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# One clear June day on a 16x16 plane
write_unit_square_obj("${WORK_DIR}/plane.obj")
expect_success("${PATINA_TEXGEN}" exposure --mesh "${WORK_DIR}/plane.obj" -o "${WORK_DIR}/maps"
  --resolution 16 --latitude 43.5 --longitude -80.5 --timezone -5 --start 2026-06-21
  --end 2026-06-22 --sun-bins-deg 5 --sky-samples 16 --quiet)

expect_success("${PATINA_TEXGEN}" fade --exposure "${WORK_DIR}/maps/exposure.exr"
  --material newsprint --out "${WORK_DIR}/stack" --entries 16 --sublayers 20
  --wavelengths 300:830:10 --plot "${WORK_DIR}/stack.png")
expect_in("${LAST_STDERR}" "newsprint under D65")
foreach(f fade.toml fade_table.exr dose.exr)
  if(NOT EXISTS "${WORK_DIR}/stack/${f}")
    message(FATAL_ERROR "fade wrote no ${f}")
  endif()
endforeach()
if(NOT EXISTS "${WORK_DIR}/stack.png")
  message(FATAL_ERROR "fade --plot wrote no stack.png")
endif()
file(READ "${WORK_DIR}/stack/fade.toml" toml)
expect_in("${toml}" "material = 'newsprint'")
expect_in("${toml}" "channels = [ 'R_bottom', 'R_top', 'R_total', 'T' ]")
expect_in("${toml}" "entries = 16")
expect_in("${toml}" "max_interpolation_error")

# The same map twice: the doses add up
expect_success("${PATINA_TEXGEN}" fade --exposure "${WORK_DIR}/maps/exposure.exr"
  --exposure "${WORK_DIR}/maps/exposure.exr" --material newsprint --out "${WORK_DIR}/twice"
  --entries 16 --sublayers 20 --wavelengths 300:830:10)
if(NOT EXISTS "${WORK_DIR}/twice/dose.exr")
  message(FATAL_ERROR "fade with two maps wrote no dose.exr")
endif()

# A uniform dose under the fluorescent lamp, with a plot labelled in time
expect_success("${PATINA_TEXGEN}" fade --dose 6.048e7 --duration 7d --illuminant F11
  --material congo_red --out "${WORK_DIR}/lamp" --plot "${WORK_DIR}/lamp.png" --quiet)
if(NOT EXISTS "${WORK_DIR}/lamp.png")
  message(FATAL_ERROR "fade --dose --plot wrote no lamp.png")
endif()

# Bad inputs: one message each, no stack folder
function(expect_fade_error name message_part)
  expect_failure("${message_part}" "${PATINA_TEXGEN}" fade ${ARGN} --out "${WORK_DIR}/bad_${name}"
    --quiet)
  if(EXISTS "${WORK_DIR}/bad_${name}")
    message(FATAL_ERROR "a failed fade (${name}) left ${WORK_DIR}/bad_${name} behind")
  endif()
endfunction()
expect_fade_error(missing "does not exist" --exposure "${WORK_DIR}/nowhere.exr"
  --material newsprint)
expect_fade_error(material "newspaper" --exposure "${WORK_DIR}/maps/exposure.exr"
  --material newspaper)
expect_fade_error(both "exclude" --exposure "${WORK_DIR}/maps/exposure.exr" --dose 1
  --material newsprint)
expect_fade_error(duration "--duration '7 weeks'" --exposure "${WORK_DIR}/maps/exposure.exr"
  --duration "7 weeks" --material newsprint)
expect_fade_error(illuminant "D50" --dose 1e6 --illuminant D50 --material newsprint)
