# Installs Patina into a scratch prefix, builds samples/plugin_template against the installed
# package (find_package(Patina) + patina_add_plugin), and loads the result with the
# installed patina-render.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(LAST_OUTPUT "${out}${err}" PARENT_SCOPE)
endfunction()

run(${CMAKE_COMMAND} --install "${BINARY_DIR}" --prefix "${prefix}")
run(${CMAKE_COMMAND} -S "${SOURCE_DIR}/samples/plugin_template" -B "${WORK_DIR}/build"
    -G Ninja -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build "${WORK_DIR}/build")

if(NOT EXISTS "${WORK_DIR}/build/patina_checker.so")
  message(FATAL_ERROR "the out-of-tree plugin was not built where expected")
endif()
run("${prefix}/bin/patina-render" --list-shaders --plugin-path "${WORK_DIR}/build")
foreach(expect checker_lambert color_a scale lambert conductor dielectric emitter)
  string(FIND "${LAST_OUTPUT}" "${expect}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "--list-shaders output lacks '${expect}':\n${LAST_OUTPUT}")
  endif()
endforeach()
message(STATUS "out-of-tree plugin built and listed")
