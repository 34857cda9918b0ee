# Runs COMMAND (a ;-list) with the environment ENV (a ;-list of NAME=VALUE) and passes only when it
# exits with EXIT ("nonzero" for any failure) and its output matches MATCH.
# cmake "-DCOMMAND=..." "-DENV=..." -DEXIT=... "-DMATCH=..." -P expect_run.cmake
foreach(assignment IN LISTS ENV)
  string(FIND "${assignment}" "=" eq)
  string(SUBSTRING "${assignment}" 0 ${eq} name)
  math(EXPR start "${eq} + 1")
  string(SUBSTRING "${assignment}" ${start} -1 value)
  set(ENV{${name}} "${value}")
endforeach()
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE result OUTPUT_VARIABLE output
                ERROR_VARIABLE output)
if(EXIT STREQUAL "nonzero")
  if(result EQUAL 0)
    message(FATAL_ERROR "expected a failure, got exit 0:\n${output}")
  endif()
elseif(NOT result STREQUAL EXIT)
  message(FATAL_ERROR "expected exit ${EXIT}, got ${result}:\n${output}")
endif()
if(NOT output MATCHES "${MATCH}")
  message(FATAL_ERROR "the output does not match '${MATCH}':\n${output}")
endif()
message(STATUS "exit ${result}, output matches '${MATCH}'")
