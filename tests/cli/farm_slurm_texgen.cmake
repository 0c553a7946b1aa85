# patina-farm submit-texgen on a real one-node Slurm (the slurm fixture): a patina time series
# and a fade series as job arrays (a task per time, per dose) and a stone run as a chain of segments (each resuming the
# last one's checkpoint), each with its finishing job. Both are bitwise the one-process runs
# (every map's pixels; series.toml byte for byte). A cancelled segment takes the rest of the
# chain with it; `resubmit` runs the chain on from it, to the same bits. A task run again
# does nothing.
include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/lib/slurm.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
use_slurm_cluster()

function(expect_same_maps a b)
  file(GLOB maps RELATIVE "${a}" "${a}/*.exr")
  if(NOT maps)
    message(FATAL_ERROR "no maps in ${a}")
  endif()
  foreach(m IN LISTS maps)
    expect_bitwise("${a}/${m}" "${b}/${m}")
  endforeach()
endfunction()

# ---- A patina series: six times of the urban strip, 64 texels, at most 3 tasks at once.
set(script "${SOURCE_DIR}/samples/copper_strips/urban.patina")
set(times t00 t06 t12 t18 t24 t30)
expect_success("${PATINA_TEXGEN}" patina "${script}" --times 0,6,12,18,24,30 --resolution 64
               --no-preview -q -o "${WORK_DIR}/one_process")
expect_success("${PATINA_FARM}" submit-texgen --job "${WORK_DIR}/patina_job" --throttle 3 --
               patina "${script}" --times 0,6,12,18,24,30 --resolution 64 --no-preview -q
               -o "${WORK_DIR}/farm_series")
string(STRIP "${LAST_STDOUT}" ids)
string(REPLACE " " "," ids "${ids}")
wait_for_jobs("${ids}")
file(READ "${WORK_DIR}/one_process/series.toml" expected)
file(READ "${WORK_DIR}/farm_series/series.toml" got)
if(NOT got STREQUAL expected)
  message(FATAL_ERROR "the farm's series.toml differs from the one-process run's:\n${got}")
endif()
foreach(t IN LISTS times)
  expect_same_maps("${WORK_DIR}/one_process/${t}" "${WORK_DIR}/farm_series/${t}")
endforeach()
expect_success("${PATINA_FARM}" status "${WORK_DIR}/patina_job")
expect_in("${LAST_STDOUT}" "6 task(s): 6 done, 0 running, 0 pending, 0 broken, 0 missing; the series manifest written")
expect_success("${PATINA_FARM}" task "${WORK_DIR}/patina_job" 2)
expect_in("${LAST_STDERR}" "task 2 (t = 12 y): already done")

# ---- A fade series: the newsprint swatch at three doses, a stack each, each task given
# both CPUs (--cpus-per-task).
expect_success("${PATINA_FARM}" submit-texgen --job "${WORK_DIR}/fade_job" --cpus-per-task 2
               -- fade --dose 0,1e6,2.5e7 --material newsprint --entries 16 --quiet
               -o "${WORK_DIR}/fade_farm")
string(STRIP "${LAST_STDOUT}" ids)
string(REPLACE " " ";" id_list "${ids}")
list(GET id_list 0 fade_array)
string(REPLACE " " "," ids "${ids}")
wait_for_jobs("${ids}")
expect_success(scontrol show job "${fade_array}")
expect_in("${LAST_STDOUT}" "NumCPUs=2")
foreach(dose 0 1e6 2.5e7)
  expect_success("${PATINA_TEXGEN}" fade --dose ${dose} --material newsprint --entries 16 --quiet
                 -o "${WORK_DIR}/fade_one/${dose}")
  expect_same_maps("${WORK_DIR}/fade_one/${dose}" "${WORK_DIR}/fade_farm/${dose}")
endforeach()
expect_success("${PATINA_FARM}" status "${WORK_DIR}/fade_job")
expect_in("${LAST_STDOUT}" "task 1 (--dose 1e6): done")

# ---- A stone run: 12 cycles, snapshots every 4, three chained segments.
write_uv_cube_obj("${WORK_DIR}/cube.obj")
set(stone stone --mesh "${WORK_DIR}/cube.obj" --stone sandstone --feature-size 0.05
  --tangential-res 8 --depth-res 8 --cycles 12 --steps 3 --rain-dir 0 -1 0 --deposit-value 0.3
  --grid 16 --map-resolution 32 --quiet)
set(cycles cycle_0000 cycle_0004 cycle_0008 cycle_0012)
expect_success("${PATINA_TEXGEN}" ${stone} --out "${WORK_DIR}/stone_one_process")
expect_success("${PATINA_FARM}" submit-texgen --job "${WORK_DIR}/stone_job" --
               ${stone} --out "${WORK_DIR}/stone_farm")
