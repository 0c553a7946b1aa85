# patina-texgen uv-check: the report on stdout for good, overlapping and uv-less meshes;
# --strict turns missing or overlapping uvs into exit 1; unreadable meshes and bad options
# give one error line.
include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")


write_unit_square_obj("${WORK_DIR}/square.obj")
# Two squares on the same uvs.
file(WRITE "${WORK_DIR}/overlap.obj" [=[
v -1 0 1
v 1 0 1
v 1 0 -1
v -1 0 -1
v -1 2 1
v 1 2 1
v 1 2 -1
v -1 2 -1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
f 1/1 2/2 3/3 4/4
f 5/1 6/2 7/3 8/4
]=])
file(WRITE "${WORK_DIR}/no_uvs.obj" [=[
v -1 0 1
v 1 0 1
v 1 0 -1
f 1 2 3
]=])
file(WRITE "${WORK_DIR}/garbage.ply" "ply\nformat ascii 1.0\nelement vertex 3\n")

expect_success("${PATINA_TEXGEN}" uv-check "${WORK_DIR}/square.obj" --resolution 512 256)
expect_in("${LAST_STDOUT}" "triangles        2")
expect_in("${LAST_STDOUT}" "uv islands       1")
expect_in("${LAST_STDOUT}" "overlapping uvs  none")
expect_in("${LAST_STDOUT}" "udim tiles       1001")
# 512 * 256 texels over 4 m^2: 32768 texels/m^2, texels of sqrt(1/32768) m = 5.52 mm.
expect_in("${LAST_STDOUT}" "at 512 x 256: mean 3.277e+04 texels/m^2 (5.52 mm texels)")
expect_success("${PATINA_TEXGEN}" uv-check "${WORK_DIR}/square.obj" --strict)

expect_success("${PATINA_TEXGEN}" uv-check "${WORK_DIR}/overlap.obj" --resolution 64)
expect_in("${LAST_STDOUT}" "overlapping uvs  100% of the covered uv area")
expect_in("${LAST_STDOUT}" "uv islands       2")
expect_failure("has overlapping uvs (100% of the covered uv area, 2 triangle pairs)"
  "${PATINA_TEXGEN}" uv-check "${WORK_DIR}/overlap.obj" --resolution 64 --strict)

expect_success("${PATINA_TEXGEN}" uv-check "${WORK_DIR}/no_uvs.obj")
expect_in("${LAST_STDOUT}" "no uvs; bake per vertex with --per-vertex out.ply")
expect_failure("has no uvs" "${PATINA_TEXGEN}" uv-check "${WORK_DIR}/no_uvs.obj" --strict)

expect_failure("file not found" "${PATINA_TEXGEN}" uv-check "${WORK_DIR}/missing.obj")
expect_failure("garbage.ply" "${PATINA_TEXGEN}" uv-check "${WORK_DIR}/garbage.ply")
expect_failure("supersampling must be 1..8"
  "${PATINA_TEXGEN}" uv-check "${WORK_DIR}/square.obj" --supersampling 9)
