# patina-texgen patina: the §5.1 urban script (Dorsey & Hanrahan 1996) as a time series on a
# strip and on a mesh, and bad scripts, each failing with one message naming the line and
# column and writing nothing.
include(${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(urban "${SOURCE_DIR}/samples/copper_strips/urban.patina")

# A strip, six steps: one stack per step and series.toml.
expect_success("${PATINA_TEXGEN}" patina "${urban}" -o "${WORK_DIR}/strip" --resolution 32
  --times 0,6,12,18,24,30 --quiet)
foreach(t t00 t06 t12 t18 t24 t30)
  foreach(f stack.toml preview.png total_thickness.exr layer01_tarnish.exr layer05_dirt.exr)
    if(NOT EXISTS "${WORK_DIR}/strip/${t}/${f}")
      message(FATAL_ERROR "patina wrote no ${t}/${f}")
    endif()
  endforeach()
endforeach()
file(READ "${WORK_DIR}/strip/series.toml" series)
expect_in("${series}" "folder = 't30'")
file(READ "${WORK_DIR}/strip/t30/stack.toml" stack)
expect_in("${stack}" "base = 'copper'")
expect_in("${stack}" "material = 'patina urban 4'")
expect_in("${stack}" "[maps.layer05_dirt]")

# A script with fewer layers written over the same folder drops the old layers.
file(WRITE "${WORK_DIR}/one.patina" "new copper\ncoat tarnish 1 0.5\nrender maps;\n")
expect_success("${PATINA_TEXGEN}" patina "${WORK_DIR}/one.patina" -o "${WORK_DIR}/strip/t30"
  --resolution 32 --quiet)
file(READ "${WORK_DIR}/strip/t30/stack.toml" stack)
string(FIND "${stack}" "layer05_dirt" stale)
if(NOT stale EQUAL -1 OR EXISTS "${WORK_DIR}/strip/t30/layer05_dirt.exr")
  message(FATAL_ERROR "a rerun left the earlier run's dirt layer:\n${stack}")
endif()

# On a mesh (a uv-mapped plane) with a curve, a built-in field and a grown map.
write_unit_square_obj("${WORK_DIR}/plane.obj")
file(WRITE "${WORK_DIR}/mesh.patina" [=[
curve age = (0 0, 10 1)
new copper
coat cuprite 2 1.0 age * inclination
coat rural patina 3 2.0 texture(DPD linear 20 40)
render maps
]=])
expect_success("${PATINA_TEXGEN}" patina "${WORK_DIR}/mesh.patina" --mesh "${WORK_DIR}/plane.obj"
  -o "${WORK_DIR}/mesh" --resolution 32 --times 5,10)
expect_in("${LAST_STDERR}" "2 step(s), 2 layer(s) over copper")
if(NOT EXISTS "${WORK_DIR}/mesh/t10/layer02_rural_patina_3.exr")
  message(FATAL_ERROR "the mesh run wrote no t10/layer02_rural_patina_3.exr")
endif()

# Bad scripts: line and column, and no output folder.
function(expect_script_error name text message_part)
  file(WRITE "${WORK_DIR}/${name}.patina" "${text}")
  expect_failure("${message_part}" "${PATINA_TEXGEN}" patina "${WORK_DIR}/${name}.patina"
    -o "${WORK_DIR}/bad_${name}" --resolution 16 --quiet)
  if(EXISTS "${WORK_DIR}/bad_${name}")
    message(FATAL_ERROR "a failed script (${name}) left ${WORK_DIR}/bad_${name} behind")
  endif()
endfunction()
expect_script_error(operator "new copper\nplate copper 1.0\n" "operator.patina:2:1:")
expect_script_error(material "new copper\ncoat marine patina 5 1.0\n"
  "material.patina:2:6: unknown material 'marine patina 5'")
expect_script_error(model "new copper\ncoat tarnish 1 0.35 texture(DBD linear 1 20);\n"
  "model.patina:2:29:")
expect_script_error(negative "new copper\ncoat tarnish 1 -0.35\n" "negative.patina:2:")
expect_script_error(missing_map "map wet = \"nowhere.exr\"\nnew copper\ncoat dirt 1.0 wet\n"
  "missing_map.patina:1:1:")
expect_failure("--times must ascend" "${PATINA_TEXGEN}" patina "${urban}" -o "${WORK_DIR}/bad_times"
  --times 6,0 --quiet)

# A periodic strip: the manifest says so, the layers differ from the open strip's (the same
# seed grows other edges), and a mesh has no strip boundary to choose.
expect_success("${PATINA_TEXGEN}" patina "${urban}" -o "${WORK_DIR}/periodic" --resolution 32
  --strip-boundary periodic --quiet)
file(READ "${WORK_DIR}/periodic/stack.toml" stack)
expect_in("${stack}" "periodic")
expect_success("${PATINA_TEXGEN}" patina "${urban}" -o "${WORK_DIR}/open" --resolution 32 --quiet)
file(READ "${WORK_DIR}/open/stack.toml" stack)
expect_in("${stack}" "open")
file(SHA256 "${WORK_DIR}/periodic/total_thickness.exr" periodic_hash)
file(SHA256 "${WORK_DIR}/open/total_thickness.exr" open_hash)
if(periodic_hash STREQUAL open_hash)
  message(FATAL_ERROR "--strip-boundary periodic grew the same layers as the open strip")
endif()
expect_failure("--strip-boundary" "${PATINA_TEXGEN}" patina "${urban}" -o "${WORK_DIR}/bad_boundary"
  --strip-boundary torus --quiet)
expect_failure("--mesh" "${PATINA_TEXGEN}" patina "${urban}" -o "${WORK_DIR}/bad_boundary"
  --mesh "${WORK_DIR}/plane.obj" --strip-boundary periodic --quiet)
