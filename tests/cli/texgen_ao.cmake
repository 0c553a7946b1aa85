# patina-texgen ao and accessibility end to end: on an open plane AO is 1 and the tangent
# sphere reaches its cap everywhere (closed forms); the maps, their header parameters and
# stack.toml entries are written; the per-vertex mode writes a PLY; bad values of the
# baker options give one error line naming the option.
cmake_policy(SET CMP0007 NEW)
include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")


# Min and max of channel `channel` of an image, from oiiotool --stats.
function(channel_range image channel out_min out_max)
  execute_process(COMMAND oiiotool -v --stats "${image}" RESULT_VARIABLE rc
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "oiiotool --stats ${image} failed: ${err}")
  endif()
  string(REGEX MATCH "Stats Min: ([^\n(]*)" _ "${out}")
  string(STRIP "${CMAKE_MATCH_1}" mins)
  string(REPLACE " " ";" mins "${mins}")
  string(REGEX MATCH "Stats Max: ([^\n(]*)" _ "${out}")
  string(STRIP "${CMAKE_MATCH_1}" maxs)
  string(REPLACE " " ";" maxs "${maxs}")
  list(GET mins ${channel} lo)
  list(GET maxs ${channel} hi)
  set(${out_min} "${lo}" PARENT_SCOPE)
  set(${out_max} "${hi}" PARENT_SCOPE)
endfunction()

write_unit_square_obj("${WORK_DIR}/square.obj")
set(out "${WORK_DIR}/maps")

# AO of an open plane is exactly 1 in every texel (padding fills the rest with it).
expect_success("${PATINA_TEXGEN}" ao --mesh "${WORK_DIR}/square.obj" -o "${out}"
  --resolution 32 --rays 16 --padding -1 --quiet)
channel_range("${out}/ao.exr" 0 lo hi)
if(NOT lo STREQUAL "1.000000" OR NOT hi STREQUAL "1.000000")
  message(FATAL_ERROR "ao of an open plane should be 1 everywhere, got [${lo}, ${hi}]")
endif()

# Tangent sphere: on an open plane the radius is the cap, 0.25 m; accessibility 1.
expect_success("${PATINA_TEXGEN}" accessibility --mesh "${WORK_DIR}/square.obj" -o "${out}"
  --resolution 32 --max-radius 0.25 --padding -1 --quiet)
channel_range("${out}/accessibility.exr" 0 lo hi)
if(NOT lo STREQUAL "1.000000" OR NOT hi STREQUAL "1.000000")
  message(FATAL_ERROR "accessibility of an open plane should be 1, got [${lo}, ${hi}]")
endif()
channel_range("${out}/accessibility.exr" 1 lo hi)
if(NOT lo STREQUAL "0.250000" OR NOT hi STREQUAL "0.250000")
  message(FATAL_ERROR "accessibility_radius of an open plane should be 0.25, got [${lo}, ${hi}]")
endif()

# Offset surface: the plane is its own closing, so accessibility is (close to) 1.
expect_success("${PATINA_TEXGEN}" accessibility --mesh "${WORK_DIR}/square.obj" -o "${out}"
  --name offset --method offset-surface --voxels 32 --resolution 16 --max-radius 0.25
  --padding -1 --quiet)
channel_range("${out}/offset.exr" 0 lo hi)
if(lo LESS 0.97)
  message(FATAL_ERROR "offset-surface accessibility of an open plane should be ~1, got ${lo}")
endif()

file(READ "${out}/stack.toml" manifest)
expect_in("${manifest}" "[maps.ao]")
expect_in("${manifest}" "rays = 16")
expect_in("${manifest}" "[maps.accessibility]")
expect_in("${manifest}" "method = 'tangent-sphere'")
expect_in("${manifest}" "[maps.offset]")
expect_in("${manifest}" "voxels = 32")
# Every texel map ends with its coverage channel, named in the manifest (issue: a baked 0
# and an empty texel must differ).
string(REGEX MATCHALL "coverage = 'coverage.A'" coverage_lines "${manifest}")
list(LENGTH coverage_lines coverage_count)
if(NOT coverage_count EQUAL 3)
  message(FATAL_ERROR "3 maps, ${coverage_count} coverage entries in:\n${manifest}")
endif()
execute_process(COMMAND oiiotool --info -v "${out}/ao.exr" OUTPUT_VARIABLE header)
expect_in("${header}" "channel list: ao, coverage.A")
execute_process(COMMAND oiiotool -v --info "${out}/ao.exr" OUTPUT_VARIABLE header)
expect_in("${header}" "rays: 16")

# Per-vertex mode: a PLY with the channels as vertex properties.
expect_success("${PATINA_TEXGEN}" ao --mesh "${WORK_DIR}/square.obj"
  --per-vertex "${WORK_DIR}/ao.ply" --rays 8 --quiet)
file(READ "${WORK_DIR}/ao.ply" ply LIMIT 1000)
expect_in("${ply}" "property float ao")

expect_failure("--rays must be at least 1"
  "${PATINA_TEXGEN}" ao --mesh "${WORK_DIR}/square.obj" -o "${out}" --rays 0 --quiet)
expect_failure("--max-distance must be positive"
  "${PATINA_TEXGEN}" ao --mesh "${WORK_DIR}/square.obj" -o "${out}" --max-distance -2 --quiet)
expect_failure("--max-radius"
  "${PATINA_TEXGEN}" accessibility --mesh "${WORK_DIR}/square.obj" -o "${out}"
  --max-radius 0 --quiet)
expect_failure("--voxels must be in [8, 2048]"
  "${PATINA_TEXGEN}" accessibility --mesh "${WORK_DIR}/square.obj" -o "${out}"
  --method offset-surface --voxels 4 --quiet)
