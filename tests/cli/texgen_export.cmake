# patina-texgen export: the §5.1 urban strip (Dorsey & Hanrahan 1996) over three steps as one
# glTF 2.0 asset with a material variant per age, as .glb and as .gltf with its files, and
# a step's flattened maps as an asset of their own; the Khronos glTF validator finds no
# error and no warning in any; bad inputs fail with one message and write nothing.
include(${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/lib/gltf_validator.cmake)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(urban "${SOURCE_DIR}/samples/copper_strips/urban.patina")

expect_success("${PATINA_TEXGEN}" patina "${urban}" -o "${WORK_DIR}/urban" --resolution 32
  --times 0,6,30 --quiet --no-preview)
expect_success("${PATINA_TEXGEN}" export "${WORK_DIR}/urban" -o "${WORK_DIR}/urban.glb")
expect_in("${LAST_STDERR}" "3 step(s) of 32x32")
expect_valid_gltf("${WORK_DIR}/urban.glb")
expect_in("${LAST_VALIDATOR_REPORT}" "KHR_materials_variants")
expect_in("${LAST_VALIDATOR_REPORT}" "materials: 3")
# A clearcoat only on materials the fit gave a coat, and declared only then (the validator
# script fails an asset that declares a material extension no material uses).
expect_in("${LAST_VALIDATOR_REPORT}" "material extensions declared and unused: none")
# The variants are named by age (the JSON chunk starts after the 20 bytes of GLB header).
file(READ "${WORK_DIR}/urban.glb" glb OFFSET 20 LIMIT 8192)
expect_in("${glb}" "\"name\":\"0 y\"")
expect_in("${glb}" "\"name\":\"30 y\"")

# One step, as .gltf with its .bin and PNGs named by the template.
expect_success("${PATINA_TEXGEN}" export "${WORK_DIR}/urban/t30" -o "${WORK_DIR}/sep/strip.gltf"
  --separate --quiet)
# (A clearcoat map too where the fit gives the step a coat; the urban step has none here.)
foreach(f strip.bin strip_t30_base_color.png strip_t30_metallic_roughness.png
          strip_t30_normal.png)
  if(NOT EXISTS "${WORK_DIR}/sep/${f}")
    message(FATAL_ERROR "export --separate wrote no ${f}")
  endif()
endforeach()
expect_valid_gltf("${WORK_DIR}/sep/strip.gltf")

# A baked texture stack (flatten's maps) exports as the stack does.
expect_success("${PATINA_TEXGEN}" flatten "${WORK_DIR}/urban/t30" -o "${WORK_DIR}/flat" --quiet)
expect_success("${PATINA_TEXGEN}" export "${WORK_DIR}/flat" -o "${WORK_DIR}/flat.glb")
expect_in("${LAST_STDERR}" "flattened maps of 32x32")
expect_valid_gltf("${WORK_DIR}/flat.glb")
# Maps fitted for one renderer do not export for another.
expect_failure("fitted for --target khronos; flatten again with --target blender"
  "${PATINA_TEXGEN}" export "${WORK_DIR}/flat" -o "${WORK_DIR}/flat_blender.glb" --target blender)

# Bad inputs: one message, nothing written.
expect_failure("--preset 'maya'" "${PATINA_TEXGEN}" export "${WORK_DIR}/urban"
  -o "${WORK_DIR}/bad1.glb" --preset maya)
expect_failure("a binary glTF file" "${PATINA_TEXGEN}" export "${WORK_DIR}/urban"
  -o "${WORK_DIR}/bad2.gltf")
expect_failure("--target 'maya': expected khronos" "${PATINA_TEXGEN}" export "${WORK_DIR}/urban"
  -o "${WORK_DIR}/bad1.glb" --target maya)
# Name templates that would write outside -o, or no distinct file, are refused.
foreach(t "../$map" "/tmp/$map" "../../$map" "a/../../$map" "$map_$nosuch" "just_one")
  expect_failure("--name-template '${t}'" "${PATINA_TEXGEN}" export "${WORK_DIR}/urban"
    -o "${WORK_DIR}/bad_template" --preset unreal --name-template "${t}")
endforeach()
expect_failure("two maps would be written as" "${PATINA_TEXGEN}" export "${WORK_DIR}/urban"
  -o "${WORK_DIR}/bad_template" --preset unreal --name-template "$map")
expect_failure("two maps would be written as" "${PATINA_TEXGEN}" export "${WORK_DIR}/urban"
  -o "${WORK_DIR}/bad_template/a.gltf" --separate --name-template "$map")
if(EXISTS "${WORK_DIR}/bad_template" OR EXISTS "${WORK_DIR}/map.png")
  message(FATAL_ERROR "a refused name template wrote files")
endif()
expect_failure("no such file" "${PATINA_TEXGEN}" export "${WORK_DIR}/nowhere"
  -o "${WORK_DIR}/bad3.glb")
file(COPY "${WORK_DIR}/urban/" DESTINATION "${WORK_DIR}/broken")
file(REMOVE "${WORK_DIR}/broken/t06/thickness.exr")
expect_failure("does not exist" "${PATINA_TEXGEN}" export "${WORK_DIR}/broken"
  -o "${WORK_DIR}/bad4.glb")
# An output folder that cannot be made (a file is in the way; root can write anywhere else).
file(WRITE "${WORK_DIR}/a_file" "x")
expect_failure("'${WORK_DIR}/a_file' is not a folder" "${PATINA_TEXGEN}" export "${WORK_DIR}/urban"
  -o "${WORK_DIR}/a_file/bad5.glb")
foreach(f bad1.glb bad2.gltf bad3.glb bad4.glb)
  if(EXISTS "${WORK_DIR}/${f}")
    message(FATAL_ERROR "a failed export left ${WORK_DIR}/${f} behind")
  endif()
endforeach()
