# patina-texgen export of stacks grown on a mesh and of fade stacks, each opened by the
# Khronos glTF validator (0 errors, 0 warnings):
# - a patina series grown on a mesh whose uvs span two UDIM tiles becomes that mesh with a
#   primitive and a material per tile (glTF has no UDIM), one variant per age; the stack
#   records its mesh, so export finds it; moved without it, export asks for --mesh;
# - a mesh on tile 1101 is refused (glTF materials per tile stop at 1099), nothing written;
# - two fade stacks of uniform dose (unfaded, a week under F11) become a swatch with the
#   variants "0 d" and "7 d"; a fade stack from an exposure map baked on a plane becomes
#   that plane.
include(${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/lib/gltf_validator.cmake)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# Two unit quads in the y = 0 plane facing +y, the first on tile 1001, the second on 1002.
file(WRITE "${WORK_DIR}/two_tiles.obj" "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1
v 1.5 0 0\nv 2.5 0 0\nv 2.5 0 -1\nv 1.5 0 -1
vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 1 0\nvt 2 0\nvt 2 1\nvt 1 1
vn 0 1 0
f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\nf 5/5/1 6/6/1 7/7/1\nf 5/5/1 7/7/1 8/8/1\n")
file(WRITE "${WORK_DIR}/coat.patina" "new copper;
coat tarnish 1 0.5 texture(ST cubic 1 20);
coat rural patina 3 1.0 texture(ST cubic 10 20);
render maps;\n")
expect_success("${PATINA_TEXGEN}" patina "${WORK_DIR}/coat.patina" --mesh "${WORK_DIR}/two_tiles.obj"
  -o "${WORK_DIR}/tiles" --resolution 16 --times 0,30 --quiet --no-preview)
expect_success("${PATINA_TEXGEN}" export "${WORK_DIR}/tiles" -o "${WORK_DIR}/tiles.glb")
expect_in("${LAST_STDERR}" "2 step(s) of 16x16")
expect_valid_gltf("${WORK_DIR}/tiles.glb")
expect_in("${LAST_VALIDATOR_REPORT}" "materials: 4")
file(READ "${WORK_DIR}/tiles.glb" glb OFFSET 20 LIMIT 16384)
expect_in("${glb}" "\"name\":\"tiles 30 y 1002\"")
expect_in("${glb}" "\"udim\":1001")

# Moved without its mesh: the stack's path to it no longer leads anywhere.
file(COPY "${WORK_DIR}/tiles" DESTINATION "${WORK_DIR}/moved")
expect_success("${CMAKE_COMMAND}" -E rename "${WORK_DIR}/two_tiles.obj" "${WORK_DIR}/renamed.obj")
expect_failure("pass --mesh" "${PATINA_TEXGEN}" export "${WORK_DIR}/moved/tiles"
  -o "${WORK_DIR}/moved.glb")
expect_success("${PATINA_TEXGEN}" export "${WORK_DIR}/moved/tiles" -o "${WORK_DIR}/moved.glb"
  --mesh "${WORK_DIR}/renamed.obj" --quiet)

# Tile 1101 (v in [10, 11)): beyond what export makes materials for.
file(WRITE "${WORK_DIR}/far.obj" "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1
vt 0 10\nvt 1 10\nvt 1 11\nvt 0 11\nvn 0 1 0\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n")
expect_success("${PATINA_TEXGEN}" patina "${WORK_DIR}/coat.patina" --mesh "${WORK_DIR}/far.obj"
  -o "${WORK_DIR}/far" --resolution 16 --quiet --no-preview)
expect_failure("UDIM tile 1101 is beyond 1099" "${PATINA_TEXGEN}" export "${WORK_DIR}/far"
  -o "${WORK_DIR}/far.glb")
if(EXISTS "${WORK_DIR}/far.glb")
  message(FATAL_ERROR "a refused export left far.glb behind")
endif()

# Fade stacks of a uniform dose: a swatch, one variant per stack in order of age.
expect_success("${PATINA_TEXGEN}" fade --dose 0 --material newsprint --out "${WORK_DIR}/np0"
  --entries 8 --quiet)
expect_success("${PATINA_TEXGEN}" fade --dose 6.048e7 --duration 7d --illuminant F11
  --material newsprint --out "${WORK_DIR}/np7" --entries 8 --quiet)
expect_success("${PATINA_TEXGEN}" export "${WORK_DIR}/np0" "${WORK_DIR}/np7"
  -o "${WORK_DIR}/swatch.glb")
expect_in("${LAST_STDERR}" "2 fade stack(s)")
expect_valid_gltf("${WORK_DIR}/swatch.glb")
file(READ "${WORK_DIR}/swatch.glb" glb OFFSET 20 LIMIT 8192)
expect_in("${glb}" "\"name\":\"0 d\"")
expect_in("${glb}" "\"name\":\"7 d\"")
expect_failure("in order of age" "${PATINA_TEXGEN}" export "${WORK_DIR}/np7" "${WORK_DIR}/np0"
  -o "${WORK_DIR}/backwards.glb")

# A fade stack from an exposure map baked on a plane: the plane, found through the map.
expect_success("${PATINA_TEXGEN}" mesh plane --size 0.5 -o "${WORK_DIR}/page.obj")
expect_success("${PATINA_TEXGEN}" exposure --mesh "${WORK_DIR}/page.obj" -o "${WORK_DIR}/sun"
  --latitude 43.47 --longitude -80.54 --timezone -5 --start 2026-06-21 --end 2026-06-22
  --sky clear --sun-bins-deg 10 --sky-samples 8 --resolution 16 --seed 1 --quiet)
expect_success("${PATINA_TEXGEN}" fade --exposure "${WORK_DIR}/sun/exposure.exr" --scale 0.58
  --material newsprint --out "${WORK_DIR}/page" --entries 8 --quiet)
expect_success("${PATINA_TEXGEN}" export "${WORK_DIR}/page" -o "${WORK_DIR}/page.glb")
expect_valid_gltf("${WORK_DIR}/page.glb")
# A faded page has no coat: no clearcoat extension anywhere in the asset.
expect_in("${LAST_VALIDATOR_REPORT}" "materials with an extension: none")
string(FIND "${LAST_VALIDATOR_REPORT}" "KHR_materials_clearcoat" coat_at)
if(NOT coat_at EQUAL -1)
  message(FATAL_ERROR "page.glb declares KHR_materials_clearcoat without a coat:\n${LAST_VALIDATOR_REPORT}")
endif()
expect_success("${PATINA_TEXGEN}" export "${WORK_DIR}/page" -o "${WORK_DIR}/page_unreal"
  --preset unreal --quiet)
if(NOT EXISTS "${WORK_DIR}/page_unreal/page_unreal_page_BaseColor.png")
  message(FATAL_ERROR "export --preset unreal of a fade stack wrote no BaseColor")
endif()
