include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(WRITE "${WORK_DIR}/scene.toml" [=[
[[shader]]
name = "cloth"
type = "velvet"

[[object]]
shape = "sphere"
bsdf = "cloth"
]=])
expect_failure("no plugin provides shader 'velvet'"
  "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --output "${WORK_DIR}/out.exr")
if(EXISTS "${WORK_DIR}/out.exr")
  message(FATAL_ERROR "a failed render left an output file behind")
endif()
