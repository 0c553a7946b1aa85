# patina-texgen flatten: the §5.1 urban strip (Dorsey & Hanrahan 1996) flattened into maps
# for other renderers, in sRGB and ACEScg; bad inputs fail with one message and write nothing.
include(${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(urban "${SOURCE_DIR}/samples/copper_strips/urban.patina")

expect_success("${PATINA_TEXGEN}" patina "${urban}" -o "${WORK_DIR}/urban" --resolution 32
  --quiet --no-preview)
expect_success("${PATINA_TEXGEN}" flatten "${WORK_DIR}/urban" -o "${WORK_DIR}/flat")
expect_in("${LAST_STDERR}" "5 layer(s) over copper, 32x32 x 1 tile(s)")
foreach(f diffuse_albedo height normal gltf_base_color gltf_metallic_roughness gltf_clearcoat
          interface00_copper_specular interface00_copper_roughness
          interface05_dirt_specular interface05_dirt_roughness)
  if(NOT EXISTS "${WORK_DIR}/flat/${f}.exr")
    message(FATAL_ERROR "flatten wrote no ${f}.exr")
  endif()
endforeach()
file(READ "${WORK_DIR}/flat/stack.toml" manifest)
expect_in("${manifest}" "[maps.diffuse_albedo]")
expect_in("${manifest}" "colorspace = 'srgb_texture'")
expect_in("${manifest}" "two_lobe = 'glTF 2.0 metallic-roughness + KHR_materials_clearcoat'")

# ACEScg, half floats, into the stack's own folder, from its stack.toml.
expect_success("${PATINA_TEXGEN}" flatten "${WORK_DIR}/urban/stack.toml" -o "${WORK_DIR}/urban"
  --color-space acescg --half --resolution 16 --quiet)
file(READ "${WORK_DIR}/urban/stack.toml" manifest)
expect_in("${manifest}" "colorspace = 'ACEScg'")
expect_in("${manifest}" "[maps.layer05_dirt]")

# Bad inputs.
expect_failure("no such file" "${PATINA_TEXGEN}" flatten "${WORK_DIR}/nowhere"
  -o "${WORK_DIR}/bad1")
expect_failure("--color-space" "${PATINA_TEXGEN}" flatten "${WORK_DIR}/urban"
  -o "${WORK_DIR}/bad2" --color-space rec2020)
expect_failure("--target 'maya': expected khronos" "${PATINA_TEXGEN}" flatten "${WORK_DIR}/urban"
  -o "${WORK_DIR}/bad2" --target maya)
file(COPY "${WORK_DIR}/urban/" DESTINATION "${WORK_DIR}/broken")
file(REMOVE "${WORK_DIR}/broken/layer03_patina_urban_3.exr")
expect_failure("map 'layer03_patina_urban_3': file" "${PATINA_TEXGEN}" flatten
  "${WORK_DIR}/broken" -o "${WORK_DIR}/bad3")
foreach(d bad1 bad2 bad3)
  if(EXISTS "${WORK_DIR}/${d}")
    message(FATAL_ERROR "a failed flatten left ${WORK_DIR}/${d} behind")
  endif()
endforeach()
