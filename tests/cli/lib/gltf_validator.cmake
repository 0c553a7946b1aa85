# The Khronos glTF validator (tests/clients, npm package gltf-validator, installed by
# scripts/bootstrap.sh) on one asset: fails the test, with the validator's report, unless
# the asset has 0 errors and 0 warnings and declares no material extension that no
# material uses. Never skipped: without node or the package it
# fails and says what to install.
function(expect_valid_gltf file)
  find_program(NODE node)
  if(NOT NODE)
    message(FATAL_ERROR "node not found: install Node.js (Debian: nodejs npm), then run "
                        "scripts/bootstrap.sh, which installs the glTF validator")
  endif()
  set(clients "${SOURCE_DIR}/tests/clients")
  if(NOT EXISTS "${clients}/node_modules/gltf-validator/package.json")
    message(FATAL_ERROR "the Khronos glTF validator is not installed: run scripts/bootstrap.sh "
                        "(npm ci in tests/clients)")
  endif()
  execute_process(COMMAND "${NODE}" "${clients}/validate_gltf.mjs" "${file}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "glTF validator on ${file} (exit ${rc}):\n${out}${err}")
  endif()
  set(LAST_VALIDATOR_REPORT "${out}" PARENT_SCOPE)
endfunction()
