# patina-farm submit on a real one-node Slurm (the slurm fixture, tests/farm/slurm_cluster.sh):
# a 2-frame x 4-tile render and a 1-frame 4-way sample split, each a job array plus a merge
# job chained with afterok; the merged frames are bitwise (tiles) and to float rounding
# (samples) the one-process renders. A task run again does nothing (idempotent). A
# dry run writes the job folder (with its OpenJD template and shell loop) and submits
# nothing.
include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/lib/slurm.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
use_slurm_cluster()

foreach(frame 1 2)
  math(EXPR z "2 + ${frame}")
  file(WRITE "${WORK_DIR}/shot.000${frame}.toml" "[film]
width = 32
height = 20
spp = 8
seed = ${frame}
[camera]
from = [0, 1, ${z}]
to = [0, 0.5, 0]
[environment]
color = [0.8, 0.9, 1.0]
[[shader]]
name = \"clay\"
type = \"lambert\"
reflectance = [0.7, 0.4, 0.3]
[[object]]
shape = \"plane\"
size = 20.0
bsdf = \"clay\"
[[object]]
shape = \"sphere\"
center = [0, 0.6, 0]
radius = 0.6
bsdf = \"clay\"
")
  expect_success("${PATINA_RENDER}" "${WORK_DIR}/shot.000${frame}.toml" --quiet
                 --output "${WORK_DIR}/one_process.000${frame}.exr")
endforeach()
expect_success("${PATINA_RENDER}" "${WORK_DIR}/shot.0001.toml" --quiet --spp 16
               --output "${WORK_DIR}/one_process_16spp.exr")

function(expect_identical a b tolerance)
  execute_process(COMMAND oiiotool "${a}" "${b}" --diff --fail ${tolerance} --failpercent 0
                          --warn ${tolerance}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT out MATCHES "PASS")
    message(FATAL_ERROR "${b} differs from ${a}:\n${out}${err}")
  endif()
endfunction()

# 2 frames x 4 tiles, at most 2 tasks at once.
expect_success("${PATINA_FARM}" submit "${WORK_DIR}/shot.####.toml" --frames 1-2 --tiles 4
               --throttle 2 --job "${WORK_DIR}/tiles")
string(STRIP "${LAST_STDOUT}" ids)
string(REPLACE " " ";" ids "${ids}")
list(LENGTH ids n)
if(NOT n EQUAL 2)
  message(FATAL_ERROR "submit printed '${LAST_STDOUT}', not the array and merge job ids")
endif()
list(JOIN ids "," id_list)
wait_for_jobs("${id_list}")
foreach(frame 1 2)
  set(merged "${WORK_DIR}/tiles/frames/frame.000${frame}.exr")
  if(NOT EXISTS "${merged}")
    file(READ "${WORK_DIR}/tiles/logs/merge.log" log)
    message(FATAL_ERROR "the merge job wrote no ${merged}; its log:\n${log}")
  endif()
  expect_identical("${WORK_DIR}/one_process.000${frame}.exr" "${merged}" 0)
endforeach()
# A log per task and attempt: one attempt each here.
file(GLOB task_logs "${WORK_DIR}/tiles/logs/task_*.1.log")
list(LENGTH task_logs n)
if(NOT n EQUAL 8)
  message(FATAL_ERROR "expected 8 task logs (task_<i>.1.log), found ${n}")
endif()
# A task run again finds its valid output and does nothing.
file(TIMESTAMP "${WORK_DIR}/tiles/parts/f0001_t002_s000.exr" before "%s" UTC)
expect_success("${PATINA_FARM}" task "${WORK_DIR}/tiles" 2)
expect_in("${LAST_STDERR}" "already rendered")

# One frame, its 16 samples in 4 ranges.
expect_success("${PATINA_FARM}" submit "${WORK_DIR}/shot.0001.toml" --sample-splits 4 --spp 16
               --job "${WORK_DIR}/samples")
string(STRIP "${LAST_STDOUT}" ids)
string(REPLACE " " "," id_list "${ids}")
wait_for_jobs("${id_list}")
expect_identical("${WORK_DIR}/one_process_16spp.exr" "${WORK_DIR}/samples/frames/frame.0000.exr" 1e-5)

# A dry run: the folder, nothing submitted.
expect_success("${PATINA_FARM}" submit "${WORK_DIR}/shot.0001.toml" --tiles 2
               --job "${WORK_DIR}/dry" --dry-run)
expect_in("${LAST_STDOUT}" "not submitted")
foreach(f job.toml slurm_task.sh slurm_merge.sh run_local.sh job.openjd.yaml)
  if(NOT EXISTS "${WORK_DIR}/dry/${f}")
    message(FATAL_ERROR "the dry run wrote no ${f}")
  endif()
endforeach()
if(EXISTS "${WORK_DIR}/dry/submitted.toml")
  message(FATAL_ERROR "the dry run submitted")
endif()
# The OpenJD template moves with its folder: its job folder, program and plugin path are job
# parameters, and the plugin path reaches the tasks through a job environment. The folder
# copied elsewhere and its template run there (tests/clients/openjd_run.py, a minimal runner)
# render and merge the frame of the one-process render, PATINA_PLUGIN_PATH set from the
# template's PluginPath (the runner also checks that no step spells the old folder).
file(COPY "${WORK_DIR}/dry/" DESTINATION "${WORK_DIR}/moved/dry_elsewhere")
expect_success(${CMAKE_COMMAND} -E env --unset=PATINA_PLUGIN_PATH
               python3 "${SOURCE_DIR}/tests/clients/openjd_run.py"
               "${WORK_DIR}/moved/dry_elsewhere/job.openjd.yaml"
               "JobRoot=${WORK_DIR}/moved/dry_elsewhere" "PluginPath=${PLUGIN_DIR}")
expect_identical("${WORK_DIR}/one_process.0001.exr"
                 "${WORK_DIR}/moved/dry_elsewhere/frames/frame.0000.exr" 0)
# A job folder whose name holds quotes: the template still parses, with the folder as it is.
set(odd "${WORK_DIR}/it's \"odd\" job")
expect_success("${PATINA_FARM}" submit "${WORK_DIR}/shot.0001.toml" --tiles 2 --job "${odd}"
               --dry-run)
execute_process(COMMAND python3 -c "import sys, yaml
t = yaml.safe_load(open(sys.argv[1]))
print({p['name']: p.get('default') for p in t['parameterDefinitions']}['JobRoot'], end='')"
                "${odd}/job.openjd.yaml" OUTPUT_VARIABLE root RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT root STREQUAL "${odd}")
  message(FATAL_ERROR "the template of '${odd}' reads back as '${root}':\n${err}")
endif()
# The plain shell loop renders and merges the same frame without a scheduler; the finishing
# step removes the staging folder a killed task left (made here as one would be).
file(MAKE_DIRECTORY "${WORK_DIR}/dry/parts/.patina-staging-Kx7q2a/parts")
file(WRITE "${WORK_DIR}/dry/parts/.patina-staging-Kx7q2a/f0000_t000_s000.exr" "half written")
expect_success(bash "${WORK_DIR}/dry/run_local.sh")
if(EXISTS "${WORK_DIR}/dry/parts/.patina-staging-Kx7q2a")
  message(FATAL_ERROR "finish left a killed task's staging folder in parts/")
endif()
expect_identical("${WORK_DIR}/one_process.0001.exr" "${WORK_DIR}/dry/frames/frame.0000.exr" 0)
# A part cut short after its header (a node lost while writing it) is broken, not done, and
# the task renders it again.
file(GLOB dry_parts "${WORK_DIR}/dry/parts/*.exr")
list(GET dry_parts 0 cut_part)
file(SIZE "${cut_part}" cut_size)
math(EXPR cut_size "${cut_size} * 2 / 3")
execute_process(COMMAND truncate -s ${cut_size} "${cut_part}")
file(SIZE "${cut_part}" cut_now)
if(NOT cut_now EQUAL cut_size)
  message(FATAL_ERROR "could not cut ${cut_part} to ${cut_size} bytes (${cut_now})")
endif()
expect_success("${PATINA_FARM}" status "${WORK_DIR}/dry")
expect_in("${LAST_STDOUT}" ": broken")
expect_in("${LAST_STDOUT}" "1 broken, 0 missing")
expect_success(bash "${WORK_DIR}/dry/run_local.sh")
expect_success("${PATINA_FARM}" status "${WORK_DIR}/dry")
expect_in("${LAST_STDOUT}" "0 broken, 0 missing")

# A broken scene: every task fails, so the merge job (afterok) never runs; status names each
# task's failure from its log.
file(WRITE "${WORK_DIR}/broken.toml" "[film]
width = 16
height = 8
spp = 4
[camera]
from = [0, 1, 4]
to = [0, 0, 0]
[[shader]]
name = \"x\"
type = \"no_such_shader\"
[[object]]
shape = \"sphere\"
radius = 1.0
bsdf = \"x\"
")
expect_success("${PATINA_FARM}" submit "${WORK_DIR}/broken.toml" --tiles 2
               --job "${WORK_DIR}/broken")
string(STRIP "${LAST_STDOUT}" ids)
string(REPLACE " " "," id_list "${ids}")
wait_for_jobs("${id_list}")
if(EXISTS "${WORK_DIR}/broken/frames/frame.0000.exr" OR EXISTS "${WORK_DIR}/broken/logs/merge.log")
  message(FATAL_ERROR "the merge job ran although every task failed")
endif()
expect_success("${PATINA_FARM}" status "${WORK_DIR}/broken")
expect_in("${LAST_STDOUT}" "task 0 (frame 0, tile 0): missing: patina-render: error:")
expect_in("${LAST_STDOUT}" "no_such_shader")
expect_in("${LAST_STDOUT}" "2 task(s): 0 done, 0 running, 0 pending, 0 broken, 2 missing; 0 of 1 frame(s) merged; the merge did not run: a task it waits for failed")
# When squeue cannot be asked, status says so and fails, rather than show queued tasks as
# missing (a squeue that fails, first on the PATH).
file(MAKE_DIRECTORY "${WORK_DIR}/no_squeue")
file(WRITE "${WORK_DIR}/no_squeue/squeue" "#!/bin/sh\necho 'slurm_load_jobs error: Unable to contact slurm controller' >&2\nexit 1\n")
file(CHMOD "${WORK_DIR}/no_squeue/squeue" PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)
expect_failure("Slurm's queue could not be asked" "${CMAKE_COMMAND}" -E env
               "PATH=${WORK_DIR}/no_squeue:$ENV{PATH}" "${PATINA_FARM}" status "${WORK_DIR}/broken")

# A task cancelled while it runs and requeued (what preemption does): the array's afterok
# fails, so Slurm cancels the merge; resubmit finds every part there and valid, submits the
# merge alone, and the frame is bitwise the one-process render.
file(READ "${WORK_DIR}/shot.0001.toml" heavy)
string(REPLACE "width = 32" "width = 320" heavy "${heavy}")
string(REPLACE "height = 20" "height = 200" heavy "${heavy}")
string(REPLACE "spp = 8" "spp = 256" heavy "${heavy}")
file(WRITE "${WORK_DIR}/heavy.toml" "${heavy}")
expect_success("${PATINA_FARM}" submit "${WORK_DIR}/heavy.toml" --tiles 2 --throttle 1
               --job "${WORK_DIR}/requeue")
string(STRIP "${LAST_STDOUT}" ids)
string(REPLACE " " ";" ids "${ids}")
list(GET ids 0 array)
list(GET ids 1 merge)
set(running "")
foreach(i RANGE 120)
  execute_process(COMMAND squeue -h -r -j "${array}" -o "%K %t" OUTPUT_VARIABLE q ERROR_QUIET)
  if(q MATCHES "0 R")
    set(running 1)
    break()
  endif()
  execute_process(COMMAND sleep 0.25)
endforeach()
if(NOT running)
  message(FATAL_ERROR "task 0 of job ${array} never ran within 30 s")
endif()
expect_success(scancel "${array}_0")
expect_success(scontrol requeue "${array}_0")
# A requeued job waits for a begin time (two minutes): once it does, release it.
foreach(i RANGE 120)
  execute_process(COMMAND squeue -h -r -j "${array}" -o "%K %t %r" OUTPUT_VARIABLE q ERROR_QUIET)
  if(q MATCHES "0 PD BeginTime")
    expect_success(scontrol update "jobid=${array}_0" StartTime=now)
  elseif(NOT q MATCHES "(^|\n)0 ")
    break()
  endif()
  execute_process(COMMAND sleep 0.25)
endforeach()
wait_for_jobs("${array},${merge}")
# Task 0 ran twice: a log per attempt, the cancelled one kept.
foreach(attempt 1 2)
  if(NOT EXISTS "${WORK_DIR}/requeue/logs/task_0.${attempt}.log")
    message(FATAL_ERROR "the requeued task wrote no log for attempt ${attempt}")
  endif()
endforeach()
expect_success("${PATINA_FARM}" status "${WORK_DIR}/requeue")
expect_in("${LAST_STDOUT}" "2 task(s): 2 done, 0 running, 0 pending, 0 broken, 0 missing; 0 of 1 frame(s) merged")
expect_success("${PATINA_FARM}" resubmit "${WORK_DIR}/requeue")
string(STRIP "${LAST_STDOUT}" ids)
if(NOT ids MATCHES "^merge job ([0-9]+)$")
  message(FATAL_ERROR "resubmit printed '${LAST_STDOUT}', not the merge alone")
endif()
set(merge "${CMAKE_MATCH_1}")
wait_for_jobs("${merge}")
expect_success("${PATINA_RENDER}" "${WORK_DIR}/heavy.toml" --quiet
               --output "${WORK_DIR}/heavy_one_process.exr")
expect_identical("${WORK_DIR}/heavy_one_process.exr" "${WORK_DIR}/requeue/frames/frame.0000.exr" 0)
expect_success("${PATINA_FARM}" resubmit "${WORK_DIR}/requeue")
expect_in("${LAST_STDOUT}" "nothing to resubmit")
