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
# Its own tests, with the installed testing headers (chi-square, white furnace, reciprocity).
run(${CMAKE_CTEST_COMMAND} --test-dir "${WORK_DIR}/build" --output-on-failure)
string(FIND "${LAST_OUTPUT}" "100% tests passed" pos)
if(pos EQUAL -1)
  message(FATAL_ERROR "the template's tests did not all pass:\n${LAST_OUTPUT}")
endif()
run("${prefix}/bin/patina-render" --list-shaders --plugin-path "${WORK_DIR}/build")
foreach(expect checker_lambert color_a scale lambert conductor dielectric emitter)
  string(FIND "${LAST_OUTPUT}" "${expect}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "--list-shaders output lacks '${expect}':\n${LAST_OUTPUT}")
  endif()
endforeach()

# Patina::core and Patina::formats from the installed package: a small program using both.
file(WRITE "${WORK_DIR}/core_user/CMakeLists.txt" [=[
cmake_minimum_required(VERSION 3.25)
project(core_user LANGUAGES C CXX)
set(CMAKE_CXX_STANDARD 20)
find_package(Patina 0.1 REQUIRED)
add_executable(core_user main.cpp)
target_link_libraries(core_user PRIVATE Patina::core Patina::formats)
]=])
file(WRITE "${WORK_DIR}/core_user/main.cpp" [=[
#include "core/spectrum.h"
#include "formats/stone_volume/stone_volume.h"
#include <cstdio>
// D65 at 560 nm: 100 (CIE 15:2004, the table's normalisation); a stone volume's bounds part
// written and read back (ny = 3).
int main()
{
    patina::formats::VolumeGrid g;
    g.min = {0, 0, 0};
    g.max = {1, 1, 1};
    g.n = {2, 3, 4};
    const auto px = patina::formats::volume_bounds_pixels(g);
    const auto r = patina::formats::read_volume_bounds("v.exr", 3, 4, 1, px.data());
    std::printf("%.6f ny=%d", patina::d65(560.0f), r.n[1]);
}
]=])
run(${CMAKE_COMMAND} -S "${WORK_DIR}/core_user" -B "${WORK_DIR}/core_user/build" -G Ninja
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build "${WORK_DIR}/core_user/build")
run("${WORK_DIR}/core_user/build/core_user")
string(FIND "${LAST_OUTPUT}" "100.000000 ny=3" pos)
if(pos EQUAL -1)
  message(FATAL_ERROR "Patina::core consumer printed '${LAST_OUTPUT}', expected 100.000000 ny=3")
endif()
message(STATUS "out-of-tree plugin built and listed; Patina::core linked and ran")
