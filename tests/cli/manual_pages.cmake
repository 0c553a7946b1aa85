# Every command's --help names its page of the manual, and that page exists in docs/.
include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")

function(expect_manual_page page)
  expect_success(${ARGN} --help)
  expect_in("${LAST_STDOUT}" "Manual: docs/${page}")
  if(NOT EXISTS "${SOURCE_DIR}/docs/${page}")
    message(FATAL_ERROR "${ARGN} --help names docs/${page}, which does not exist")
  endif()
endfunction()

expect_manual_page(render.md "${PATINA_RENDER}")
expect_manual_page(texgen.md "${PATINA_TEXGEN}")
foreach(pair mesh:texgen.md uv-check:texgen.md ao:texgen-ao.md accessibility:texgen-ao.md
        sun:texgen-exposure.md exposure:texgen-exposure.md wetness:texgen-wetness.md
        deposit:texgen-wetness.md patina:patina-script.md stone:stone.md flatten:flatten.md
        fade:fading.md forecast:forecast.md restore:forecast.md export:export.md)
  string(REPLACE ":" ";" parts "${pair}")
  list(GET parts 0 command)
  list(GET parts 1 page)
  expect_manual_page(${page} "${PATINA_TEXGEN}" ${command})
endforeach()
expect_manual_page(farm.md "${PATINA_FARM}")
foreach(command submit task finish merge)
  expect_manual_page(farm.md "${PATINA_FARM}" ${command})
endforeach()
