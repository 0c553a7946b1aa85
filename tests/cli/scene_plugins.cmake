# A scene's [plugins] path loads native code, so it is refused unless the user allows it:
# --allow-scene-plugins, or the folder lies in one that the trust file lists
# (scene_plugin_dirs in $PATINA_CONFIG_DIR/trust.toml). The refusal names the scene's line
# and says how to allow the folder.
include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/studio/plugins" "${WORK_DIR}/config" "${WORK_DIR}/elsewhere")
file(WRITE "${WORK_DIR}/scene.toml" "[plugins]
path = [\"studio/plugins\"]
[film]
width = 4
height = 4
spp = 1
[environment]
color = [1, 1, 1]
")
set(no_trust ${CMAKE_COMMAND} -E env "PATINA_CONFIG_DIR=${WORK_DIR}/config")

expect_failure("scene.toml:2:8: [plugins] path names '${WORK_DIR}/studio/plugins'"
  ${no_trust} "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --quiet -o "${WORK_DIR}/a.exr")
expect_failure("pass --allow-scene-plugins"
  ${no_trust} "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --quiet -o "${WORK_DIR}/a.exr")
if(EXISTS "${WORK_DIR}/a.exr")
  message(FATAL_ERROR "a refused scene was rendered")
endif()

# The switch allows it.
expect_success(${no_trust} "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --quiet
  -o "${WORK_DIR}/b.exr" --allow-scene-plugins)

# A trust file that lists the studio's folder allows it; one that lists another does not.
file(WRITE "${WORK_DIR}/config/trust.toml" "scene_plugin_dirs = [\"${WORK_DIR}/elsewhere\"]\n")
expect_failure("scene_plugin_dirs in ${WORK_DIR}/config/trust.toml"
  ${no_trust} "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --quiet -o "${WORK_DIR}/c.exr")
file(WRITE "${WORK_DIR}/config/trust.toml" "scene_plugin_dirs = [\"${WORK_DIR}/studio\"]\n")
expect_success(${no_trust} "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --quiet
  -o "${WORK_DIR}/d.exr")
# A '..' cannot climb out of a trusted folder.
file(WRITE "${WORK_DIR}/scene2.toml" "[plugins]
path = [\"studio/../elsewhere\"]
[environment]
color = [1, 1, 1]
")
expect_failure("elsewhere" ${no_trust} "${PATINA_RENDER}" "${WORK_DIR}/scene2.toml" --quiet
  -o "${WORK_DIR}/e.exr")
# A trust file that does not parse is named with its line.
file(WRITE "${WORK_DIR}/config/trust.toml" "scene_plugin_dirs = [\"relative/dir\"]\n")
expect_failure("trust.toml:1:22: scene_plugin_dirs entries must be absolute"
  ${no_trust} "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --quiet -o "${WORK_DIR}/f.exr")
