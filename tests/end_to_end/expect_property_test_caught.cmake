# Runs one property test (OBLIQUE_PROPERTY_TEST) of a wrong function and passes only when it fails
# with a report, its replay command, and a likely cause matching CAUSE (a regular expression) in
# the failure and in the report.
# cmake -DBINARY=... -DTEST=Suite.Name -DCAUSE=regex -DREPORTS=... -P expect_property_test_caught.cmake
file(REMOVE_RECURSE "${REPORTS}")
set(ENV{OBLIQUE_REPORT_DIR} "${REPORTS}")
execute_process(COMMAND "${BINARY}" --gtest_filter=${TEST}
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(result EQUAL 0)
  message(FATAL_ERROR "${TEST} passed: the property suite should have caught it:\n${output}")
endif()
if(NOT output MATCHES "likely cause[^\n]*${CAUSE}")
  message(FATAL_ERROR "${TEST} failed, but the likely cause ${CAUSE} is not named:\n${output}")
endif()
file(GLOB reports "${REPORTS}/*.md")
if(NOT reports)
  message(FATAL_ERROR "${TEST} was caught but no report was written:\n${output}")
endif()
foreach(report ${reports})
  file(READ "${report}" text)
  if(NOT text MATCHES "## Replay")
    message(FATAL_ERROR "the report ${report} has no replay command:\n${text}")
  endif()
  # A cause of several entries ("a \\+ b") is written entry by entry in the report: each named.
  string(REPLACE " \\+ " ";" entries "${CAUSE}")
  foreach(entry ${entries})
    if(NOT text MATCHES "## Likely cause\n\n.*${entry}")
      message(FATAL_ERROR "the report ${report} does not name the likely cause ${entry}:\n${text}")
    endif()
  endforeach()
endforeach()
list(LENGTH reports count)
message(STATUS "${TEST}: caught, ${count} report(s)")
