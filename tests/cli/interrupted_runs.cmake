# A run's outputs change all at once or not at all. Each command first writes a result; a
# second run with other settings is then interrupted by SIGTERM in each phase (set-up,
# compute, write: PATINA_TEST_SIGNAL_AT makes the process signal itself there) or fails on
# a bad input or output found late. Every time, the folder must stay byte for byte as the
# first run left it, with no staging folder or temporary behind, the exit status 130 for a
# signal, and the message must say truthfully that nothing was written.
include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# Every path under `dir` (hidden ones too), with the SHA-256 of each file.
function(tree_digest dir out)
  file(GLOB_RECURSE entries LIST_DIRECTORIES true RELATIVE "${dir}" "${dir}/*")
  list(SORT entries)
  set(text "")
  foreach(e IN LISTS entries)
    if(IS_DIRECTORY "${dir}/${e}")
      string(APPEND text "${e}/\n")
    else()
      file(SHA256 "${dir}/${e}" h)
      string(APPEND text "${e} ${h}\n")
    endif()
  endforeach()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

function(expect_same_tree dir before what)
  tree_digest("${dir}" after)
  if(NOT after STREQUAL before)
    message(FATAL_ERROR "${what} changed '${dir}'.\nbefore:\n${before}\nafter:\n${after}")
  endif()
endfunction()

# Run the command (ARGN) with a SIGTERM at `phase`; expect exit 130, the truthful message
# and `dir` unchanged.
function(expect_interruption_changes_nothing dir phase)
  tree_digest("${dir}" before)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E env PATINA_TEST_SIGNAL_AT=${phase} ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 130)
    message(FATAL_ERROR "SIGTERM at ${phase}: expected exit 130, got ${rc}: ${ARGN}\n${err}")
  endif()
  string(REGEX MATCH "(no output was written|outputs were not written)" said "${err}")
  if(NOT said)
    message(FATAL_ERROR "SIGTERM at ${phase}: the message does not say nothing was written:\n${err}")
  endif()
  expect_same_tree("${dir}" "${before}" "a SIGTERM at ${phase} of ${ARGN}")
endfunction()

# Run the command (ARGN), expect the failure `message_part` and `dir` unchanged.
function(expect_failure_changes_nothing dir message_part)
  tree_digest("${dir}" before)
  expect_failure("${message_part}" ${ARGN})
  expect_same_tree("${dir}" "${before}" "a failed run of ${ARGN}")
endfunction()

set(phases setup compute write)

# --- patina: a time series (new steps, rewritten steps, deleted layers) -------------------
set(urban "${SOURCE_DIR}/samples/copper_strips/urban.patina")
expect_success("${PATINA_TEXGEN}" patina "${urban}" -o "${WORK_DIR}/strip" --resolution 16
  --times 0,6,30 --quiet)
foreach(phase IN LISTS phases)
  expect_interruption_changes_nothing("${WORK_DIR}/strip" ${phase}
    "${PATINA_TEXGEN}" patina "${urban}" -o "${WORK_DIR}/strip" --resolution 24
    --times 0,3,6,12,30 --seed 7 --quiet)
endforeach()
# A script whose one coat fails after the stacks of earlier steps were computed.
file(WRITE "${WORK_DIR}/huge.patina" "new copper\ncoat tarnish 3e38\n")
tree_digest("${WORK_DIR}/strip" before)
execute_process(COMMAND "${PATINA_TEXGEN}" patina "${WORK_DIR}/huge.patina" -o "${WORK_DIR}/strip"
  --resolution 16 --times 0,6,30 --quiet RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0)
  # Accepted as a (huge) thickness: then it must have replaced the series whole.
  message(STATUS "a 3e38 coat was accepted")
else()
  expect_same_tree("${WORK_DIR}/strip" "${before}" "the failed 3e38 coat run")
endif()

# --- ao: a bake into a stack folder -------------------------------------------------------
write_unit_square_obj("${WORK_DIR}/square.obj")
expect_success("${PATINA_TEXGEN}" ao --mesh "${WORK_DIR}/square.obj" -o "${WORK_DIR}/maps"
  --resolution 16 --rays 4 --quiet)
foreach(phase IN LISTS phases)
  expect_interruption_changes_nothing("${WORK_DIR}/maps" ${phase}
    "${PATINA_TEXGEN}" ao --mesh "${WORK_DIR}/square.obj" -o "${WORK_DIR}/maps"
    --resolution 32 --rays 8 --quiet)