string(STRIP "${LAST_STDOUT}" ids)
string(REPLACE " " ";" ids "${ids}")
list(GET ids 0 chain)
list(GET ids 1 finish)
string(REPLACE "," ";" chain "${chain}")
list(LENGTH chain n)
if(NOT n EQUAL 3)
  message(FATAL_ERROR "expected a chain of 3 jobs, got '${chain}'")
endif()
# Cancel the second segment while it waits for the first: the third and the finishing job
# can never run (--kill-on-invalid-dep).
list(GET chain 1 second)
expect_success(scancel "${second}")
string(REPLACE ";" "," all "${chain};${finish}")
wait_for_jobs("${all}")
expect_success("${PATINA_FARM}" status "${WORK_DIR}/stone_job")
expect_in("${LAST_STDOUT}" "task 0 (cycles 0-4): done")
expect_in("${LAST_STDOUT}" "task 1 (cycles 4-8): missing")
expect_in("${LAST_STDOUT}" "task 2 (cycles 8-12): missing")
if(EXISTS "${WORK_DIR}/stone_farm/cycle_0008")
  message(FATAL_ERROR "the cancelled segment wrote cycle 8")
endif()
expect_success("${PATINA_FARM}" resubmit "${WORK_DIR}/stone_job")
# "array job N" and "merge job M", a line each.
string(REGEX MATCHALL "job [0-9]+" ids "${LAST_STDOUT}")
string(REPLACE "job " "" ids "${ids}")
string(REPLACE ";" "," ids "${ids}")
if(NOT ids MATCHES "^[0-9]+(,[0-9]+)?$")
  message(FATAL_ERROR "resubmit printed '${LAST_STDOUT}', not labelled job ids")
endif()
wait_for_jobs("${ids}")
expect_success("${PATINA_FARM}" status "${WORK_DIR}/stone_job")
expect_in("${LAST_STDOUT}" "3 task(s): 3 done, 0 running, 0 pending, 0 broken, 0 missing")
foreach(c IN LISTS cycles)
  expect_same_maps("${WORK_DIR}/stone_one_process/${c}" "${WORK_DIR}/stone_farm/${c}")
endforeach()
expect_success("${PATINA_FARM}" resubmit "${WORK_DIR}/stone_job")
expect_in("${LAST_STDOUT}" "nothing to resubmit")
# Every step written, the finishing job removed the chain's checkpoints (not asked to keep
# them with --keep-checkpoints).
file(GLOB left "${WORK_DIR}/stone_job/checkpoints/*")
if(left)
  message(FATAL_ERROR "the finished chain kept its checkpoints: ${left}")
endif()

# Refused at submit, naming what is missing: a patina run without --times, a stone run
# without --steps or with an option the farm sets.
expect_failure("needs --times" "${PATINA_FARM}" submit-texgen --job "${WORK_DIR}/bad" --dry-run
               -- patina "${script}")
expect_failure("give --cycles N and --steps K" "${PATINA_FARM}" submit-texgen
               --job "${WORK_DIR}/bad" --dry-run -- stone --mesh "${WORK_DIR}/cube.obj")
expect_failure("needs a list, --duration" "${PATINA_FARM}" submit-texgen
               --job "${WORK_DIR}/bad" --dry-run -- fade --dose 1 --material newsprint -o x)
expect_failure("--resume: the farm cuts a stone run" "${PATINA_FARM}" submit-texgen
               --job "${WORK_DIR}/bad" --dry-run -- ${stone} --resume x.stone)
# The farm asks patina-texgen for its plan, so patina-texgen's own limits hold: 1001 steps
# are refused as a run without a farm refuses them.
set(many_times "0")
foreach(t RANGE 1 1000)
  string(APPEND many_times ",${t}")
endforeach()
expect_failure("--times: 1001 times, more than the limit of 1000" "${PATINA_FARM}" submit-texgen
               --job "${WORK_DIR}/bad" --dry-run -- patina "${script}" --times "${many_times}")
if(EXISTS "${WORK_DIR}/bad")
  message(FATAL_ERROR "a refused submit wrote ${WORK_DIR}/bad")
endif()
# The plan as patina-texgen prints it.
expect_success("${PATINA_TEXGEN}" patina "${script}" --times 0,30 -o "${WORK_DIR}/planned" --plan)
expect_in("${LAST_STDOUT}" "command = 'patina'")
expect_in("${LAST_STDOUT}" "folder = 't30'")
if(EXISTS "${WORK_DIR}/planned")
  message(FATAL_ERROR "--plan ran the series")
endif()
