# Helpers of the command-line tests (cmake -P scripts): include(${CMAKE_CURRENT_LIST_DIR}/../cli_checks.cmake).
# They run ${RIGIDLAB}, in ${CLI_DIRECTORY} if the script sets it (else where cmake runs).

# run(STATUS ARGS...): runs `rigidlab ARGS...`, fails unless it exits with STATUS; sets `out` and
# `err` to its standard output and error.
function(run expected_status)
  if(NOT DEFINED CLI_DIRECTORY)
    set(CLI_DIRECTORY .)
  endif()
  execute_process(COMMAND ${RIGIDLAB} ${ARGN} WORKING_DIRECTORY ${CLI_DIRECTORY} RESULT_VARIABLE status
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL expected_status)
    message(FATAL_ERROR "rigidlab ${ARGN}: exit ${status}, expected ${expected_status}\nstdout: ${out}\nstderr: ${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()

function(expect_equal what actual expected)
  if(NOT "${actual}" STREQUAL "${expected}")
    message(FATAL_ERROR "${what}: got '${actual}', expected '${expected}'")
  endif()
endfunction()

# `text` must match the regular expression.
function(expect_match what text regex)
  if(NOT "${text}" MATCHES "${regex}")
    message(FATAL_ERROR "${what}: '${regex}' not found in:\n${text}")
  endif()
endfunction()
