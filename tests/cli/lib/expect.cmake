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
  # ... on a line of its own: never after a progress line's carriage return.
  string(REGEX MATCH "(^|\n)patina-[a-z]+: error" own_line "${err}")
  if(NOT own_line)
    message(FATAL_ERROR "the error does not start a line of its own:\n${err}")
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

# A closed 0.3 m cube, outward-wound, each face in its own cell of a 3 x 2 uv atlas (stone
# tests).
function(write_uv_cube_obj path)
  set(obj "")
  foreach(v "-1 -1 -1" "1 -1 -1" "1 1 -1" "-1 1 -1" "-1 -1 1" "1 -1 1" "1 1 1" "-1 1 1")
    string(REPLACE "1" "0.15" v "${v}")
    string(APPEND obj "v ${v}\n")
  endforeach()
  set(faces "5 6 7 8" "2 1 4 3" "6 2 3 7" "1 5 8 4" "8 7 3 4" "1 2 6 5")
  set(cell 0)
  foreach(f IN LISTS faces)
    math(EXPR c "${cell} % 3")
    math(EXPR r "${cell} / 3")
    math(EXPR u0 "${c} * 333 + 10")
    math(EXPR u1 "${c} * 333 + 323")
    math(EXPR v0 "${r} * 500 + 10")
    math(EXPR v1 "${r} * 500 + 490")
    string(APPEND obj "vt 0.${u0} 0.${v0}\nvt 0.${u1} 0.${v0}\nvt 0.${u1} 0.${v1}\nvt 0.${u0} 0.${v1}\n")
    string(REPLACE " " ";" idx "${f}")
    math(EXPR t0 "${cell} * 4 + 1")
    math(EXPR t1 "${cell} * 4 + 2")
    math(EXPR t2 "${cell} * 4 + 3")
    math(EXPR t3 "${cell} * 4 + 4")
    list(GET idx 0 a)
    list(GET idx 1 b)
    list(GET idx 2 cc)
    list(GET idx 3 d)
    string(APPEND obj "f ${a}/${t0} ${b}/${t1} ${cc}/${t2} ${d}/${t3}\n")
    math(EXPR cell "${cell} + 1")
  endforeach()
  # u0 "0.10" for cell 0 is 0.10, "0.343" for cell 1, "0.676" for cell 2: all inside [0, 1].
  file(WRITE "${path}" "${obj}")
endfunction()

# Two images with the same bits: every part (a render's beauty and sums), channel and pixel.
function(expect_bitwise a b)
  execute_process(COMMAND oiiotool -a "${a}" -a "${b}" --diff --fail 0 --failpercent 0 --warn 0
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT out MATCHES "PASS")
    message(FATAL_ERROR "${b} differs from ${a}:\n${out}${err}")
  endif()
endfunction()