endforeach()
# A corrupt stack.toml is found before ao.exr is replaced.
file(COPY "${WORK_DIR}/maps/" DESTINATION "${WORK_DIR}/corrupt")
file(WRITE "${WORK_DIR}/corrupt/stack.toml" "[stack\nformat = 1\n")
expect_failure_changes_nothing("${WORK_DIR}/corrupt" "stack.toml"
  "${PATINA_TEXGEN}" ao --mesh "${WORK_DIR}/square.obj" -o "${WORK_DIR}/corrupt"
  --resolution 32 --rays 8 --quiet)

# --- stone: a series of steps -------------------------------------------------------------
write_small_cube_obj("${WORK_DIR}/cube.obj")
set(stone_args stone --mesh "${WORK_DIR}/cube.obj" --stone sandstone --feature-size 0.05
  --tangential-res 4 --depth-res 4 --cycles 4 --steps 2 --rain-dir 0 -1 0 --grid 16
  --out "${WORK_DIR}/stone" --quiet)
expect_success("${PATINA_TEXGEN}" ${stone_args})
foreach(phase IN LISTS phases)
  expect_interruption_changes_nothing("${WORK_DIR}/stone" ${phase}
    "${PATINA_TEXGEN}" ${stone_args} --seed 9)
endforeach()

# --- fade: a fade stack and its plot ------------------------------------------------------
set(fade_args fade --dose 6.048e7 --duration 7d --illuminant F11 --material congo_red
  --out "${WORK_DIR}/fade/stack" --quiet)
expect_success("${PATINA_TEXGEN}" ${fade_args} --plot "${WORK_DIR}/fade/plot.png")
foreach(phase IN LISTS phases)
  expect_interruption_changes_nothing("${WORK_DIR}/fade" ${phase}
    "${PATINA_TEXGEN}" ${fade_args} --plot "${WORK_DIR}/fade/plot.png" --entries 12)
endforeach()
# A plot that cannot be written is found before the stack is replaced.
file(WRITE "${WORK_DIR}/fade/not_a_folder" "x")
expect_failure_changes_nothing("${WORK_DIR}/fade" "not_a_folder"
  "${PATINA_TEXGEN}" ${fade_args} --entries 12 --plot "${WORK_DIR}/fade/not_a_folder/x.png")

# --- patina-render: the EXR and PNG pair --------------------------------------------------
file(MAKE_DIRECTORY "${WORK_DIR}/render")
file(WRITE "${WORK_DIR}/scene.toml" "
[film]
width = 32
height = 16
spp = 4
[environment]
color = [1, 1, 1]
[[shader]]
name = 'grey'
type = 'lambert'
[[object]]
shape = 'sphere'
bsdf = 'grey'
")
expect_success("${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --quiet
  --output "${WORK_DIR}/render/out.exr")
foreach(phase IN LISTS phases)
  expect_interruption_changes_nothing("${WORK_DIR}/render" ${phase}
    "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --quiet --seed 5
    --output "${WORK_DIR}/render/out.exr")
endforeach()
# A folder named like the PNG: refused before rendering, out.exr kept.
file(MAKE_DIRECTORY "${WORK_DIR}/render2/out.png")
file(COPY "${WORK_DIR}/render/out.exr" DESTINATION "${WORK_DIR}/render2")
expect_failure_changes_nothing("${WORK_DIR}/render2" "out.png"
  "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" --quiet --output "${WORK_DIR}/render2/out.exr")

# A real SIGTERM from outside, mid-render: sent once the render reports progress (its
# first progress line: the plugins are loaded and the film is being rendered), so that a
# loaded machine cannot send it before the run has started.
tree_digest("${WORK_DIR}/render" before)
execute_process(COMMAND bash -c [=[
  "$0" "$1" --spp 100000 --resolution 256 128 --output "$2" 2> "$3" &
  pid=$!
  for i in $(seq 1200); do
    grep -q "render:" "$3" 2> /dev/null && break
    sleep 0.05
  done
  kill -TERM "$pid"
  wait "$pid"]=] "${PATINA_RENDER}" "${WORK_DIR}/scene.toml" "${WORK_DIR}/render/out.exr"
  "${WORK_DIR}/term.log"
  RESULT_VARIABLE rc)
file(READ "${WORK_DIR}/term.log" err)
if(NOT rc EQUAL 130)
  message(FATAL_ERROR "patina-render under SIGTERM: expected exit 130, got ${rc}:\n${err}")
endif()
expect_same_tree("${WORK_DIR}/render" "${before}" "a SIGTERM from outside")
