# patina-texgen wetness and deposit: bakes that write maps and stack.toml entries, and bad
# input (source files, --source values, input maps) that fails with one clear message naming
# the file and line and leaves no map behind.
include(${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# A 2 x 2 m ground quad with uvs, and a roof over its x < 0 half.
file(WRITE "${WORK_DIR}/ground.obj" [=[
v -1 0 -1
v 1 0 -1
v 1 0 1
v -1 0 1
vt 0 1
vt 1 1
vt 1 0
vt 0 0
vn 0 1 0
f 1/1/1 3/3/1 2/2/1
f 1/1/1 4/4/1 3/3/1
]=])
file(WRITE "${WORK_DIR}/roof.obj" [=[
v -2 1 -2
v 0 1 -2
v 0 1 2
v -2 1 2
f 1 2 3
f 1 3 4
]=])
set(maps "${WORK_DIR}/maps")

expect_success("${PATINA_TEXGEN}" wetness --mesh "${WORK_DIR}/ground.obj"
  --occluder "${WORK_DIR}/roof.obj" --resolution 16 --rays 16 --spread-deg 10 --quiet
  -o "${maps}")
if(NOT EXISTS "${maps}/wetness.exr")
  message(FATAL_ERROR "wetness wrote no wetness.exr")
endif()

file(WRITE "${WORK_DIR}/sources.toml" [=[
[[source]]
type = "sphere"
center = [0.5, 2.0, 0.0]
radius = 0.5

[[source]]
type = "directional"
direction = [1.0, -1.0, 0.0]
spread_deg = 10
strength = 0.5
]=])
expect_success("${PATINA_TEXGEN}" deposit --mesh "${WORK_DIR}/ground.obj"
  --occluder "${WORK_DIR}/roof.obj" --resolution 16 --rays 8 --access-rays 8 --quiet
  --sources "${WORK_DIR}/sources.toml" --source "disc center=0,3,0 normal=0,1,0 radius=1"
  -o "${maps}")
if(NOT EXISTS "${maps}/deposit.exr")
  message(FATAL_ERROR "deposit wrote no deposit.exr")
endif()

# Both maps are in the manifest, with their parameters.
file(READ "${maps}/stack.toml" manifest)
expect_in("${manifest}" "coverage = 'coverage.A'")
foreach(part "[maps.wetness]" "[maps.deposit]" "spread_deg = 10" "sphere center=0.5,2,0"
        "disc center=0,3,0")
  string(FIND "${manifest}" "${part}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "stack.toml lacks '${part}':\n${manifest}")
  endif()
endforeach()

# Wetness dried by the deposit map read as an exposure map (any channel can be named).
expect_success("${PATINA_TEXGEN}" wetness --mesh "${WORK_DIR}/ground.obj" --resolution 16
  --exposure "${maps}/deposit.exr" --exposure-channel deposit --drying 0.5 --name dried
  --quiet -o "${maps}")
if(NOT EXISTS "${maps}/dried.exr")
  message(FATAL_ERROR "wetness --name dried wrote no dried.exr")
endif()
# Defaults the baker resolved (the map's maximum, the mesh's lowest point) are recorded as
# numbers, so the map tells exactly how it was made.
file(READ "${maps}/stack.toml" manifest)
foreach(pattern "exposure_scale = [0-9]" "base_level = [-0-9]")
  if(NOT manifest MATCHES "${pattern}")
    message(FATAL_ERROR "stack.toml lacks a resolved '${pattern}':\n${manifest}")
  endif()
endforeach()

# Bad input: the message names the file and line (or the option), and nothing is written.
set(bad "${WORK_DIR}/bad")
file(WRITE "${WORK_DIR}/bad_sources.toml" [=[
[[source]]
type = "sphere"
radius = 1.0
centre = [0.0, 2.0, 0.0]
]=])
expect_failure("bad_sources.toml:4:" "${PATINA_TEXGEN}" deposit
  --mesh "${WORK_DIR}/ground.obj" --resolution 8 --sources "${WORK_DIR}/bad_sources.toml"
  -o "${bad}")
expect_failure("unknown key 'centre'" "${PATINA_TEXGEN}" deposit
  --mesh "${WORK_DIR}/ground.obj" --resolution 8 --sources "${WORK_DIR}/bad_sources.toml"
  -o "${bad}")
expect_failure("--source 'sphere center=0,2 radius=1': 'center' must be 3 numbers"
  "${PATINA_TEXGEN}" deposit --mesh "${WORK_DIR}/ground.obj" --resolution 8
  --source "sphere center=0,2 radius=1" -o "${bad}")
expect_failure("no deposit source" "${PATINA_TEXGEN}" deposit
  --mesh "${WORK_DIR}/ground.obj" --resolution 8 -o "${bad}")
expect_failure("missing.exr" "${PATINA_TEXGEN}" wetness --mesh "${WORK_DIR}/ground.obj"
  --resolution 8 --exposure "${WORK_DIR}/missing.exr" -o "${bad}")
expect_failure("--spread-deg 90" "${PATINA_TEXGEN}" wetness --mesh "${WORK_DIR}/ground.obj"
  --resolution 8 --spread-deg 90 -o "${bad}")
expect_failure("'w' is not an axis" "${PATINA_TEXGEN}" wetness --mesh "${WORK_DIR}/ground.obj"
  --resolution 8 --up w -o "${bad}")
if(EXISTS "${bad}/wetness.exr" OR EXISTS "${bad}/deposit.exr")
  message(FATAL_ERROR "a failed bake left a map behind in ${bad}")
endif()
