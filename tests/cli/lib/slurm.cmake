# The one-node Slurm cluster of the farm.slurm_start fixture (tests/farm/slurm_cluster.sh),
# for the farm tests.

# Points squeue, sbatch and scontrol at the cluster (its SLURM_CONF), or fails when the
# fixture did not start it.
macro(use_slurm_cluster)
  if(NOT EXISTS "${SLURM_DIR}/env")
    message(FATAL_ERROR "no Slurm cluster in ${SLURM_DIR}: the farm.slurm_start fixture failed "
                        "(see its output; Debian 12's slurm-wlm and munge, scripts/bootstrap.sh)")
  endif()
  file(STRINGS "${SLURM_DIR}/env" slurm_env)
  foreach(line IN LISTS slurm_env)
    string(REGEX MATCH "^([A-Z_]+)=(.*)$" _ "${line}")
    set(ENV{${CMAKE_MATCH_1}} "${CMAKE_MATCH_2}")
  endforeach()
endmacro()

# Wait (at most 180 s) until the jobs `ids` have left the queue.
function(wait_for_jobs)
  foreach(i RANGE 360)
    execute_process(COMMAND squeue -h -j "${ARGV0}" -o %i RESULT_VARIABLE rc
                    OUTPUT_VARIABLE out ERROR_QUIET)
    string(STRIP "${out}" out)
    if(out STREQUAL "")
      return()
    endif()
    execute_process(COMMAND sleep 0.5)
  endforeach()
  message(FATAL_ERROR "jobs ${ARGV0} still queued after 180 s:\n${out}")
endfunction()
