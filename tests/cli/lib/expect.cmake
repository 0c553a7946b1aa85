# Helpers for command-line tests run with `cmake -P`.
function(expect_failure message_part)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0)
    message(FATAL_ERROR "expected a non-zero exit from: ${ARGN}\nstdout: ${out}\nstderr: ${err}")
  endif()
  string(FIND "${err}" "${message_part}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "stderr of ${ARGN} lacks '${message_part}':\n${err}")
  endif()
  # One clear message: the error is reported once, on one line that starts with the tool.
  string(REGEX MATCHALL "patina-[a-z]+: error" hits "${err}")
  list(LENGTH hits n)
  if(NOT n EQUAL 1)
    message(FATAL_ERROR "expected exactly one 'patina-<tool>: error' line, got ${n}:\n${err}")
  endif()
endfunction()

function(expect_success)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed (${rc}): ${ARGN}\nstdout: ${out}\nstderr: ${err}")
  endif()
  set(LAST_STDOUT "${out}" PARENT_SCOPE)
  set(LAST_STDERR "${err}" PARENT_SCOPE)
endfunction()

# Fail unless `part` occurs in `text`.
function(expect_in text part)
  string(FIND "${text}" "${part}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "expected '${part}' in:\n${text}")
  endif()
endfunction()

# A 2 m square in the plane y = 0, facing up, whose uvs fill the unit square (texgen tests).
function(write_unit_square_obj path)
  file(WRITE "${path}" "v -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\n"
                       "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n")
endfunction()

# A 0.2 m cube standing on y = 0, no uvs (stone tests).
function(write_small_cube_obj path)
  file(WRITE "${path}" "v -0.1 0 -0.1\nv 0.1 0 -0.1\nv 0.1 0 0.1\nv -0.1 0 0.1\n"
    "v -0.1 0.2 -0.1\nv 0.1 0.2 -0.1\nv 0.1 0.2 0.1\nv -0.1 0.2 0.1\n"
    "f 1 2 3 4\nf 8 7 6 5\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n")
endfunction()
